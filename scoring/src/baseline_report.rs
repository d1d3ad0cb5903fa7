//! The human study behind a baseline: per participant × task, the trial times averaged; per
//! task, mean, spread (sample std, min–max), participants and trials, flagged below a
//! minimum number of trials. Rendered for a terminal (fixed width) and as Markdown.
//!
//! The POMDAR paper's study: 6 participants × 3 trials = 18 trials per task
//! ([`POMDAR_STUDY_TRIALS_PER_TASK`]). A lab with fewer trials gets a table all the same;
//! the report says which tasks rest on fewer.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use serde::Serialize;

use crate::baseline::{BaselineComputation, LeftOut, TaskBaseline, UsedTrial, ms};
use crate::catalog::TaskCatalog;
use crate::stats::MeanStd;

/// Trials per task in the POMDAR paper's study: 6 participants × 3 trials.
pub const POMDAR_STUDY_TRIALS_PER_TASK: u32 = 18;

/// How trials without a recorded user are listed.
pub const UNNAMED_PARTICIPANT: &str = "(unnamed)";

/// The study table of a baseline computation ([`baseline_study`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BaselineStudy {
    /// The table's source note.
    pub source: String,
    /// Trials per task below which a task is flagged.
    pub min_trials: u32,
    /// Every task of the catalog, in catalog order.
    pub tasks: Vec<StudyTask>,
    /// Human trials not averaged (practice, aborted, timed out).
    pub left_out: Vec<LeftOut>,
    /// Trials that are not human trials.
    pub refused: Vec<LeftOut>,
}

/// One task of the study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyTask {
    /// Task ID.
    pub id: String,
    /// Task name.
    pub name: String,
    /// The trials averaged, per participant: sorted by name, trials without a user last.
    pub participants: Vec<ParticipantTimes>,
    /// The statistics; `None` when no usable human trial of the task was found.
    pub summary: Option<StudySummary>,
}

/// One participant's averaged trials of one task.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParticipantTimes {
    /// The participant (the trials' `user`); `None` for trials without a recorded user.
    pub participant: Option<String>,
    /// The trials, in trial-index order (numeric indices first, then others, then none).
    pub trials: Vec<StudyTrial>,
}

impl ParticipantTimes {
    /// The participant's name, or [`UNNAMED_PARTICIPANT`].
    pub fn label(&self) -> &str {
        self.participant.as_deref().unwrap_or(UNNAMED_PARTICIPANT)
    }
}

/// One averaged trial.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyTrial {
    /// The trial's index in its series, if recorded.
    pub trial_index: Option<String>,
    /// Completion time, seconds (rounded to the millisecond).
    pub time_s: f64,
    /// The trial's file.
    pub source: String,
}

/// One task's statistics over its averaged trials.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudySummary {
    /// Trials averaged.
    pub trials: u32,
    /// Distinct named participants (trials without a user are not counted here).
    pub participants: u32,
    /// Trials without a recorded user.
    pub unnamed_trials: u32,
    /// Mean time, seconds (as in the table).
    pub mean_s: f64,
    /// Sample standard deviation, seconds (as in the table; `None` for a single trial).
    pub std_s: Option<f64>,
    /// Fastest trial, seconds.
    pub min_s: f64,
    /// Slowest trial, seconds.
    pub max_s: f64,
    /// Fewer trials than the study's minimum.
    pub below_minimum: bool,
}

impl StudySummary {
    /// `FEW: 6 trials < minimum 18` for a task below `min_trials`.
    pub fn flag(&self, min_trials: u32) -> Option<String> {
        self.below_minimum
            .then(|| format!("FEW: {} trials < minimum {min_trials}", self.trials))
    }

    /// `6`, or `5 + unnamed` when some trials have no user.
    fn participants_cell(&self) -> String {
        if self.unnamed_trials > 0 {
            format!("{} + unnamed", self.participants)
        } else {
            self.participants.to_string()
        }
    }
}

impl BaselineStudy {
    /// The tasks with trials, but fewer than [`BaselineStudy::min_trials`].
    pub fn below_minimum(&self) -> impl Iterator<Item = (&StudyTask, &StudySummary)> {
        self.tasks.iter().filter_map(|t| {
            t.summary
                .as_ref()
                .filter(|s| s.below_minimum)
                .map(|s| (t, s))
        })
    }
}

