//! The score report: everything the renderers (terminal, Markdown, CSV, JSON, figures) show,
//! with its warnings, assembled once.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::aggregate::{Aggregate, EmbodimentResult, TaskResult, aggregate};
use crate::baseline::BaselineTable;
use crate::catalog::TaskCatalog;
use crate::rules::ScoringRules;
use crate::trial_score::TrialScore;

/// A file that was not scored, and why.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct FileProblem {
    /// The file.
    pub file: String,
    /// Why.
    pub reason: String,
}

/// A catalog task as the report shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TaskInfo {
    /// Task ID.
    pub id: String,
    /// Name.
    pub name: String,
    /// How correctness is computed.
    pub correctness: String,
    /// Grasping task (6-task radar) or manipulation task (12-task radar).
    pub grasp: bool,
    /// Baseline mean time, seconds, if the baseline has the task.
    pub baseline_s: Option<f64>,
}

/// The baseline used, as the report shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BaselineInfo {
    /// The file.
    pub origin: String,
    /// Whether it says it is an example.
    pub example: bool,
    /// Its source note.
    pub source: String,
    /// Tasks it covers.
    pub tasks: Vec<String>,
}

/// The rules used.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RulesInfo {
    /// The file, or `default rules`.
    pub origin: String,
    /// One line.
    pub description: String,
    /// The rules.
    pub rules: ScoringRules,
}

/// What a report is built from.
#[derive(Debug, Clone)]
pub struct ReportInputs<'a> {
    /// The task catalog.
    pub catalog: &'a TaskCatalog,
    /// The baseline table, if any.
    pub baseline: Option<&'a BaselineTable>,
    /// The rules.
    pub rules: &'a ScoringRules,
    /// Where the rules came from.
    pub rules_origin: &'a str,
    /// Degrees of freedom per embodiment name.
    pub dof: &'a BTreeMap<String, u32>,
    /// The scored trials.
    pub scores: Vec<TrialScore>,
    /// Files that could not be scored.
    pub rejected: Vec<FileProblem>,
    /// Files skipped on purpose (unfinished `.part` recordings).
    pub skipped: Vec<FileProblem>,
}

/// The complete report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScoreReport {
    /// Warnings every format shows prominently (missing or example baseline, rejected files).
    pub warnings: Vec<String>,
    /// Informational remarks (practice trials left out, unknown DoF, skipped files).
    pub notes: Vec<String>,
    /// The catalog's origin and name.
    pub catalog: String,
    /// The catalog's tasks.
    pub catalog_tasks: Vec<TaskInfo>,
    /// The rules.
    pub rules: RulesInfo,
    /// The baseline, if any.
    pub baseline: Option<BaselineInfo>,
    /// Per embodiment.
    pub embodiments: Vec<EmbodimentResult>,
    /// Per task × embodiment.
    pub tasks: Vec<TaskResult>,
    /// Per trial, in input order.
    pub trials: Vec<TrialScore>,
    /// Files not scored.
    pub rejected: Vec<FileProblem>,
    /// Files skipped.
    pub skipped: Vec<FileProblem>,
    /// Figure files written beside the report (set by the caller).
    pub figures: Vec<String>,
}

impl ScoreReport {
    /// Aggregates the scores and collects the warnings.
    pub fn build(inputs: ReportInputs<'_>) -> ScoreReport {
        let ReportInputs {
            catalog,
            baseline,
            rules,
            rules_origin,
            dof,
            scores,
            rejected,
            skipped,
        } = inputs;
        let aggregated = aggregate(&scores, catalog, dof);
        let mut warnings = baseline_warnings(baseline, catalog, &aggregated);
        warnings.extend(input_warnings(rules, &rejected));
        let notes = notes(&scores, &aggregated.embodiments, &skipped);
        let Aggregate { tasks, embodiments } = aggregated;
        ScoreReport {
            warnings,
            notes,
            catalog: format!("{}; {}", catalog.header.name, catalog.origin),
            catalog_tasks: task_infos(catalog, baseline),
            rules: RulesInfo {
                origin: rules_origin.to_string(),
                description: rules.describe(),
                rules: rules.clone(),
            },
            baseline: baseline.map(|b| BaselineInfo {
                origin: b.origin.clone(),
                example: b.header.example,
                source: b.header.source.clone(),
                tasks: b.tasks.iter().map(|t| t.id.clone()).collect(),
            }),
            embodiments,
            tasks,
            trials: scores,
            rejected,
            skipped,
            figures: Vec::new(),
        }
    }

