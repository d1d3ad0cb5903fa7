//! Aggregation: per task × embodiment, then per embodiment overall.
//!
//! ```text
//! per (task, embodiment), over counted trials (recorded, not excluded):
//!     score       = mean ± sample std of trial scores          (none without a baseline)
//!     correctness = mean ± sample std of trial correctness
//! per embodiment, with s_t the mean score of task t and A the attempted tasks (≥ 1 counted
//! trial), N the catalog's task count (18):
//!     overall (attempted)         = Σ_{t∈A} s_t / |A|
//!     overall (all N, missing = 0) = Σ_{t∈A} s_t / N
//!     spread                      = sample std of s_t over A
//! ```
//!
//! The paper does not say how it aggregated the reduced hands (H2–H4 were not run with them),
//! so both overalls are reported. If an attempted task has no baseline, the embodiment's
//! overall scores are not computed (they would mix scores with correctness); the overall
//! correctness (same two means over correctness) always is.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::catalog::TaskCatalog;
use crate::stats::MeanStd;
use crate::trial_score::{Outcome, TrialScore};

/// One task × embodiment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TaskResult {
    /// Task ID.
    pub task: String,
    /// Embodiment.
    pub embodiment: String,
    /// Trials in the means.
    pub counted: usize,
    /// Practice trials (not in the means).
    pub practice: usize,
    /// Recorded trials left out by the rule for unfinished trials.
    pub excluded: usize,
    /// Recorded trials that were aborted.
    pub aborted: usize,
    /// Recorded trials that timed out.
    pub timed_out: usize,
    /// Score over counted trials; `None` without a baseline or without counted trials.
    pub score: Option<MeanStd>,
    /// Correctness over counted trials.
    pub correctness: Option<MeanStd>,
    /// Trial time over counted trials, seconds.
    pub time_s: Option<MeanStd>,
    /// Whether the task has a baseline (scores) or shows correctness only.
    pub has_baseline: bool,
}

/// One embodiment's overall results.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EmbodimentResult {
    /// Embodiment.
    pub embodiment: String,
    /// Degrees of freedom, if the embodiment is known.
    pub dof: Option<u32>,
    /// Tasks with at least one counted trial.
    pub tasks_attempted: usize,
    /// Tasks in the catalog.
    pub tasks_total: usize,
    /// Counted trials.
    pub trials: usize,
    /// Mean of the task scores over attempted tasks.
    pub overall_attempted: Option<f64>,
    /// Mean of the task scores over all catalog tasks, missing = 0.
    pub overall_all: Option<f64>,
    /// Sample std of the task scores over attempted tasks (spread across tasks).
    pub overall_spread: Option<f64>,
    /// Mean correctness over attempted tasks.
    pub correctness_attempted: Option<f64>,
    /// Mean correctness over all catalog tasks, missing = 0.
    pub correctness_all: Option<f64>,
    /// Attempted tasks without a baseline (why the overall scores are absent).
    pub tasks_without_baseline: Vec<String>,
}

/// Per task × embodiment and per embodiment results.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Aggregate {
    /// Every task × embodiment with at least one trial, embodiments in report order, tasks in
    /// catalog order.
    pub tasks: Vec<TaskResult>,
    /// Every embodiment with at least one trial: by DoF ascending, then unknown DoF by name.
    pub embodiments: Vec<EmbodimentResult>,
}

/// The two overall means of per-task values over attempted tasks: `(mean over attempted,
/// mean over all total tasks with missing = 0)`; `None` if no task was attempted.
pub fn overall_means(task_values: &[f64], total_tasks: usize) -> Option<(f64, f64)> {
    if task_values.is_empty() || total_tasks == 0 {
        return None;
    }
    let sum: f64 = task_values.iter().sum();
    Some((sum / task_values.len() as f64, sum / total_tasks as f64))
}

/// Aggregates scored trials. `dof` maps embodiment names to their degrees of freedom.
pub fn aggregate(
    scores: &[TrialScore],
    catalog: &TaskCatalog,
    dof: &BTreeMap<String, u32>,
) -> Aggregate {
    let mut names: Vec<&str> = scores.iter().map(|s| s.embodiment.as_str()).collect();
    names.sort_unstable();
    names.dedup();
    names.sort_by_key(|n| (dof.get(*n).map_or(u32::MAX, |d| *d), n.to_string()));

    let mut tasks = Vec::new();
    let mut embodiments = Vec::new();
    for name in names {
        let mut task_scores = Vec::new();
        let mut task_correctness = Vec::new();
        let mut without_baseline = Vec::new();
        let mut trials = 0;
        for spec in &catalog.tasks {
            let of_task: Vec<&TrialScore> = scores
                .iter()
                .filter(|s| s.embodiment == name && s.task == spec.id)
                .collect();
            if of_task.is_empty() {
                continue;
            }
            let counted: Vec<&TrialScore> = of_task.iter().copied().filter(|s| s.counted).collect();
            let recorded = of_task.iter().filter(|s| !s.practice);
            let has_baseline = of_task.iter().all(|s| s.score.is_some());
            let values = |f: &dyn Fn(&TrialScore) -> Option<f64>| {
                counted.iter().filter_map(|s| f(s)).collect::<Vec<f64>>()
            };
            let score = if has_baseline {
                MeanStd::of(&values(&|s| s.score))
            } else {
                None
            };
            let correctness = MeanStd::of(&values(&|s| Some(s.correctness)));
            if let Some(c) = correctness {
                task_correctness.push(c.mean);
                if !has_baseline {
                    without_baseline.push(spec.id.clone());
                }
            }
            if let Some(s) = score {
                task_scores.push(s.mean);
            }
            trials += counted.len();
            tasks.push(TaskResult {
                task: spec.id.clone(),
                embodiment: name.to_string(),
                counted: counted.len(),
                practice: of_task.iter().filter(|s| s.practice).count(),
                excluded: recorded.clone().filter(|s| !s.counted).count(),
                aborted: recorded
                    .clone()
                    .filter(|s| s.outcome == Outcome::Aborted)
                    .count(),
                timed_out: recorded.filter(|s| s.outcome == Outcome::TimedOut).count(),
                score,
                correctness,
                time_s: MeanStd::of(&values(&|s| Some(s.time_s))),
                has_baseline,
            });
        }
        let total = catalog.len();
        let scored = if without_baseline.is_empty() {
            overall_means(&task_scores, total)
        } else {
            None
        };
        let correct = overall_means(&task_correctness, total);
        embodiments.push(EmbodimentResult {
            embodiment: name.to_string(),
            dof: dof.get(name).copied(),
            tasks_attempted: task_correctness.len(),
            tasks_total: total,
            trials,
            overall_attempted: scored.map(|s| s.0),
            overall_all: scored.map(|s| s.1),
            overall_spread: scored
                .and_then(|_| MeanStd::of(&task_scores))
                .and_then(|s| s.std),
            correctness_attempted: correct.map(|c| c.0),
            correctness_all: correct.map(|c| c.1),
            tasks_without_baseline: without_baseline,
        });
    }
    Aggregate { tasks, embodiments }
}
