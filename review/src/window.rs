//! The trial's time window: from its `start` event to its `stop` (or `abort`), and the
//! conversion of log times to seconds into the trial.

use serde::Serialize;

use crate::error::ReviewError;
use crate::input::TrialInput;

/// The trial's start and end on the log's clock.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TrialWindow {
    /// The `start` event's log time, nanoseconds.
    pub start_ns: i64,
    /// The `stop` or `abort` event's log time, else the last logged time, nanoseconds.
    pub end_ns: i64,
}

impl TrialWindow {
    /// The window of `input`; `Err` without a `start` event.
    pub fn of(input: &TrialInput) -> Result<TrialWindow, ReviewError> {
        let named = |name: &str| {
            input
                .events
                .iter()
                .find(|(_, e)| e["event"] == name)
                .map(|(t, _)| *t)
        };
        let start_ns = named("start").ok_or_else(|| ReviewError::NoStart {
            file: input.source.clone(),
        })?;
        let last_logged = [
            input.events.last().map(|e| e.0),
            input.statuses.last().map(|s| s.0),
            input.glove_frames.last().map(|f| f.t_ns),
            input.joint_targets.last().map(|j| j.t_ns),
        ]
        .into_iter()
        .flatten()
        .max()
        .unwrap_or(start_ns);
        let end_ns = named("abort")
            .or_else(|| named("stop"))
            .unwrap_or(last_logged)
            .max(start_ns + 1);
        Ok(TrialWindow { start_ns, end_ns })
    }

    /// Seconds from the start to `t_ns`.
    pub fn secs(&self, t_ns: i64) -> f64 {
        (t_ns - self.start_ns) as f64 * 1e-9
    }

    /// The trial's length, seconds.
    pub fn duration_s(&self) -> f64 {
        self.secs(self.end_ns)
    }

    /// Whether `t_ns` is inside the trial.
    pub fn contains(&self, t_ns: i64) -> bool {
        (self.start_ns..=self.end_ns).contains(&t_ns)
    }
}
