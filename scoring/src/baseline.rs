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
//! std_s = 2.304              # sample standard deviation (omitted when n = 1)
//! ```

use std::collections::BTreeMap;

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
    /// in `catalog`, once; `mean_s` finite and > 0; `n` ≥ 1; `std_s` finite and ≥ 0.
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
        for (i, t) in file.task.iter().enumerate() {
            if catalog.get(&t.id).is_none() {
                return Err(ScoringError::invalid(
                    origin,
                    format!("task[{i}].id"),
                    format!("{:?}", t.id),
                    format!("a task of the catalog ({})", catalog.ids()),
                ));
            }
            if file.task[..i].iter().any(|o| o.id == t.id) {
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

/// Why a trial was not used for the baseline.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LeftOut {
    /// The trial's file.
    pub file: String,
    /// Why.
    pub reason: String,
}

/// The result of [`compute_baseline`].
#[derive(Debug, Clone, PartialEq)]
pub struct BaselineComputation {
    /// The table (tasks in catalog order; tasks without usable trials are absent).
    pub table: BaselineTable,
    /// Trials that are not human trials: refused.
    pub refused: Vec<LeftOut>,
    /// Human trials not averaged (practice, aborted, timed out).
    pub left_out: Vec<LeftOut>,
}

/// Rounds seconds to the millisecond (the precision of an operator's mark).
fn ms(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

/// The baseline from human trials: per task, mean and sample standard deviation of the
/// times of recorded (non-practice) trials that were stopped, not aborted, within the time
/// limit of `rules`. Trials of another embodiment are refused by name. `source` goes in the
/// header (`example = false`: these are measured times).
pub fn compute_baseline(
    trials: &[TrialRecord],
    catalog: &TaskCatalog,
    rules: &ScoringRules,
    source: &str,
) -> BaselineComputation {
    let mut refused = Vec::new();
    let mut left_out = Vec::new();
    let mut times: BTreeMap<usize, Vec<f64>> = BTreeMap::new();
    for trial in trials {
        let leave = |reason: String| LeftOut {
            file: trial.source.clone(),
            reason,
        };
        if trial.embodiment != HUMAN_EMBODIMENT {
            refused.push(leave(format!(
                "embodiment {:?}, not {HUMAN_EMBODIMENT:?}: a baseline is computed from human trials only",
                trial.embodiment
            )));
            continue;
        }
        if trial.practice {
            left_out.push(leave("practice trial".to_string()));
            continue;
        }
        if trial.ending == Ending::Aborted {
            left_out.push(leave("aborted".to_string()));
            continue;
        }
        let time = trial.time_s();
        if let Some(limit) = rules.timeout_for(&trial.task)
            && time > limit
        {
            left_out.push(leave(format!("timed out ({time:.3} s > {limit} s)")));
            continue;
        }
        if let Some(position) = catalog.position(&trial.task) {
            times.entry(position).or_default().push(time);
        }
    }
    let tasks = times
        .into_iter()
        .filter_map(|(position, times)| {
            let stats = MeanStd::of(&times)?;
            Some(TaskBaseline {
                id: catalog.tasks[position].id.clone(),
                mean_s: ms(stats.mean),
                n: u32::try_from(stats.n).unwrap_or(u32::MAX),
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
        refused,
        left_out,
    }
}