/// The study table of `computation`: per task of `catalog` (in its order) the averaged
/// trials per participant and their statistics, flagged below `min_trials` trials. Mean and
/// std are the table's (the values written to the TOML file).
pub fn baseline_study(
    computation: &BaselineComputation,
    catalog: &TaskCatalog,
    min_trials: u32,
) -> BaselineStudy {
    let tasks = catalog
        .tasks
        .iter()
        .map(|spec| {
            let used: Vec<&UsedTrial> = computation
                .used
                .iter()
                .filter(|u| u.task == spec.id)
                .collect();
            let participants = group_by_participant(&used);
            let summary = summarise(
                &used,
                &participants,
                computation.table.get(&spec.id),
                min_trials,
            );
            StudyTask {
                id: spec.id.clone(),
                name: spec.name.clone(),
                participants,
                summary,
            }
        })
        .collect();
    BaselineStudy {
        source: computation.table.header.source.clone(),
        min_trials,
        tasks,
        left_out: computation.left_out.clone(),
        refused: computation.refused.clone(),
    }
}

/// Orders trial indices: numbers numerically, then other text, then none.
fn index_key(index: Option<&str>) -> (u8, u64, &str) {
    match index {
        Some(text) => match text.trim().parse::<u64>() {
            Ok(n) => (0, n, ""),
            Err(_) => (1, 0, text),
        },
        None => (2, 0, ""),
    }
}

/// `used` per participant, sorted by name (unnamed last), each in trial-index order.
fn group_by_participant(used: &[&UsedTrial]) -> Vec<ParticipantTimes> {
    let mut groups: BTreeMap<(bool, &str), Vec<&UsedTrial>> = BTreeMap::new();
    for u in used {
        let key = (
            u.participant.is_none(),
            u.participant.as_deref().unwrap_or(""),
        );
        groups.entry(key).or_default().push(u);
    }
    groups
        .into_values()
        .map(|mut trials| {
            trials.sort_by(|a, b| {
                (index_key(a.trial_index.as_deref()), &a.source)
                    .cmp(&(index_key(b.trial_index.as_deref()), &b.source))
            });
            ParticipantTimes {
                participant: trials.first().and_then(|t| t.participant.clone()),
                trials: trials
                    .into_iter()
                    .map(|t| StudyTrial {
                        trial_index: t.trial_index.clone(),
                        time_s: t.time_s,
                        source: t.source.clone(),
                    })
                    .collect(),
            }
        })
        .collect()
}

/// The statistics of `used`; mean and std from the table `entry` when there is one.
fn summarise(
    used: &[&UsedTrial],
    participants: &[ParticipantTimes],
    entry: Option<&TaskBaseline>,
    min_trials: u32,
) -> Option<StudySummary> {
    let times: Vec<f64> = used.iter().map(|u| u.time_s).collect();
    let stats = MeanStd::of(&times)?;
    let (mean_s, std_s) = match entry {
        Some(b) => (b.mean_s, b.std_s),
        None => (ms(stats.mean), stats.std.map(ms)),
    };
    let count = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
    let trials = count(used.len());
    Some(StudySummary {
        trials,
        participants: count(
            participants
                .iter()
                .filter(|p| p.participant.is_some())
                .count(),
        ),
        unnamed_trials: count(used.iter().filter(|u| u.participant.is_none()).count()),
        mean_s,
        std_s,
        min_s: times.iter().copied().fold(f64::INFINITY, f64::min),
        max_s: times.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        below_minimum: trials < min_trials,
    })
}

/// `#3 12.345`: a trial's index and time.
fn trial_cell(trial: &StudyTrial) -> String {
    format!(
        "#{} {:.3}",
        trial.trial_index.as_deref().unwrap_or("?"),
        trial.time_s
    )
}

fn std_cell(std_s: Option<f64>) -> String {
    std_s.map_or("–".to_string(), |s| format!("{s:.3}"))
}

/// The study for a terminal: the per-task table, then the trial times per participant ×
/// task.
pub fn render_study_text(study: &BaselineStudy) -> String {
    let mut out = String::new();
    let w = study
        .tasks
        .iter()
        .map(|t| t.name.chars().count())
        .fold(16, usize::max);
    let _ = writeln!(
        out,
        "{:<5} {:<w$} {:>7} {:>8} {:>8} {:>8} {:>8} {:>13}",
        "task", "name", "trials", "mean s", "std s", "min s", "max s", "participants"
    );
    for task in &study.tasks {
        let Some(s) = &task.summary else {
            let _ = writeln!(
                out,
                "{:<5} {:<w$} {:>7}   (no usable human trial)",
                task.id, task.name, 0
            );
            continue;
        };
        let row = format!(
            "{:<5} {:<w$} {:>7} {:>8.3} {:>8} {:>8.3} {:>8.3} {:>13}",
            task.id,
            task.name,
            s.trials,
            s.mean_s,
            std_cell(s.std_s),
            s.min_s,
            s.max_s,
            s.participants_cell()
        );
        let _ = match s.flag(study.min_trials) {
            Some(flag) => writeln!(out, "{row}  {flag}"),
            None => writeln!(out, "{row}"),
        };
    }
    let _ = writeln!(
        out,
        "minimum {} trials per task: {} of {} tasks with trials below it",
        study.min_trials,
        study.below_minimum().count(),
        study.tasks.iter().filter(|t| t.summary.is_some()).count()
    );
    write_text_listing(&mut out, study);
    out
}

