//! A trial as the scoring needs it, and its structural checks.
//!
//! [`TrialLog`] is what the station's log holds for scoring (built by `teleop` from the MCAP
//! file: the `pomdar_trial` metadata record and the JSON events on `/pomdar/trial_events`,
//! in file order). [`TrialRecord::from_log`] checks it and returns the trial's facts, or an
//! error naming the file and the first problem found.
//!
//! ## Metadata (`pomdar_trial` record)
//!
//! Required: `task` (an ID of the catalog), `embodiment` (`orca_full`, ..., `human`),
//! `practice` (`"true"` or `"false"`). Kept when present: `user`, `operator`, `trial_index`.
//! Every entry (these and any other, e.g. `keypoint_source`, `station_version`) is kept in
//! [`TrialRecord::metadata`], so a report can group trials by any of them.
//!
//! ## Events
//!
//! Each event is a JSON object with a string `event`:
//!
//! | event | fields | meaning |
//! |---|---|---|
//! | `start` | | the trial's clock starts (exactly one) |
//! | `progress` | `value` (number) | progress in the task's unit (see the crate docs) |
//! | `drop` | | the object fell (grasp tasks: level 0.5) |
//! | `abort` | `reason` (optional) | the trial was abandoned (at most one) |
//! | `note` | `text` | free text; allowed anywhere |
//! | `stop` | `summary` (ignored) | the trial's clock stops (at most one) |
//!
//! Rules: log times never decrease in file order; nothing but notes before `start`; after
//! `abort` only `stop` and notes; nothing but notes after `stop`; a trial without `abort`
//! needs a `stop`; the trial time (start → stop, or start → abort) is > 0. Unknown event
//! names are errors, so a misspelt event is never silently ignored.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::catalog::TaskCatalog;
use crate::error::ScoringError;

/// Name of the MCAP metadata record that describes a trial.
pub const TRIAL_METADATA_NAME: &str = "pomdar_trial";

/// The embodiment name of human (baseline) trials.
pub const HUMAN_EMBODIMENT: &str = "human";

/// A trial's log as read from its file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TrialLog {
    /// The file (as the operator named it): every error about the trial names it.
    pub source: String,
    /// The entries of the `pomdar_trial` metadata record.
    pub metadata: BTreeMap<String, String>,
    /// The trial events `(log time ns, JSON)`, in file order.
    pub events: Vec<(i64, serde_json::Value)>,
}

/// A progress-relevant mark of a trial, in log order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mark {
    /// A `progress` event with its value.
    Progress(f64),
    /// A `drop` event.
    Drop,
}

/// How a trial ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Ending {
    /// A `stop` event without `abort`.
    Stopped,
    /// An `abort` event (the trial time ends there).
    Aborted,
}

/// A structurally valid trial: its metadata and its events, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct TrialRecord {
    /// The file.
    pub source: String,
    /// Task ID (in the catalog).
    pub task: String,
    /// Embodiment name.
    pub embodiment: String,
    /// Practice trial (unscored in the means).
    pub practice: bool,
    /// The user wearing the glove, if recorded.
    pub user: Option<String>,
    /// The operator, if recorded.
    pub operator: Option<String>,
    /// The trial's index in its series, if recorded.
    pub trial_index: Option<String>,
    /// Every entry of the `pomdar_trial` metadata record, the ones above included.
    pub metadata: BTreeMap<String, String>,
    /// Log time of `start`, ns.
    pub start_ns: i64,
    /// Log time of `stop` (or of `abort` for an aborted trial), ns.
    pub end_ns: i64,
    /// How it ended.
    pub ending: Ending,
    /// Progress and drop events with their log times, in order.
    pub marks: Vec<(i64, Mark)>,
    /// The operator's notes and the abort reason, in order.
    pub notes: Vec<String>,
}

impl TrialRecord {
    /// Trial time in seconds (start → stop, or start → abort).
    pub fn time_s(&self) -> f64 {
        (self.end_ns - self.start_ns) as f64 / 1e9
    }

