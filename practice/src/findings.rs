//! The paper's findings about its embodiments, checked against a benchmark's recorded trials:
//! each one held, not held, or not tested (an embodiment or a task it speaks of is missing),
//! and why, in numbers.
//!
//! A task's value for an embodiment is its mean score over the counted trials when every one
//! has a score (a baseline for the task), else its mean correctness; an embodiment's overall is
//! the mean value over the tasks every compared embodiment attempted. A task is *feasible* for
//! an embodiment when at least one recorded run completed it (correctness 1).

use std::collections::{BTreeMap, BTreeSet};

use scoring::{Configuration, TaskCatalog, TrialScore};
use serde::{Deserialize, Serialize};

/// Whether a finding held.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// The trials agree with the paper.
    Held,
    /// They do not.
    NotHeld,
    /// They cannot say: an embodiment or a task it speaks of was not run.
    NotTested,
}

impl Verdict {
    /// The word in the report.
    pub fn word(self) -> &'static str {
        match self {
            Verdict::Held => "held",
            Verdict::NotHeld => "not held",
            Verdict::NotTested => "not tested",
        }
    }

    pub(crate) fn of(held: bool) -> Verdict {
        if held {
            Verdict::Held
        } else {
            Verdict::NotHeld
        }
    }
}

/// One finding.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Finding {
    /// Short name.
    pub id: String,
    /// The paper's claim, in short.
    pub claim: String,
    /// What the trials say.
    pub verdict: Verdict,
    /// Why, with the numbers.
    pub why: String,
}

/// One embodiment on one task, over its counted trials.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Cell {
    /// Counted trials.
    pub runs: usize,
    /// Trials that completed the task (correctness 1).
    pub completed: usize,
    /// Mean score, or mean correctness without a baseline.
    pub value: f64,
    /// Mean trial time of the completed trials, seconds.
    pub completed_time_s: Option<f64>,
}

impl Cell {
    /// Share of the runs that completed.
    pub fn completion(&self) -> f64 {
        self.completed as f64 / self.runs.max(1) as f64
    }
}

/// The trials as the findings read them.
#[derive(Debug, Clone, PartialEq)]
pub struct Evidence<'a> {
    cells: BTreeMap<(String, String), Cell>,
    catalog: &'a TaskCatalog,
    /// Embodiments with finger or thumb abduction.
    pub(crate) abduction: &'a BTreeSet<String>,
    /// "score" or "correctness" (without a baseline).
    pub(crate) measure: &'static str,
}

impl<'a> Evidence<'a> {
    /// The counted trials of `scores`, per embodiment and task; `abduction` names the
    /// embodiments that have abduction.
    pub fn new(
        scores: &[TrialScore],
        catalog: &'a TaskCatalog,
        abduction: &'a BTreeSet<String>,
    ) -> Evidence<'a> {
        let mut groups: BTreeMap<(String, String), Vec<&TrialScore>> = BTreeMap::new();
        for s in scores.iter().filter(|s| s.counted) {
            groups
                .entry((s.embodiment.clone(), s.task.clone()))
                .or_default()
                .push(s);
        }
        let all_scored = scores
            .iter()
            .filter(|s| s.counted)
            .all(|s| s.score.is_some());
        let cells = groups
            .into_iter()
            .map(|(key, trials)| (key, cell(&trials, all_scored)))
            .collect();
        Evidence {
            cells,
            catalog,
            abduction,
            measure: if all_scored { "score" } else { "correctness" },
        }
    }

    /// The cell of `embodiment` on `task`.
    pub fn cell(&self, embodiment: &str, task: &str) -> Option<&Cell> {
        self.cells.get(&(embodiment.to_string(), task.to_string()))
    }

    /// The embodiments that ran, in name order.
    pub fn embodiments(&self) -> BTreeSet<&str> {
        self.cells.keys().map(|(e, _)| e.as_str()).collect()
    }

    pub(crate) fn tasks_of(&self, configuration: Configuration) -> Vec<&str> {
        self.catalog
            .tasks
            .iter()
            .filter(|t| t.configuration == configuration)
            .map(|t| t.id.as_str())
            .collect()
    }

    /// Tasks every one of `embodiments` ran.
    pub(crate) fn common_tasks(&self, embodiments: &[&str]) -> Vec<&str> {
        self.catalog
            .tasks
            .iter()
            .map(|t| t.id.as_str())
            .filter(|t| embodiments.iter().all(|e| self.cell(e, t).is_some()))
            .collect()
    }

    /// Mean value of `embodiment` over `tasks`.
    pub(crate) fn mean_value(&self, embodiment: &str, tasks: &[&str]) -> Option<f64> {
        let values: Vec<f64> = tasks
            .iter()
            .filter_map(|t| self.cell(embodiment, t))
            .map(|c| c.value)
            .collect();
        (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
    }
}

fn cell(trials: &[&TrialScore], scored: bool) -> Cell {
    let n = trials.len().max(1) as f64;
    let done: Vec<&&TrialScore> = trials
        .iter()
        .filter(|s| s.correctness >= 1.0 - 1e-9)
        .collect();
    let value = trials
        .iter()
        .map(|s| {
            if scored {
                s.score.unwrap_or(0.0)
            } else {
                s.correctness
            }
        })
        .sum::<f64>()
        / n;
    Cell {
        runs: trials.len(),
        completed: done.len(),
        value,
        completed_time_s: (!done.is_empty())
            .then(|| done.iter().map(|s| s.time_s).sum::<f64>() / done.len() as f64),
    }
}

#[cfg(test)]
#[path = "findings_tests.rs"]
mod tests;
