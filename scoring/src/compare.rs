//! The source ablation: trials grouped by a metadata entry, side by side per task and
//! embodiment (`pomdar score … --compare FIELD`).
//!
//! The groups are the distinct values of the `pomdar_trial` record's entry `field`
//! (`keypoint_source`: `rokoko`, `avp`, …; or `user`, `station_version`, any entry); trials
//! without it, or with it blank, form the group [`MISSING_GROUP`]. The comparison is built from
//! a [`ScoreReport`], so its trials, scores and rows are exactly the report's: only counted
//! trials (recorded, not practice, not excluded by the rule for unfinished trials) enter.
//!
//! ```text
//! per task t × embodiment e × group g, over its counted trials:
//!     n, correctness, time (s), score (only with a baseline for t): mean ± sample std
//! per group g ≠ the reference r, where both have trials:
//!     d = mean_g − mean_r with Welch's 95 % interval (see `welch`)
//! ```
//!
//! The reference is the first group in sorted order (the missing group sorts last and is the
//! reference only when asked for), or the one asked for.

use serde::Serialize;

use crate::error::ScoringError;
use crate::report::ScoreReport;
use crate::stats::MeanStd;
use crate::trial_score::TrialScore;
use crate::welch::{CONFIDENCE_LEVEL, Difference, welch_difference};

/// The group of trials whose metadata has no entry (or a blank one) for the field.
pub const MISSING_GROUP: &str = "(missing)";

/// One group of trials: a value of the field.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct CompareGroup {
    /// The field's value, or [`MISSING_GROUP`].
    pub name: String,
    /// Whether this is the group of trials without the entry.
    pub missing: bool,
    /// Whether the others are compared against this one.
    pub reference: bool,
    /// Counted trials in the group (all tasks and embodiments).
    pub trials: usize,
}

impl CompareGroup {
    /// `avp (12 trials, reference)`, `(missing) (1 trial)`: the group as legends and headings
    /// name it.
    pub fn describe(&self) -> String {
        let trials = if self.trials == 1 {
            "1 trial".to_string()
        } else {
            format!("{} trials", self.trials)
        };
        let role = if self.reference { ", reference" } else { "" };
        format!("{} ({trials}{role})", self.name)
    }
}

/// A group's differences from the reference group in one task × embodiment.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct VersusReference {
    /// Correctness difference.
    pub correctness: Difference,
    /// Trial time difference, seconds (positive: slower than the reference).
    pub time_s: Difference,
    /// Score difference; `None` without a baseline for the task.
    pub score: Option<Difference>,
}

/// One group in one task × embodiment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GroupResult {
    /// The group's name.
    pub group: String,
    /// Counted trials.
    pub n: usize,
    /// Correctness over them.
    pub correctness: Option<MeanStd>,
    /// Trial time over them, seconds.
    pub time_s: Option<MeanStd>,
    /// Score over them; `None` without a baseline for the task (never an invented time).
    pub score: Option<MeanStd>,
    /// Against the reference group; `None` for the reference itself or when either group has
    /// no trial here.
    pub versus_reference: Option<VersusReference>,
}

/// One task × embodiment: every group, in the comparison's group order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CompareRow {
    /// Task ID.
    pub task: String,
    /// The catalog's name of the task.
    pub task_name: String,
    /// Embodiment.
    pub embodiment: String,
    /// Whether the task has a baseline (scores) or shows correctness and time only.
    pub has_baseline: bool,
    /// One entry per group (n = 0 where the group has no trial here).
    pub groups: Vec<GroupResult>,
}

impl CompareRow {
    /// The group named `name`, if it is in the comparison.
    pub fn group(&self, name: &str) -> Option<&GroupResult> {
        self.groups.iter().find(|g| g.group == name)
    }
}

/// Trials grouped by a metadata field, per task × embodiment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    /// The metadata field the trials are grouped by.
    pub field: String,
    /// The reference group's name.
    pub reference: String,
    /// The confidence level of the intervals.
    pub confidence_level: f64,
    /// The groups: values in sorted order, [`MISSING_GROUP`] last.
    pub groups: Vec<CompareGroup>,
    /// Counted trials without the entry (in [`MISSING_GROUP`]).
    pub missing_trials: usize,
    /// Per task × embodiment with counted trials, in the report's order.
    pub rows: Vec<CompareRow>,
    /// Whether the baseline says it is an example (its scores are not real POMDAR scores).
    pub example_baseline: bool,
    /// The report's warnings (baseline, rejected files).
    pub warnings: Vec<String>,
    /// Remarks: trials left out, the missing group, undefined intervals.
    pub notes: Vec<String>,
    /// Figure files written beside the comparison (set by the caller).
    pub figures: Vec<String>,
}

