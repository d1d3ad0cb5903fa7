//! Human baseline times: the table (a TOML file) and its computation from human trials.
//!
//! `Speed = baseline / time` needs, per task, the mean completion time of human participants
//! (the paper: 6 participants × 3 trials; its per-task times are not published). A lab records
//! human trials (embodiment `human`) and computes its own table with [`compute_baseline`]
//! (`pomdar baseline`). A task without a baseline is scored on correctness only, with a
//! warning: this crate never makes up a time.
//!
//! ```toml
//! [baseline]
//! example = false            # true: illustrative values, every report says so loudly
//! source = "pomdar baseline: 54 human trials (users a, b, c) recorded 2026-11 at ETH"
//!
//! [[task]]
//! id = "V1"
//! mean_s = 14.210            # mean completion time, seconds
//! n = 18                     # trials averaged
//! participants = 6           # distinct users among them (omitted when some have no user)
//! std_s = 2.304              # sample standard deviation (omitted when n = 1)
//! ```
//!
//! The computation also keeps which trials it averaged ([`UsedTrial`]): the study report
//! (`baseline_report.rs`) lists them per participant × task.

use std::collections::{BTreeMap, BTreeSet};

use serde::{Deserialize, Serialize};

use crate::catalog::TaskCatalog;
use crate::error::ScoringError;
use crate::rules::ScoringRules;
use crate::stats::MeanStd;
use crate::trial_log::{Ending, HUMAN_EMBODIMENT, TrialRecord};

/// The baseline file's header.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BaselineHeader {
    /// Whether the values are an example (not measured human data). Reports say so loudly.
    pub example: bool,
    /// Where the values come from (who, how many trials, when, where).
    pub source: String,
}

/// One task's baseline.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskBaseline {
    /// Task ID.
    pub id: String,
    /// Mean completion time, seconds.
    pub mean_s: f64,
    /// Number of trials averaged.
    pub n: u32,
    /// Number of distinct participants (trial users) among them; absent when unknown (an
    /// older table, or some trials without a recorded user).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub participants: Option<u32>,
    /// Sample standard deviation of the times, seconds (absent for a single trial).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub std_s: Option<f64>,
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct BaselineFile {
    baseline: BaselineHeader,
    #[serde(default)]
    task: Vec<TaskBaseline>,
}

/// A validated baseline table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BaselineTable {
    /// Where it was loaded from.
    pub origin: String,
    /// The header.
    pub header: BaselineHeader,
    /// Per-task baselines, in file order.
    pub tasks: Vec<TaskBaseline>,
}

impl BaselineTable {
    /// Parses and validates a table; `origin` names the file in errors. Every task must be
    /// in `catalog`, once; `mean_s` finite and > 0; `n` ≥ 1; `participants` (if given)
    /// 1 ..= `n`; `std_s` finite and ≥ 0.
    pub fn from_toml_str(
        text: &str,
        origin: &str,
        catalog: &TaskCatalog,
    ) -> Result<BaselineTable, ScoringError> {
        let file: BaselineFile =
            toml::from_str(text).map_err(|e| ScoringError::syntax(origin, &e))?;
        if file.baseline.source.trim().is_empty() {
            return Err(ScoringError::invalid(
                origin,
                "baseline.source",
                "\"\"",
                "a note saying where the times come from",
            ));
        }
        for i in 0..file.task.len() {
            validate_task(&file.task, i, origin, catalog)?;
        }
        Ok(BaselineTable {
            origin: origin.to_string(),
            header: file.baseline,
            tasks: file.task,
        })
    }

    /// The baseline of `task`.
    pub fn get(&self, task: &str) -> Option<&TaskBaseline> {
        self.tasks.iter().find(|t| t.id == task)
    }

    /// The table as a TOML file, with a comment saying what it is.
    pub fn to_toml(&self) -> String {
        let file = BaselineFile {
            baseline: self.header.clone(),
            task: self.tasks.clone(),
        };
        let body = toml::to_string(&file).unwrap_or_default();
        let mut text = String::from(
            "# POMDAR human baseline: mean completion time per task, seconds.\n\
             # Speed = mean_s / trial time. Load with `pomdar score --baseline FILE`.\n",
        );
        if self.header.example {
            text.push_str("# EXAMPLE: these values are illustrative, not measured human data.\n");
        }
        text.push('\n');
        text.push_str(&body);
        text
    }
}