    /// Checks `log` (see the module docs) against `catalog`.
    pub fn from_log(log: &TrialLog, catalog: &TaskCatalog) -> Result<TrialRecord, ScoringError> {
        let fail = |reason: String| ScoringError::trial(&log.source, reason);
        let Metadata {
            task,
            embodiment,
            practice,
        } = Metadata::read(log, catalog).map_err(fail)?;
        let events = parse_events(log)?;
        check_order_and_start(&events).map_err(fail)?;
        let walked = walk_events(&events).map_err(fail)?;
        let (start_ns, end_ns, ending) = walked.span().map_err(fail)?;
        let optional = |key: &str| log.metadata.get(key).cloned();
        Ok(TrialRecord {
            source: log.source.clone(),
            task,
            embodiment,
            practice,
            user: optional("user"),
            operator: optional("operator"),
            trial_index: optional("trial_index"),
            metadata: log.metadata.clone(),
            start_ns,
            end_ns,
            ending,
            marks: walked.marks,
            notes: walked.notes,
        })
    }
}

/// The required metadata entries, checked.
struct Metadata {
    task: String,
    embodiment: String,
    practice: bool,
}

impl Metadata {
    /// The required entries of `log`'s metadata; the task must be in `catalog`.
    fn read(log: &TrialLog, catalog: &TaskCatalog) -> Result<Metadata, String> {
        let required = |key: &str| {
            log.metadata
                .get(key)
                .filter(|v| !v.trim().is_empty())
                .cloned()
                .ok_or_else(|| {
                    format!(
                        "the {TRIAL_METADATA_NAME} metadata record has no '{key}' (required: task, embodiment, practice)"
                    )
                })
        };
        let task = required("task")?;
        if catalog.get(&task).is_none() {
            return Err(format!(
                "unknown task {task:?}: not in the {} ({})",
                catalog.origin,
                catalog.ids()
            ));
        }
        let embodiment = required("embodiment")?;
        let practice = match required("practice")?.as_str() {
            "true" => true,
            "false" => false,
            other => {
                return Err(format!(
                    "metadata practice = {other:?}: expected \"true\" or \"false\""
                ));
            }
        };
        Ok(Metadata {
            task,
            embodiment,
            practice,
        })
    }
}

/// Event `i` of `events` for a message: `event 3 (progress, +1.500 s)`, the time counted
/// from the first event.
fn describe_event(events: &[(i64, Event)], i: usize) -> String {
    let base_ns = events.first().map_or(0, |(t, _)| *t);
    let (t, e) = &events[i];
    format!(
        "event {} ({}, +{:.3} s)",
        i + 1,
        e.name(),
        (t - base_ns) as f64 * 1e-9
    )
}

/// Log times never decrease, and there is a start event.
fn check_order_and_start(events: &[(i64, Event)]) -> Result<(), String> {
    let at = |i: usize| describe_event(events, i);
    for i in 1..events.len() {
        if events[i].0 < events[i - 1].0 {
            return Err(format!(
                "events out of order: {} is earlier than {}",
                at(i),
                at(i - 1)
            ));
        }
    }
    if !events.iter().any(|(_, e)| *e == Event::Start) {
        let first = events
            .iter()
            .position(|(_, e)| !matches!(e, Event::Note(_)))
            .map_or(String::new(), |i| {
                format!(" (the first event is {})", at(i))
            });
        return Err(format!("missing start event{first}"));
    }
    Ok(())
}

/// What the events say, once their sequence has been checked.
#[derive(Default)]
struct WalkedEvents {
    start: Option<i64>,
    abort: Option<i64>,
    stop: Option<i64>,
    marks: Vec<(i64, Mark)>,
    notes: Vec<String>,
}