    /// The task × embodiment result, if any trial exists for it.
    pub fn task_result(&self, task: &str, embodiment: &str) -> Option<&TaskResult> {
        self.tasks
            .iter()
            .find(|t| t.task == task && t.embodiment == embodiment)
    }

    /// The catalog's name of task `id`.
    pub fn task_name(&self, id: &str) -> &str {
        self.catalog_tasks
            .iter()
            .find(|t| t.id == id)
            .map_or("", |t| t.name.as_str())
    }

    /// The report as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Counted (non-practice, not excluded) trials.
    pub fn counted_trials(&self) -> usize {
        self.trials.iter().filter(|t| t.counted).count()
    }
}

/// `0.72` or `–`.
pub(crate) fn opt(value: Option<f64>, decimals: usize) -> String {
    value.map_or("–".to_string(), |v| format!("{v:.decimals$}"))
}

/// Warnings about the baseline: none given, an example one, or tasks attempted that it lacks.
fn baseline_warnings(
    baseline: Option<&BaselineTable>,
    catalog: &TaskCatalog,
    aggregated: &Aggregate,
) -> Vec<String> {
    let mut warnings = Vec::new();
    match baseline {
        None => warnings.push(
            "NO BASELINE: no baseline table was given, so there are no scores: every task \
             shows correctness only (record human trials, compute a table with `pomdar \
             baseline`, pass it with --baseline)."
                .to_string(),
        ),
        Some(b) if b.header.example => warnings.push(format!(
            "EXAMPLE BASELINE: {} says example = true: its times are illustrative, not \
             measured human data, so these scores are not real POMDAR scores.",
            b.origin
        )),
        Some(_) => {}
    }
    if let Some(b) = baseline {
        let mut missing: Vec<&str> = Vec::new();
        for spec in &catalog.tasks {
            let attempted = aggregated.tasks.iter().any(|t| t.task == spec.id);
            if attempted && b.get(&spec.id).is_none() {
                missing.push(&spec.id);
            }
        }
        if !missing.is_empty() {
            let affected: Vec<&str> = aggregated
                .embodiments
                .iter()
                .filter(|e| !e.tasks_without_baseline.is_empty())
                .map(|e| e.embodiment.as_str())
                .collect();
            warnings.push(format!(
                "NO BASELINE for {} in {}: these tasks show correctness only (marked *), \
                 and the overall score of {} is not computed.",
                missing.join(", "),
                b.origin,
                affected.join(", ")
            ));
        }
    }
    warnings
}

/// Warnings about the inputs: files rejected, weights other than the paper's.
fn input_warnings(rules: &ScoringRules, rejected: &[FileProblem]) -> Vec<String> {
    let mut warnings = Vec::new();
    if !rejected.is_empty() {
        warnings.push(format!(
            "{} file(s) could not be scored (listed with the reason under \"Rejected files\").",
            rejected.len()
        ));
    }
    if !rules.has_paper_weights() {
        warnings.push(format!(
            "Weights differ from the paper's (0.8 / 0.2): {} / {}.",
            rules.correctness_weight, rules.speed_weight
        ));
    }
    warnings
}

/// Informational notes: practice and excluded trials, unknown DoF, skipped files.
fn notes(
    scores: &[TrialScore],
    embodiments: &[EmbodimentResult],
    skipped: &[FileProblem],
) -> Vec<String> {
    let mut notes = Vec::new();
    let practice = scores.iter().filter(|s| s.practice).count();
    if practice > 0 {
        notes.push(format!(
            "{practice} practice trial(s) scored but left out of every mean."
        ));
    }
    let excluded = scores.iter().filter(|s| !s.practice && !s.counted).count();
    if excluded > 0 {
        notes.push(format!(
            "{excluded} aborted or timed-out trial(s) left out of the means (rule: exclude)."
        ));
    }
    for e in embodiments {
        if e.dof.is_none() {
            notes.push(format!(
                "embodiment {}: DoF unknown (not in the embodiment catalog), so not in the \
                 overall-vs-DoF figure.",
                e.embodiment
            ));
        }
    }
    if !skipped.is_empty() {
        notes.push(format!(
            "{} file(s) skipped (listed under \"Skipped files\").",
            skipped.len()
        ));
    }
    notes
}

/// The catalog's tasks with their baseline times.
fn task_infos(catalog: &TaskCatalog, baseline: Option<&BaselineTable>) -> Vec<TaskInfo> {
    catalog
        .tasks
        .iter()
        .map(|t| TaskInfo {
            id: t.id.clone(),
            name: t.name.clone(),
            correctness: t.correctness.describe(),
            grasp: t.configuration.is_grasp(),
            baseline_s: baseline.and_then(|b| b.get(&t.id)).map(|b| b.mean_s),
        })
        .collect()
}