impl Comparison {
    /// The row of `task` × `embodiment`, if it has counted trials.
    pub fn row(&self, task: &str, embodiment: &str) -> Option<&CompareRow> {
        self.rows
            .iter()
            .find(|r| r.task == task && r.embodiment == embodiment)
    }

    /// The comparison as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }
}

/// The group of `trial` for `field`: the entry's value (trimmed), or [`MISSING_GROUP`].
pub fn group_of<'a>(trial: &'a TrialScore, field: &str) -> &'a str {
    trial
        .metadata
        .get(field)
        .map(|v| v.trim())
        .filter(|v| !v.is_empty())
        .unwrap_or(MISSING_GROUP)
}

/// Groups the report's counted trials by `field` and compares them per task × embodiment
/// against `reference` (default: the first group in sorted order, the missing group last).
/// An error when fewer than two groups have counted trials or `reference` is not a group.
pub fn compare_by(
    report: &ScoreReport,
    field: &str,
    reference: Option<&str>,
) -> Result<Comparison, ScoringError> {
    let fail = |reason: String| ScoringError::Comparison {
        field: field.to_string(),
        reason,
    };
    let counted: Vec<&TrialScore> = report.trials.iter().filter(|t| t.counted).collect();
    let mut groups = find_groups(&counted, field);
    check_groups(&groups, counted.len()).map_err(fail)?;
    let reference = choose_reference(&mut groups, reference).map_err(fail)?;
    let rows: Vec<CompareRow> = report
        .tasks
        .iter()
        .filter(|r| r.counted > 0)
        .map(|r| {
            let of_row: Vec<&TrialScore> = (counted.iter().copied())
                .filter(|t| t.task == r.task && t.embodiment == r.embodiment)
                .collect();
            CompareRow {
                task: r.task.clone(),
                task_name: report.task_name(&r.task).to_string(),
                embodiment: r.embodiment.clone(),
                has_baseline: r.has_baseline,
                groups: row_groups(&of_row, field, &groups, &reference, r.has_baseline),
            }
        })
        .collect();
    let missing_trials = groups.iter().find(|g| g.missing).map_or(0, |g| g.trials);
    let notes = notes(report, field, missing_trials, &rows);
    Ok(Comparison {
        field: field.to_string(),
        reference,
        confidence_level: CONFIDENCE_LEVEL,
        groups,
        missing_trials,
        rows,
        example_baseline: report.baseline.as_ref().is_some_and(|b| b.example),
        warnings: report.warnings.clone(),
        notes,
        figures: Vec::new(),
    })
}

/// The groups of `counted` trials: values sorted, the missing group last.
fn find_groups(counted: &[&TrialScore], field: &str) -> Vec<CompareGroup> {
    let mut names: Vec<&str> = counted.iter().map(|t| group_of(t, field)).collect();
    names.sort_unstable_by_key(|n| (*n == MISSING_GROUP, *n));
    names.dedup();
    names
        .into_iter()
        .map(|name| CompareGroup {
            name: name.to_string(),
            missing: name == MISSING_GROUP,
            reference: false,
            trials: counted
                .iter()
                .filter(|t| group_of(t, field) == name)
                .count(),
        })
        .collect()
}

/// Two or more groups, or why not.
fn check_groups(groups: &[CompareGroup], counted: usize) -> Result<(), String> {
    match groups {
        [] => Err(
            "no recorded trial to compare (practice and excluded trials do not count)".to_string(),
        ),
        [only] if only.missing => Err(format!(
            "none of the {counted} recorded trials has this metadata entry: nothing to compare"
        )),
        [only] => Err(format!(
            "all {counted} recorded trials have the value {:?}: a comparison needs two or \
             more groups",
            only.name
        )),
        _ => Ok(()),
    }
}

