//! A running session ([`SessionRun`]: the pose session, its log, the hand, the fit and the
//! console) and what it does with each wake-up of its loop: a glove frame logged and judged,
//! the commanded pose re-sent, a key, the fit's end; then the rest of the turn: an
//! interruption or a glove that never came ends the session, the script's and the operator's
//! actions and the clock go to the pose session, its effects are carried out, the simulated
//! user is cued and the console shown.

use msgs::JointState;
use serde_json::json;
use station::convert::KeypointMessage;
use tokio::sync::watch;
use tokio::time::Instant;

use crate::calibrate::CalibrateError;
use crate::calibrate::calibration_console::{ConsoleFront, FrontAction};
use crate::calibrate::calibration_view::CalState;
use crate::calibrate::fit_session::{FitOutcome, fit_done};
use crate::calibrate::pose_session::{CalibrationAction, Effect, PosePhase, PoseSession};
use crate::clock::StationClock;
use crate::disk_wait::without_holding_the_runtime;
use crate::mcap_log::{FinishedTrial, LogError, WriterThread};
use crate::tui::terminal::Input;
use crate::tui::terminal_shell::Next;

use super::fit_run::FitRun;
use super::hand_command::HandCommand;
use super::session_end::{ScriptFailure, SessionEnd};
use super::session_log::{SLOW_DISK_QUEUE, SessionLog, finish_log};
use super::{PoseCue, SessionOptions};

/// What one wake-up of the session's loop brought: the operator's actions and the session's
/// effects so far (the consoles' shared turn, [`crate::tui::terminal_shell::Turn`]).
pub(super) type Turn = crate::tui::terminal_shell::Turn<CalibrationAction, Effect>;

/// A running session: the pose session, its log, the hand, the fit and the console.
pub(super) struct SessionRun<'a> {
    pub(super) options: &'a SessionOptions,
    /// The session pose by pose (pure).
    pub(super) session: PoseSession,
    pub(super) log: SessionLog,
    pub(super) hand: HandCommand,
    pub(super) fit: FitRun,
    /// The operator's side.
    pub(super) front: &'a mut ConsoleFront,
    /// The pose and attempt a simulated user follows, and the last sent.
    pub(super) cue: Option<watch::Sender<Option<PoseCue>>>,
    pub(super) cued: Option<PoseCue>,
    pub(super) clock: StationClock,
    /// When the session started waiting for the glove.
    pub(super) started: Instant,
    pub(super) end: SessionEnd,
}