/// Checks `tasks[i]`: in `catalog`, listed once; `mean_s` finite and > 0; `n` ≥ 1;
/// `participants` in 1 ..= `n`; `std_s` finite and ≥ 0.
fn validate_task(
    tasks: &[TaskBaseline],
    i: usize,
    origin: &str,
    catalog: &TaskCatalog,
) -> Result<(), ScoringError> {
    let t = &tasks[i];
    if catalog.get(&t.id).is_none() {
        return Err(ScoringError::invalid(
            origin,
            format!("task[{i}].id"),
            format!("{:?}", t.id),
            format!("a task of the catalog ({})", catalog.ids()),
        ));
    }
    if tasks[..i].iter().any(|o| o.id == t.id) {
        return Err(ScoringError::invalid(
            origin,
            format!("task {}", t.id),
            "listed twice",
            "one entry per task",
        ));
    }
    if !(t.mean_s.is_finite() && t.mean_s > 0.0) {
        return Err(ScoringError::invalid(
            origin,
            format!("task {}: mean_s", t.id),
            t.mean_s,
            "seconds, finite and > 0",
        ));
    }
    if t.n == 0 {
        return Err(ScoringError::invalid(
            origin,
            format!("task {}: n", t.id),
            t.n,
            "the number of trials averaged, ≥ 1",
        ));
    }
    if let Some(p) = t.participants
        && !(1..=t.n).contains(&p)
    {
        return Err(ScoringError::invalid(
            origin,
            format!("task {}: participants", t.id),
            p,
            format!(
                "the number of participants whose trials were averaged, 1 ..= n ({})",
                t.n
            ),
        ));
    }
    if let Some(s) = t.std_s
        && !(s.is_finite() && s >= 0.0)
    {
        return Err(ScoringError::invalid(
            origin,
            format!("task {}: std_s", t.id),
            s,
            "seconds, finite and ≥ 0",
        ));
    }
    Ok(())
}

/// Why a trial was not used for the baseline.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LeftOut {
    /// The trial's file.
    pub file: String,
    /// Why.
    pub reason: String,
}

/// A trial averaged into the baseline.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UsedTrial {
    /// The trial's file.
    pub source: String,
    /// Task ID.
    pub task: String,
    /// The participant (the trial's `user`), if recorded.
    pub participant: Option<String>,
    /// The trial's index in its series, if recorded.
    pub trial_index: Option<String>,
    /// Completion time, seconds, rounded to the millisecond like the table.
    pub time_s: f64,
}

/// The result of [`compute_baseline`].
#[derive(Debug, Clone, PartialEq)]
pub struct BaselineComputation {
    /// The table (tasks in catalog order; tasks without usable trials are absent).
    pub table: BaselineTable,
    /// The trials averaged, in input order.
    pub used: Vec<UsedTrial>,
    /// Trials that are not human trials: refused.
    pub refused: Vec<LeftOut>,
    /// Human trials not averaged (practice, aborted, timed out).
    pub left_out: Vec<LeftOut>,
}

