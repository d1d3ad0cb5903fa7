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
#[path = "baseline_report_tests.rs"]
mod tests;