impl SessionRun<'_> {
    /// A keypoint message: logged at its receive time `now` and given to the session.
    pub(super) fn keypoints_received(
        &mut self,
        message: &KeypointMessage,
        now: i64,
        source_ns: i64,
    ) -> Result<Vec<Effect>, LogError> {
        let topic = &self.options.station.input.keypoints_topic;
        self.log.keypoints(topic, message, now, source_ns)?;
        Ok(self.session.frame(message.points(), now))
    }

    /// The commanded pose to send again (logged), if the hand is being sent to one.
    pub(super) fn pose_to_resend(&mut self) -> Result<Option<JointState>, LogError> {
        let Some(k) = self.hand.current else {
            return Ok(None);
        };
        let now = self.clock.now_ns();
        let message = self.hand.message(k, now);
        let topic = &self.options.station.output.joint_targets_topic;
        self.log.pose_sent(topic, now, &message)?;
        Ok(Some(message))
    }

    /// A pose sent to the hand, or why it could not be: a failure is counted, said in the
    /// console the first time, and logged when the log is finished.
    pub(super) fn pose_sent<E: std::fmt::Display>(&mut self, sent: Result<(), E>) {
        if let Some(e) = self.hand.sent(sent) {
            self.session.say(format!(
                "cannot send the pose to the hand on {}: {e}",
                self.options.station.output.joint_targets_topic
            ));
        }
    }

    /// Finishes the log, after an event counting the poses that could not be sent (if any).
    pub(super) fn finish_log(&self, w: WriterThread, now: i64) -> Result<FinishedTrial, LogError> {
        let topic = &self.options.station.output.joint_targets_topic;
        finish_log(w, now, self.hand.not_sent, topic)
    }

    /// A key: an action on the session, or Ctrl-C.
    pub(super) fn key_pressed(&mut self, input: &Input, actions: &mut Vec<CalibrationAction>) {
        match ConsoleFront::key_action(input) {
            Some(FrontAction::Interrupt) => self.end.interrupted = true,
            Some(FrontAction::Act(a)) => actions.push(a),
            None => {}
        }
    }

    /// The fit task ended: its table in the console, its line and outcome to the session.
    pub(super) fn fit_finished(
        &mut self,
        result: Result<Result<FitOutcome, CalibrateError>, tokio::task::JoinError>,
    ) -> Vec<Effect> {
        let fit = &self.fit.options;
        self.fit.task = None;
        let outcome = match result {
            Ok(Ok(outcome)) => Ok(outcome),
            Ok(Err(e)) => Err(e.to_string()),
            Err(e) => Err(format!("the fit task failed: {e}")),
        };
        let done = outcome
            .as_ref()
            .map(|o| fit_done(o, self.fit.outcome.as_ref(), fit))
            .map_err(Clone::clone);
        if let Ok(o) = &outcome {
            let mut lines = o.table.clone();
            lines.push(format!("profile: {}", fit.out.display()));
            self.front.set_results(lines);
        }
        self.fit.outcome = outcome.ok();
        self.session.fit_finished(done)
    }

    /// The rest of a turn after a wake-up: an interruption or a glove that never came ends
    /// the session; the script's and the operator's actions and the clock go to the session,
    /// its effects are carried out, the simulated user cued, the console shown.
    pub(super) fn finish_turn(&mut self, mut turn: Turn) -> Result<Next, CalibrateError> {
        let now = self.clock.now_ns();
        if let Some(next) = self.stop_if_interrupted(now)? {
            self.front.show(&self.session, now)?;
            return Ok(next);
        }
        self.stop_if_no_glove()?;
        self.play_script(&mut turn.actions);
        for action in turn.actions {
            turn.effects.extend(self.session.act(action, now));
        }
        turn.effects.extend(self.session.tick(now));
        let mut next = self.carry_out(turn.effects)?;
        self.cue_pose();
        if next == Next::Continue {
            next = self.after_the_script();
        }
        self.front.show(&self.session, now)?;
        Ok(next)
    }

    /// Ctrl-C or the shutdown: while recording, the log is finished as aborted and the
    /// session ends with an error; during the fit, the fit is cancelled and the session waits
    /// for it to stop (at its next evaluation, writing no profile), then ends with an error
    /// naming the log (kept). After a fit that wrote its profile the session ends complete;
    /// after one that failed by itself, with the failure. `None`: not interrupted, the turn
    /// goes on.
    fn stop_if_interrupted(&mut self, now: i64) -> Result<Option<Next>, CalibrateError> {
        if !self.end.interrupted {
            return Ok(None);
        }
        if let Some(w) = self.log.writer.take() {
            let event = json!({"event": "abort", "reason": "interrupted"});
            w.write(move |w| w.write_event(now, &event))?;
            let finished = self.finish_log(w, now)?;
            return Err(CalibrateError::Interrupted { log: finished.path });
        }
        if self.fit.task.is_some() {
            if !self.fit.cancel() {
                self.session
                    .say("interrupted: stopping the fit; no profile will be written");
            }
            return Ok(Some(Next::Continue));
        }
        if self.fit.outcome.is_some() {
            self.end.completed = true;
            return Ok(Some(Next::Quit));
        }
        let log = self.log.path.clone().unwrap_or_default();
        if let (false, PosePhase::Failed(reason)) = (self.fit.cancelled(), self.session.phase()) {
            return Err(CalibrateError::Failed {
                reason: reason.clone(),
                log,
            });
        }
        Err(CalibrateError::InterruptedFit { log })
    }

    /// No glove keypoints within the wait: the empty log is removed and the session ends
    /// with an error.
    fn stop_if_no_glove(&mut self) -> Result<(), CalibrateError> {
        let options = self.options;
        let config = &options.station;
        let topic = &config.input.keypoints_topic;
        if *self.session.phase() == PosePhase::WaitingGlove
            && self.started.elapsed() > options.glove_wait
        {
            if let Some(w) = self.log.writer.take() {
                drop(without_holding_the_runtime(|| w.finish()));
            }
            std::fs::remove_file(&options.out).ok();
            return Err(CalibrateError::NoGlove {
                topic: topic.clone(),
                wait_s: options.glove_wait.as_secs_f64(),
                domain: crate::ros::domain_id(config.network.domain_id)?,
            });
        }
        Ok(())
    }

    /// The script's due action; a script that timed out quits the session as a failure.
    fn play_script(&mut self, actions: &mut Vec<CalibrationAction>) {
        match self.front.script_action(CalState::of(&self.session)) {
            Ok(Some(a)) => actions.push(a),
            Ok(None) => {}
            Err(e) => {
                self.session.say(e.to_string());
                self.end.failure = Some(ScriptFailure::TimedOut(e));
                actions.push(CalibrationAction::Quit);
            }
        }
    }

    /// Carries out the session's effects: the pose to command, log events, the fit, quitting.
    fn carry_out(&mut self, effects: Vec<Effect>) -> Result<Next, CalibrateError> {
        let mut next = Next::Continue;
        for effect in effects {
            match effect {
                Effect::Command(k) => self.hand.command(k),
                Effect::Log { at_ns, event } => self.log.event(at_ns, event)?,
                Effect::ContinueLog => self.log.continue_finished()?,
                Effect::Fit { .. } => {
                    self.hand.stop();
                    self.start_fit()?;
                }
                Effect::Quit { completed: done } => {
                    next = Next::Quit;
                    self.end.completed = done;
                }
            }
        }
        Ok(next)
    }

    /// Every pose accepted: the log is finished and fitted in a blocking task, its progress
    /// sent back.
    fn start_fit(&mut self) -> Result<(), CalibrateError> {
        let Some(w) = self.log.writer.take() else {
            return Ok(());
        };
        let queued = w.pending();
        if queued >= SLOW_DISK_QUEUE {
            self.session.say(format!(
                "saving the session log: {queued} writes still queued (the disk is slow)"
            ));
            self.front.show(&self.session, self.clock.now_ns())?;
        }
        let finished = self
            .finish_log(w, self.clock.now_ns())
            .map_err(|source| CalibrateError::FinishLog { source })?;
        self.session
            .say(format!("session recorded: {}", finished.path.display()));
        self.log.path = Some(finished.path.clone());
        self.fit.start(finished.path);
        Ok(())
    }

    /// A simulated user is told each new pose and attempt.
    fn cue_pose(&mut self) {
        if let PosePhase::Settling { pose, attempt, .. } = *self.session.phase() {
            let now_cue = PoseCue { pose, attempt };
            if self.cued != Some(now_cue) {
                self.cued = Some(now_cue);
                if let Some(cue) = &self.cue {
                    cue.send(Some(now_cue)).ok();
                }
            }
        }
    }

    /// A script that has ended decides nothing more: a finished session ends the console,
    /// a capture left under review is an error.
    fn after_the_script(&mut self) -> Next {
        if self.front.script_finished() != Some(true) {
            return Next::Continue;
        }
        match CalState::of(&self.session) {
            CalState::Complete => {
                self.end.completed = true;
                Next::Quit
            }
            CalState::Failed => Next::Quit,
            CalState::Review => {
                let failure = ScriptFailure::EndedInReview;
                self.session.say(failure.reason());
                self.end.failure = Some(failure);
                Next::Quit
            }
            _ => Next::Continue,
        }
    }
}