/// The trial times per participant × task, one line per participant.
fn write_text_listing(out: &mut String, study: &BaselineStudy) {
    let _ = writeln!(
        out,
        "\ntrial times per participant × task, s, in trial-index order (#index; #? not recorded):"
    );
    let w = study
        .tasks
        .iter()
        .flat_map(|t| &t.participants)
        .map(|p| p.label().chars().count())
        .fold(UNNAMED_PARTICIPANT.len(), usize::max);
    let mut any = false;
    for task in &study.tasks {
        for (i, p) in task.participants.iter().enumerate() {
            let id = if i == 0 { task.id.as_str() } else { "" };
            let times: Vec<String> = p.trials.iter().map(trial_cell).collect();
            let _ = writeln!(out, "{id:<5} {:<w$}  {}", p.label(), times.join("   "));
            any = true;
        }
    }
    if !any {
        let _ = writeln!(out, "(no trial averaged)");
    }
}

/// Escapes `|` so a value cannot break a table row.
fn md(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}

/// The study as Markdown: the source, the per-task table, the trial times per participant ×
/// task, and the trials not averaged.
pub fn render_study_markdown(study: &BaselineStudy) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# POMDAR human baseline study\n");
    let _ = writeln!(out, "Source: {}\n", md(&study.source));
    let _ = writeln!(
        out,
        "Minimum per task: {} trials (the POMDAR study: 6 participants × 3 trials = {}).\n",
        study.min_trials, POMDAR_STUDY_TRIALS_PER_TASK
    );
    for (task, s) in study.below_minimum() {
        let _ = writeln!(
            out,
            "> **WARNING:** task {}: {} trials < minimum {}\n",
            md(&task.id),
            s.trials,
            study.min_trials
        );
    }
    let _ = writeln!(out, "## Per task\n");
    let _ = writeln!(
        out,
        "| task | name | trials | participants | mean s | std s | min s | max s | flag |"
    );
    let _ = writeln!(out, "|---|---|---:|---:|---:|---:|---:|---:|---|");
    for task in &study.tasks {
        let (id, name) = (md(&task.id), md(&task.name));
        let _ = match &task.summary {
            Some(s) => writeln!(
                out,
                "| {id} | {name} | {} | {} | {:.3} | {} | {:.3} | {:.3} | {} |",
                s.trials,
                s.participants_cell(),
                s.mean_s,
                std_cell(s.std_s),
                s.min_s,
                s.max_s,
                s.flag(study.min_trials)
                    .map_or(String::new(), |f| format!("**{f}**"))
            ),
            None => writeln!(
                out,
                "| {id} | {name} | 0 | 0 | – | – | – | – | no usable human trial |"
            ),
        };
    }
    write_markdown_listing(&mut out, study);
    write_markdown_not_averaged(&mut out, study);
    out
}

fn write_markdown_listing(out: &mut String, study: &BaselineStudy) {
    let _ = writeln!(out, "\n## Trial times per participant × task\n");
    let _ = writeln!(
        out,
        "Seconds, in trial-index order (`#index`; `#?`: not recorded).\n"
    );
    let _ = writeln!(out, "| task | participant | trials | times s |");
    let _ = writeln!(out, "|---|---|---:|---|");
    for task in &study.tasks {
        for p in &task.participants {
            let times: Vec<String> = p.trials.iter().map(trial_cell).collect();
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} |",
                md(&task.id),
                md(p.label()),
                p.trials.len(),
                md(&times.join(", "))
            );
        }
    }
}

