//! The session's outcome once it has quit: its log finished (as aborted after a script's
//! failure), then the report of a complete session with its fit, or the error saying why there
//! is none and naming the log.

use std::path::PathBuf;

use serde_json::json;

use crate::calibrate::CalibrateError;
use crate::calibrate::pose_session::PosePhase;

use super::SessionReport;
use super::session_turn::SessionRun;

impl SessionRun<'_> {
    /// The session has quit: the log is finished (as aborted after a failure) and the
    /// session's outcome returned.
    pub(super) fn finish(mut self) -> Result<SessionReport, CalibrateError> {
        let failure = self.end.failure.take();
        if let Some(w) = self.log.writer.take() {
            let now = self.clock.now_ns();
            if let Some(f) = &failure {
                let event = json!({"event": "abort", "reason": f.reason()});
                w.write(move |w| w.write_event(now, &event))?;
            }
            let finished = self.finish_log(w, now)?;
            self.log.path = Some(finished.path);
        }
        let path = self
            .log
            .path
            .take()
            .unwrap_or_else(|| self.options.out.clone());
        if let Some(failure) = failure {
            return Err(failure.error(path));
        }
        self.report(path)
    }

    /// The report of a complete session with its fit; otherwise why there is none.
    fn report(self, path: PathBuf) -> Result<SessionReport, CalibrateError> {
        let session = &self.session;
        match (self.end.completed, self.fit.outcome, session.phase()) {
            (true, Some(fit), _) => {
                let accepted = |k: usize| session.accepted(k);
                Ok(SessionReport {
                    path,
                    frames_per_pose: (0..session.poses().len())
                        .map(|k| accepted(k).map_or(0, |a| a.quality.frames))
                        .collect(),
                    captures_per_pose: session.attempts().iter().map(Vec::len).collect(),
                    frames: self.log.frames,
                    poses_not_sent: self.hand.not_sent,
                    fit,
                })
            }
            (_, _, PosePhase::Failed(reason)) => Err(CalibrateError::Failed {
                reason: reason.clone(),
                log: path,
            }),
            _ => Err(CalibrateError::Abandoned { log: path }),
        }
    }
}