impl WalkedEvents {
    /// Start and end log times (ns) and how the trial ended; the trial time must be > 0.
    fn span(&self) -> Result<(i64, i64, Ending), String> {
        let Some(start_ns) = self.start else {
            return Err("missing start event".to_string());
        };
        let (end_ns, ending) = match (self.abort, self.stop) {
            (Some(t), _) => (t, Ending::Aborted),
            (None, Some(t)) => (t, Ending::Stopped),
            (None, None) => {
                return Err(
                    "missing stop event (the trial was neither stopped nor aborted)".to_string(),
                );
            }
        };
        if end_ns <= start_ns {
            return Err(format!(
                "trial time is zero: the {} event has the start event's log time",
                match ending {
                    Ending::Stopped => "stop",
                    Ending::Aborted => "abort",
                }
            ));
        }
        Ok((start_ns, end_ns, ending))
    }
}

/// Walks the events in order, checking their sequence (see the module docs) and collecting
/// the start, abort and stop times, the marks and the notes.
fn walk_events(events: &[(i64, Event)]) -> Result<WalkedEvents, String> {
    let at = |i: usize| describe_event(events, i);
    let mut walked = WalkedEvents::default();
    for (i, (t, event)) in events.iter().enumerate() {
        if let Event::Note(text) = event {
            walked.notes.push(text.clone());
            continue;
        }
        if let Event::Start = event {
            if walked.start.is_some() {
                return Err(format!("duplicate start event: {}", at(i)));
            }
            walked.start = Some(*t);
            continue;
        }
        if walked.start.is_none() {
            return Err(format!("{} comes before the start event", at(i)));
        }
        if walked.stop.is_some() {
            return Err(format!("{} comes after the stop event", at(i)));
        }
        match event {
            Event::Stop => walked.stop = Some(*t),
            Event::Abort(reason) => {
                if walked.abort.is_some() {
                    return Err(format!("duplicate abort event: {}", at(i)));
                }
                walked.abort = Some(*t);
                walked.notes.push(match reason {
                    Some(r) => format!("aborted: {r}"),
                    None => "aborted".to_string(),
                });
            }
            Event::Progress(_) | Event::Drop if walked.abort.is_some() => {
                return Err(format!("{} comes after the abort event", at(i)));
            }
            Event::Progress(v) => walked.marks.push((*t, Mark::Progress(*v))),
            Event::Drop => walked.marks.push((*t, Mark::Drop)),
            Event::Start | Event::Note(_) => {}
        }
    }
    Ok(walked)
}

#[derive(Debug, Clone, PartialEq)]
enum Event {
    Start,
    Progress(f64),
    Drop,
    Abort(Option<String>),
    Note(String),
    Stop,
}

impl Event {
    fn name(&self) -> &'static str {
        match self {
            Event::Start => "start",
            Event::Progress(_) => "progress",
            Event::Drop => "drop",
            Event::Abort(_) => "abort",
            Event::Note(_) => "note",
            Event::Stop => "stop",
        }
    }
}

fn parse_events(log: &TrialLog) -> Result<Vec<(i64, Event)>, ScoringError> {
    let mut out = Vec::with_capacity(log.events.len());
    for (i, (t, json)) in log.events.iter().enumerate() {
        let fail = |what: String| {
            ScoringError::trial(&log.source, format!("trial event {}: {what}", i + 1))
        };
        let name = json
            .get("event")
            .and_then(serde_json::Value::as_str)
            .ok_or_else(|| fail(format!("{json} has no string \"event\"")))?;
        let event = match name {
            "start" => Event::Start,
            "stop" => Event::Stop,
            "drop" => Event::Drop,
            "abort" => Event::Abort(
                json.get("reason")
                    .and_then(serde_json::Value::as_str)
                    .map(str::to_string),
            ),
            "note" => Event::Note(
                json.get("text")
                    .and_then(serde_json::Value::as_str)
                    .unwrap_or_default()
                    .to_string(),
            ),
            "progress" => {
                let value = json
                    .get("value")
                    .and_then(serde_json::Value::as_f64)
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| {
                        fail(format!("progress {json} has no finite number \"value\""))
                    })?;
                Event::Progress(value)
            }
            other => {
                return Err(fail(format!(
                    "unknown event {other:?} (known: start, progress, drop, abort, note, stop)"
                )));
            }
        };
        out.push((*t, event));
    }
    Ok(out)
}