/// Rounds seconds to the millisecond (the precision of an operator's mark).
pub(crate) fn ms(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

/// Where a trial goes in the baseline.
enum Verdict {
    /// Averaged into the task at this catalog position.
    Used(usize),
    /// Not a human trial.
    Refused(String),
    /// A human trial not averaged.
    LeftOut(String),
}

fn verdict(trial: &TrialRecord, catalog: &TaskCatalog, rules: &ScoringRules) -> Verdict {
    if trial.embodiment != HUMAN_EMBODIMENT {
        return Verdict::Refused(format!(
            "embodiment {:?}, not {HUMAN_EMBODIMENT:?}: a baseline is computed from human trials only",
            trial.embodiment
        ));
    }
    if trial.practice {
        return Verdict::LeftOut("practice trial".to_string());
    }
    if trial.ending == Ending::Aborted {
        return Verdict::LeftOut("aborted".to_string());
    }
    let time = trial.time_s();
    if let Some(limit) = rules.timeout_for(&trial.task)
        && time > limit
    {
        return Verdict::LeftOut(format!("timed out ({time:.3} s > {limit} s)"));
    }
    // A checked `TrialRecord`'s task is in the catalog; said rather than dropped if not.
    catalog.position(&trial.task).map_or_else(
        || Verdict::LeftOut(format!("task {:?} is not in the catalog", trial.task)),
        Verdict::Used,
    )
}

/// The number of distinct users of `trials`; `None` if some trial has no user recorded.
fn count_participants(trials: &[&TrialRecord]) -> Option<u32> {
    let users: Option<BTreeSet<&str>> = trials.iter().map(|t| t.user.as_deref()).collect();
    users.map(|u| u32::try_from(u.len()).unwrap_or(u32::MAX))
}

/// The baseline from human trials: per task, mean and sample standard deviation of the
/// times of recorded (non-practice) trials that were stopped, not aborted, within the time
/// limit of `rules`, and the number of participants (distinct users) among them. Trials of
/// another embodiment are refused by name. `source` goes in the header (`example = false`:
/// these are measured times).
pub fn compute_baseline(
    trials: &[TrialRecord],
    catalog: &TaskCatalog,
    rules: &ScoringRules,
    source: &str,
) -> BaselineComputation {
    let mut refused = Vec::new();
    let mut left_out = Vec::new();
    let mut used = Vec::new();
    let mut per_task: BTreeMap<usize, Vec<&TrialRecord>> = BTreeMap::new();
    for trial in trials {
        let leave = |reason: String| LeftOut {
            file: trial.source.clone(),
            reason,
        };
        match verdict(trial, catalog, rules) {
            Verdict::Used(position) => {
                per_task.entry(position).or_default().push(trial);
                used.push(UsedTrial {
                    source: trial.source.clone(),
                    task: trial.task.clone(),
                    participant: trial.user.clone(),
                    trial_index: trial.trial_index.clone(),
                    time_s: ms(trial.time_s()),
                });
            }
            Verdict::Refused(reason) => refused.push(leave(reason)),
            Verdict::LeftOut(reason) => left_out.push(leave(reason)),
        }
    }
    let tasks = per_task
        .into_iter()
        .filter_map(|(position, trials)| {
            let times: Vec<f64> = trials.iter().map(|t| t.time_s()).collect();
            let stats = MeanStd::of(&times)?;
            Some(TaskBaseline {
                id: catalog.tasks[position].id.clone(),
                mean_s: ms(stats.mean),
                n: u32::try_from(stats.n).unwrap_or(u32::MAX),
                participants: count_participants(&trials),
                std_s: stats.std.map(ms),
            })
        })
        .collect();
    BaselineComputation {
        table: BaselineTable {
            origin: "computed".to_string(),
            header: BaselineHeader {
                example: false,
                source: source.to_string(),
            },
            tasks,
        },
        used,
        refused,
        left_out,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "[baseline]\nexample = false\nsource = \"lab\"\n\n";

    fn load(tasks: &str) -> Result<BaselineTable, ScoringError> {
        let text = format!("{HEADER}{tasks}");
        BaselineTable::from_toml_str(&text, "lab_baseline.toml", &TaskCatalog::builtin())
    }

    #[test]
    fn a_table_without_participants_loads_and_round_trips_without_them() {
        let table = load("[[task]]\nid = \"V1\"\nmean_s = 10.0\nn = 3\nstd_s = 1.5\n").unwrap();
        assert_eq!(table.tasks[0].participants, None);
        let text = table.to_toml();
        assert!(!text.contains("participants"), "{text}");
        let back = BaselineTable::from_toml_str(&text, "again.toml", &TaskCatalog::builtin());
        assert_eq!(back.unwrap().tasks, table.tasks);
    }

    #[test]
    fn participants_round_trip_through_the_toml_file() {
        let table =
            load("[[task]]\nid = \"V1\"\nmean_s = 10.0\nn = 18\nparticipants = 6\n").unwrap();
        assert_eq!(table.tasks[0].participants, Some(6));
        let text = table.to_toml();
        assert!(text.contains("participants = 6"), "{text}");
        let back = BaselineTable::from_toml_str(&text, "again.toml", &TaskCatalog::builtin());
        assert_eq!(
            back.unwrap(),
            BaselineTable {
                origin: "again.toml".into(),
                ..table
            }
        );
    }

    #[test]
    fn participants_out_of_range_name_the_file_the_task_and_the_field() {
        let zero = load("[[task]]\nid = \"V1\"\nmean_s = 10.0\nn = 3\nparticipants = 0\n");
        assert_eq!(
            zero.unwrap_err().to_string(),
            "lab_baseline.toml: task V1: participants = 0: the number of participants whose \
             trials were averaged, 1 ..= n (3)"
        );
        let more = load("[[task]]\nid = \"G2\"\nmean_s = 10.0\nn = 3\nparticipants = 4\n");
        let more = more.unwrap_err().to_string();
        assert!(
            more.starts_with("lab_baseline.toml: task G2: participants = 4: "),
            "{more}"
        );
        let typo = load("[[task]]\nid = \"V1\"\nmean_s = 10.0\nn = 3\nparticipant = 3\n");
        assert!(typo.unwrap_err().to_string().contains("participant"));
    }
}
