//! One trial's score: outcome, time, correctness, speed.
//!
//! ```text
//! time        = t(stop) − t(start)            (aborted: t(abort) − t(start))
//! outcome     = aborted | timed out (time > the task's limit) | completed
//! correctness = per the task's kind (see `correctness`), counting progress up to the limit
//! speed       = baseline_mean_s / time        completed trials (unbounded above)
//!             = 0                             aborted or timed out; also completed trials with
//!                                             correctness < 1 when speed_needs_full_correctness
//! score       = w_c · correctness + w_s · speed          (w_c = 0.8, w_s = 0.2)
//!             = 0 for an unfinished trial under the rule `zero`
//!             = none (correctness only) when the task has no baseline
//! ```

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::baseline::BaselineTable;
use crate::catalog::TaskCatalog;
use crate::correctness::correctness;
use crate::error::ScoringError;
use crate::rules::{ScoringRules, UnfinishedRule};
use crate::trial_log::{Ending, TrialLog, TrialRecord};

/// How a trial ended, for scoring.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// Stopped within the time limit.
    Completed,
    /// Aborted.
    Aborted,
    /// Stopped after the time limit.
    TimedOut,
}

impl Outcome {
    /// The name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Completed => "completed",
            Outcome::Aborted => "aborted",
            Outcome::TimedOut => "timed_out",
        }
    }
}

/// A scored trial.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrialScore {
    /// The trial's file.
    pub file: String,
    /// Task ID.
    pub task: String,
    /// Embodiment.
    pub embodiment: String,
    /// User, if recorded.
    pub user: Option<String>,
    /// Operator, if recorded.
    pub operator: Option<String>,
    /// Index in its series, if recorded.
    pub trial_index: Option<String>,
    /// Every entry of the trial's `pomdar_trial` metadata record (for grouping trials by
    /// any of them, e.g. `keypoint_source`).
    #[serde(default)]
    pub metadata: BTreeMap<String, String>,
    /// Practice trial: shown, never in a mean.
    pub practice: bool,
    /// How it ended.
    pub outcome: Outcome,
    /// Trial time, seconds (start → stop, or start → abort).
    pub time_s: f64,
    /// Raw progress counted (notches, curves, degrees, mm or grasp level).
    pub progress: f64,
    /// Correctness in [0, 1].
    pub correctness: f64,
    /// The speed term's speed (`baseline / time`, or 0 for an unfinished trial); `None`
    /// without a baseline for the task.
    pub speed: Option<f64>,
    /// The score; `None` without a baseline for the task (correctness only).
    pub score: Option<f64>,
    /// Whether it counts in the means: recorded (not practice) and not excluded by the rule
    /// for unfinished trials.
    pub counted: bool,
    /// Remarks: drops, capped totals, operator notes, why not counted.
    pub notes: Vec<String>,
}

/// Scores one checked trial.
pub fn score_record(
    record: &TrialRecord,
    catalog: &TaskCatalog,
    baseline: Option<&BaselineTable>,
    rules: &ScoringRules,
) -> Result<TrialScore, ScoringError> {
    let task = catalog.get(&record.task).ok_or_else(|| {
        ScoringError::trial(
            &record.source,
            format!(
                "unknown task {:?} (catalog {})",
                record.task, catalog.origin
            ),
        )
    })?;
    let time_s = record.time_s();
    let limit = rules.timeout_for(&record.task);
    let outcome = match record.ending {
        Ending::Aborted => Outcome::Aborted,
        Ending::Stopped if limit.is_some_and(|l| time_s > l) => Outcome::TimedOut,
        Ending::Stopped => Outcome::Completed,
    };
    let cutoff_ns = match (outcome, limit) {
        (Outcome::TimedOut, Some(l)) => Some(record.start_ns + (l * 1e9).round() as i64),
        _ => None,
    };
    let c = correctness(&task.correctness, &record.marks, cutoff_ns).map_err(|reason| {
        ScoringError::trial(&record.source, format!("task {}: {reason}", task.id))
    })?;
    let mut notes = c.notes;
    notes.extend(record.notes.iter().map(|n| format!("note: {n}")));

    let unfinished = outcome != Outcome::Completed;
    let baseline_s = baseline.and_then(|b| b.get(&task.id)).map(|b| b.mean_s);
    let speed = baseline_s.map(|b| {
        if unfinished || (rules.speed_needs_full_correctness && c.value < 1.0) {
            0.0
        } else {
            b / time_s
        }
    });
    let score = speed.map(|s| {
        if unfinished && rules.unfinished == UnfinishedRule::Zero {
            0.0
        } else {
            rules.correctness_weight * c.value + rules.speed_weight * s
        }
    });
    let excluded = unfinished && rules.unfinished == UnfinishedRule::Exclude;
    if unfinished {
        notes.push(format!(
            "{}: {}",
            outcome.name().replace('_', " "),
            match rules.unfinished {
                UnfinishedRule::Partial => "correctness reached, speed term 0",
                UnfinishedRule::Zero => "scored 0",
                UnfinishedRule::Exclude => "left out of the means",
            }
        ));
    }
    if record.practice {
        notes.push("practice: not in the means".to_string());
    }
    Ok(TrialScore {
        file: record.source.clone(),
        task: record.task.clone(),
        embodiment: record.embodiment.clone(),
        user: record.user.clone(),
        operator: record.operator.clone(),
        trial_index: record.trial_index.clone(),
        metadata: record.metadata.clone(),
        practice: record.practice,
        outcome,
        time_s,
        progress: c.progress,
        correctness: c.value,
        speed,
        score,
        counted: !record.practice && !excluded,
        notes,
    })
}

/// Checks and scores one trial log: [`TrialRecord::from_log`] then [`score_record`].
pub fn score_trial(
    log: &TrialLog,
    catalog: &TaskCatalog,
    baseline: Option<&BaselineTable>,
    rules: &ScoringRules,
) -> Result<TrialScore, ScoringError> {
    let record = TrialRecord::from_log(log, catalog)?;
    score_record(&record, catalog, baseline, rules)
}