/// Marks the reference group and returns its name.
fn choose_reference(groups: &mut [CompareGroup], asked: Option<&str>) -> Result<String, String> {
    let index = match asked {
        Some(name) => groups.iter().position(|g| g.name == name).ok_or_else(|| {
            let names: Vec<&str> = groups.iter().map(|g| g.name.as_str()).collect();
            format!(
                "reference group {name:?} has no recorded trial (groups: {})",
                names.join(", ")
            )
        })?,
        // check_groups leaves at least two groups, and only one can be the missing one.
        None => groups.iter().position(|g| !g.missing).unwrap_or(0),
    };
    groups[index].reference = true;
    Ok(groups[index].name.clone())
}

/// Every group's statistics in one task × embodiment, and the differences from the
/// reference.
fn row_groups(
    of_row: &[&TrialScore],
    field: &str,
    groups: &[CompareGroup],
    reference: &str,
    has_baseline: bool,
) -> Vec<GroupResult> {
    let stats = |name: &str, value: &dyn Fn(&TrialScore) -> Option<f64>| {
        let values: Vec<f64> = (of_row.iter())
            .filter(|t| group_of(t, field) == name)
            .filter_map(|t| value(t))
            .collect();
        MeanStd::of(&values)
    };
    let mut results: Vec<GroupResult> = groups
        .iter()
        .map(|g| GroupResult {
            group: g.name.clone(),
            n: of_row
                .iter()
                .filter(|t| group_of(t, field) == g.name)
                .count(),
            correctness: stats(&g.name, &|t| Some(t.correctness)),
            time_s: stats(&g.name, &|t| Some(t.time_s)),
            score: if has_baseline {
                stats(&g.name, &|t| t.score)
            } else {
                None
            },
            versus_reference: None,
        })
        .collect();
    let Some(base) = results.iter().find(|g| g.group == reference).cloned() else {
        return results;
    };
    for g in results.iter_mut().filter(|g| g.group != reference) {
        g.versus_reference = versus(g, &base);
    }
    results
}

/// `group − reference` for each measure both have.
fn versus(group: &GroupResult, reference: &GroupResult) -> Option<VersusReference> {
    let diff =
        |a: Option<MeanStd>, b: Option<MeanStd>| Some(welch_difference(&a?, &b?, CONFIDENCE_LEVEL));
    Some(VersusReference {
        correctness: diff(group.correctness, reference.correctness)?,
        time_s: diff(group.time_s, reference.time_s)?,
        score: diff(group.score, reference.score),
    })
}

/// Trials left out, the missing group, tasks without a baseline, undefined intervals.
fn notes(
    report: &ScoreReport,
    field: &str,
    missing_trials: usize,
    rows: &[CompareRow],
) -> Vec<String> {
    let mut notes = Vec::new();
    let practice = report.trials.iter().filter(|t| t.practice).count();
    let excluded = (report.trials.iter())
        .filter(|t| !t.practice && !t.counted)
        .count();
    if practice + excluded > 0 {
        notes.push(format!(
            "{practice} practice and {excluded} excluded trial(s) left out, as in the report."
        ));
    }
    if missing_trials > 0 {
        notes.push(format!(
            "{missing_trials} recorded trial(s) have no {field:?} entry: group {MISSING_GROUP}."
        ));
    }
    let without: Vec<String> = (rows.iter())
        .filter(|r| !r.has_baseline)
        .map(|r| format!("{} ({})", r.task, r.embodiment))
        .collect();
    if !without.is_empty() {
        notes.push(format!(
            "no baseline for {}: correctness and time only, no score.",
            without.join(", ")
        ));
    }
    let differences: Vec<Difference> = (rows.iter())
        .flat_map(|r| &r.groups)
        .filter_map(|g| g.versus_reference)
        .flat_map(|v| [Some(v.correctness), Some(v.time_s), v.score])
        .flatten()
        .collect();
    let undefined = differences.iter().filter(|d| !d.ci.is_defined()).count();
    if undefined > 0 {
        notes.push(format!(
            "{undefined} of {} differences have no confidence interval: a group has fewer \
             than 2 trials there, or neither group varies.",
            differences.len()
        ));
    }
    notes
}

#[cfg(test)]
#[path = "compare_tests.rs"]
pub(crate) mod tests;
