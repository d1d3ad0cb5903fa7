//! A simulated run as a trial: the metadata record and the trial events the scoring reads,
//! the same whether kept in memory or written to a trial log.
//!
//! The trial starts with the glove script (simulated time 0). Each progress event of the
//! physics is the mark an operator's key makes at that time; a run whose marks complete the
//! task stops at the event that completed it (the trial time is the physics' completion
//! time); a run that ends first is aborted there, as an operator gives up a trial that will
//! not finish ("unfinished": its correctness counts, its speed is 0).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use serde_json::{Value, json};

use crate::stand_ins::progress_message::ProgressMessage;

/// Log time of a run's start: 2026-01-01 00:00:00 UTC, the same for every run, so a seed
/// gives the same file.
pub const RUN_EPOCH_NS: i64 = 1_767_225_600_000_000_000;

/// What the abort of an unfinished run says.
pub const UNFINISHED_REASON: &str = "the strategy's script ended before the task was done";

/// A played run as the scoring sees it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunTrial {
    /// The `pomdar_trial` metadata record.
    pub metadata: BTreeMap<String, String>,
    /// The trial events `(log time ns, JSON)`, in order.
    pub events: Vec<(i64, Value)>,
}

/// Log time of simulated time `t_s`.
pub fn log_ns(t_s: f64) -> i64 {
    RUN_EPOCH_NS + (t_s * 1e9).round() as i64
}

/// The trial event of a progress message.
pub fn progress_event(event: &ProgressMessage) -> Value {
    match event.value {
        Some(value) if event.event == "progress" => json!({"event": "progress", "value": value}),
        _ => json!({"event": "drop"}),
    }
}

/// The events that end a run: `stop` at the completion, or `abort` then `stop` at `end_s`.
pub fn ending_events(completed_at_s: Option<f64>, end_s: f64) -> Vec<(i64, Value)> {
    match completed_at_s {
        Some(t) => vec![(log_ns(t), json!({"event": "stop", "summary": "completed"}))],
        None => vec![
            (
                log_ns(end_s),
                json!({"event": "abort", "reason": UNFINISHED_REASON}),
            ),
            (
                log_ns(end_s),
                json!({"event": "stop", "summary": "unfinished"}),
            ),
        ],
    }
}

/// The whole trial of a run: start, its progress events up to the completion, the ending.
pub fn run_trial(
    metadata: BTreeMap<String, String>,
    events: &[ProgressMessage],
    completed_at_s: Option<f64>,
    end_s: f64,
) -> RunTrial {
    let mut trial_events = vec![(log_ns(0.0), json!({"event": "start"}))];
    trial_events.extend(
        events
            .iter()
            .map(|e| (log_ns(e.sim_time_s), progress_event(e))),
    );
    trial_events.extend(ending_events(completed_at_s, end_s));
    RunTrial {
        metadata,
        events: trial_events,
    }
}

impl RunTrial {
    /// As the scoring reads it, named `source`.
    pub fn log(&self, source: &str) -> scoring::TrialLog {
        scoring::TrialLog {
            source: source.to_string(),
            metadata: self.metadata.clone(),
            events: self.events.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn event(event: &str, value: Option<f64>, t: f64) -> ProgressMessage {
        ProgressMessage {
            task: "V2".into(),
            event: event.into(),
            value,
            unit: "notches".into(),
            total: 0.0,
            sim_time_s: t,
        }
    }

    fn metadata(task: &str) -> BTreeMap<String, String> {
        [
            ("task", task),
            ("embodiment", "orca_full"),
            ("practice", "false"),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect()
    }

    fn scored(trial: &RunTrial) -> scoring::TrialScore {
        let catalog = scoring::TaskCatalog::builtin();
        let rules = scoring::ScoringRules::default();
        scoring::score_trial(&trial.log("run"), &catalog, None, &rules).unwrap()
    }

    #[test]
    fn a_completed_run_stops_at_its_completion_and_an_unfinished_one_is_aborted() {
        let notches: Vec<ProgressMessage> = (1..=6)
            .map(|k| event("progress", Some(1.0), 2.0 * f64::from(k)))
            .collect();
        let done = run_trial(metadata("V2"), &notches, Some(12.0), 12.0);
        let s = scored(&done);
        assert_eq!(
            (s.outcome, s.correctness, s.time_s),
            (scoring::Outcome::Completed, 1.0, 12.0)
        );
        let half = run_trial(metadata("V2"), &notches[..3], None, 30.0);
        let s = scored(&half);
        assert_eq!(
            (s.outcome, s.correctness, s.time_s),
            (scoring::Outcome::Aborted, 0.5, 30.0)
        );
        assert!(
            s.notes.iter().any(|n| n.contains(UNFINISHED_REASON)),
            "{:?}",
            s.notes
        );
    }

    #[test]
    fn a_drop_is_the_operators_drop_mark() {
        let grasp = [event("progress", Some(0.5), 3.0), event("drop", None, 4.0)];
        let trial = run_trial(metadata("G4"), &grasp, None, 12.0);
        assert_eq!(trial.events[2].1, json!({"event": "drop"}));
        assert_eq!(scored(&trial).correctness, 0.5);
    }
}