fn write_markdown_not_averaged(out: &mut String, study: &BaselineStudy) {
    if study.left_out.is_empty() && study.refused.is_empty() {
        return;
    }
    let _ = writeln!(out, "\n## Trials not averaged\n");
    let _ = writeln!(out, "| file | reason |\n|---|---|");
    for l in &study.left_out {
        let _ = writeln!(out, "| {} | {} |", md(&l.file), md(&l.reason));
    }
    for r in &study.refused {
        let _ = writeln!(out, "| {} | refused: {} |", md(&r.file), md(&r.reason));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::baseline::compute_baseline;
    use crate::rules::ScoringRules;
    use crate::trial_log::{Ending, HUMAN_EMBODIMENT, TrialRecord};

    const T0_NS: i64 = 1_000_000_000;

    fn human(
        file: &str,
        task: &str,
        user: Option<&str>,
        index: Option<&str>,
        time_s: f64,
    ) -> TrialRecord {
        TrialRecord {
            source: file.into(),
            task: task.into(),
            embodiment: HUMAN_EMBODIMENT.into(),
            practice: false,
            user: user.map(Into::into),
            operator: None,
            trial_index: index.map(Into::into),
            start_ns: T0_NS,
            end_ns: T0_NS + (time_s * 1e9).round() as i64,
            ending: Ending::Stopped,
            marks: Vec::new(),
            notes: Vec::new(),
        }
    }

    fn study(trials: &[TrialRecord], min_trials: u32) -> BaselineStudy {
        let catalog = TaskCatalog::builtin();
        let computation = compute_baseline(trials, &catalog, &ScoringRules::default(), "test");
        baseline_study(&computation, &catalog, min_trials)
    }

    fn task<'a>(study: &'a BaselineStudy, id: &str) -> &'a StudyTask {
        study.tasks.iter().find(|t| t.id == id).unwrap()
    }

    /// V1: ann #10, #1, #2 and bob #2, #1 out of order, one trial without a user; C1: ann and
    /// bob, all named.
    fn mixed_trials() -> Vec<TrialRecord> {
        vec![
            human("bob_2.mcap", "V1", Some("bob"), Some("2"), 12.0),
            human("ann_10.mcap", "V1", Some("ann"), Some("10"), 9.0),
            human("anon.mcap", "V1", None, Some("1"), 11.0),
            human("ann_1.mcap", "V1", Some("ann"), Some("1"), 10.0),
            human("c1_bob.mcap", "C1", Some("bob"), None, 20.0),
            human("ann_2.mcap", "V1", Some("ann"), Some("2"), 11.5),
            human("bob_1.mcap", "V1", Some("bob"), Some("1"), 14.0),
            human("c1_ann.mcap", "C1", Some("ann"), Some("1"), 22.0),
        ]
    }

    /// A participant's label and trials as (index, seconds).
    type Grouped<'a> = (&'a str, Vec<(Option<&'a str>, f64)>);

    #[test]
    fn trials_are_grouped_per_participant_in_trial_index_order() {
        let study = study(&mixed_trials(), 3);
        let v1 = task(&study, "V1");
        let grouped: Vec<Grouped> = v1
            .participants
            .iter()
            .map(|p| {
                let trials = p.trials.iter();
                (
                    p.label(),
                    trials
                        .map(|t| (t.trial_index.as_deref(), t.time_s))
                        .collect(),
                )
            })
            .collect();
        assert_eq!(
            grouped,
            [
                (
                    "ann",
                    vec![(Some("1"), 10.0), (Some("2"), 11.5), (Some("10"), 9.0)]
                ),
                ("bob", vec![(Some("1"), 14.0), (Some("2"), 12.0)]),
                (UNNAMED_PARTICIPANT, vec![(Some("1"), 11.0)]),
            ]
        );
        assert_eq!(v1.participants[2].participant, None);
        let s = v1.summary.as_ref().unwrap();
        assert_eq!((s.trials, s.participants, s.unnamed_trials), (6, 2, 1));
        let c1 = task(&study, "C1");
        let s = c1.summary.as_ref().unwrap();
        assert_eq!((s.trials, s.participants, s.unnamed_trials), (2, 2, 0));
        assert_eq!(c1.participants[0].trials[0].source, "c1_ann.mcap");
        // Tasks without trials are listed, in catalog order, without statistics.
        let ids: Vec<&str> = study.tasks.iter().map(|t| t.id.as_str()).collect();
        assert_eq!(
            ids,
            TaskCatalog::builtin().ids().split(", ").collect::<Vec<_>>()
        );
        assert!(task(&study, "H2").summary.is_none() && task(&study, "H2").participants.is_empty());
    }

    #[test]
    fn the_table_counts_participants_only_when_every_trial_names_one() {
        let catalog = TaskCatalog::builtin();
        let computation =
            compute_baseline(&mixed_trials(), &catalog, &ScoringRules::default(), "test");
        assert_eq!(computation.table.get("V1").unwrap().participants, None);
        assert_eq!(computation.table.get("C1").unwrap().participants, Some(2));
        assert_eq!(computation.used.len(), 8);
        assert_eq!(computation.used[0].participant.as_deref(), Some("bob"));
    }

    #[test]
    fn mean_std_min_and_max_match_hand_computed_values() {
        // 10, 16, 12, 14: mean 13, sample std √((9 + 9 + 1 + 1) / 3) = √(20/3) = 2.58199.
        let trials = [
            human("a.mcap", "G3", Some("ann"), Some("1"), 10.0),
            human("b.mcap", "G3", Some("ann"), Some("2"), 16.0),
            human("c.mcap", "G3", Some("bob"), Some("1"), 12.0),
            human("d.mcap", "G3", Some("bob"), Some("2"), 14.0),
            human("e.mcap", "V2", Some("cat"), Some("1"), 7.25),
        ];
        let study = study(&trials, 4);
        let s = task(&study, "G3").summary.clone().unwrap();
        assert_eq!((s.mean_s, s.std_s), (13.0, Some(2.582)));
        assert_eq!((s.min_s, s.max_s), (10.0, 16.0));
        let single = task(&study, "V2").summary.clone().unwrap();
        assert_eq!((single.mean_s, single.std_s), (7.25, None));
        assert_eq!((single.min_s, single.max_s), (7.25, 7.25));
    }

    #[test]
    fn tasks_below_the_minimum_are_flagged_and_tasks_at_it_are_not() {
        let trials: Vec<TrialRecord> = (1..=4)
            .map(|i| {
                human(
                    &format!("{i}.mcap"),
                    "V1",
                    Some("ann"),
                    Some(&i.to_string()),
                    10.0,
                )
            })
            .collect();
        let at = study(&trials, 4);
        let s = task(&at, "V1").summary.clone().unwrap();
        assert!(!s.below_minimum);
        assert_eq!(s.flag(4), None);
        assert_eq!(at.below_minimum().count(), 0);
        let above = study(&trials, 5);
        let s = task(&above, "V1").summary.clone().unwrap();
        assert!(s.below_minimum);
        assert_eq!(s.flag(5).as_deref(), Some("FEW: 4 trials < minimum 5"));
        let flagged: Vec<&str> = above.below_minimum().map(|(t, _)| t.id.as_str()).collect();
        assert_eq!(flagged, ["V1"], "tasks without trials are missing, not few");
    }

    #[test]
    fn the_text_lists_the_table_then_the_times_per_participant() {
        let text = render_study_text(&study(&mixed_trials(), 18));
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(
            lines[0],
            "task  name              trials   mean s    std s    min s    max s  participants"
        );
        let v1 = lines.iter().find(|l| l.starts_with("V1 ")).unwrap();
        assert_eq!(
            *v1,
            "V1    Wheel                  6   11.250    1.725    9.000   14.000   2 + unnamed  \
             FEW: 6 trials < minimum 18"
        );
        assert!(text.contains("H2    Chopsticks             0   (no usable human trial)"));
        assert!(text.contains("minimum 18 trials per task: 2 of 2 tasks with trials below it"));
        assert!(
            text.contains("\nV1    ann        #1 10.000   #2 11.500   #10 9.000\n"),
            "{text}"
        );
        assert!(
            text.contains("\n      bob        #1 14.000   #2 12.000\n"),
            "{text}"
        );
        assert!(text.contains("\n      (unnamed)  #1 11.000\n"), "{text}");
        assert!(text.contains("\nC1    ann        #1 22.000\n      bob        #? 20.000\n"));
    }

    #[test]
    fn the_markdown_has_the_table_the_times_and_the_warnings() {
        let mut trials = mixed_trials();
        trials[0].user = Some("b|ob".into());
        let mut practice = human("p.mcap", "V1", Some("ann"), None, 30.0);
        practice.practice = true;
        trials.push(practice);
        let text = render_study_markdown(&study(&trials, 2));
        assert!(!text.contains("> **WARNING:**"), "{text}");
        assert!(
            text.contains("| V1 | Wheel | 6 | 3 + unnamed | 11.250 | 1.725 | 9.000 | 14.000 |  |"),
            "{text}"
        );
        assert!(
            text.contains("| H2 | Chopsticks | 0 | 0 | – | – | – | – | no usable human trial |")
        );
        assert!(text.contains("| V1 | b\\|ob | 1 | #2 12.000 |"), "{text}");
        assert!(text.contains("| p.mcap | practice trial |"), "{text}");
        let few = render_study_markdown(&study(&mixed_trials(), 7));
        assert!(
            few.contains("> **WARNING:** task V1: 6 trials < minimum 7"),
            "{few}"
        );
        assert!(few.contains("| **FEW: 6 trials < minimum 7** |"), "{few}");
    }
}
