//! The calibration session as a state machine, pose by pose: the hand is sent to the pose,
//! the user copies it and settles, the glove is captured, the capture's quality decides
//! (accepted, or the pose is captured again), and after the seventh pose the fit runs.
//!
//! Pure: the session node feeds it glove frames, clock ticks and the operator's actions with
//! the time, and carries out the [`Effect`]s it returns (command the hand, log an event, fit,
//! quit). Times are station-clock nanoseconds.
//!
//! ```text
//! waiting_glove ─first frame─▶ settling(k) ─settle_s─▶ capturing(k) ─capture_s─▶ quality
//!     good ─▶ accepted ─▶ settling(k+1) … after the 7th: fitting ─▶ complete | failed
//!     poor/bad ─(operator)─▶ review(k): r retries (settling(k) again), space accepts (poor only)
//!     bad ─(automatic)─▶ settling(k) again, up to max_attempts
//! complete ─(operator: r, when a pose did not fit)─▶ settling(k) ─ … ─▶ accepted ─▶ fitting
//! ```
//!
//! After the fit the session names the poses the fit could not match (the node judges them,
//! [`calibration::poses_that_do_not_fit`]). With an operator, `r` then captures the worst of
//! them alone again (the log is continued, the pose's new capture supersedes the old) and the
//! fit runs again on the seven accepted captures; `q` keeps the fit as it is.
//!
//! With an operator (the full-screen console or a `--script`), a good capture is accepted at
//! once, a poor or bad one waits in `review`: `r` captures the pose again, space / Enter
//! accepts a poor capture (a bad one cannot be fitted and is only retried). Without one (the
//! line console without a script), good and poor captures are accepted and a bad one is
//! retried automatically, at most [`AUTOMATIC_MAX_ATTEMPTS`] times per pose.

use std::collections::VecDeque;

use calibration::{CaptureThresholds, FitProgress};
use nalgebra::Point3;
use retarget::KeypointLayout;
use serde_json::{Value, json};

use crate::calibrate::capture_quality::{CaptureQuality, QualityLevel, measure};
use crate::calibrate::session_events::{DECISION_EVENT, QUALITY_EVENT, capture_event, pose_event};

/// Attempts per pose before an automatic session gives up.
pub const AUTOMATIC_MAX_ATTEMPTS: u32 = 3;
/// Messages kept for the view.
const MESSAGES_KEPT: usize = 50;

/// Who decides about a capture that is not good.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Policy {
    /// The operator (keys or a script): poor and bad captures wait for a decision.
    Operator,
    /// Nobody: poor captures are accepted, bad ones retried up to `max_attempts` per pose.
    Automatic {
        /// Captures of one pose before the session fails.
        max_attempts: u32,
    },
}

/// What the operator asks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CalibrationAction {
    /// Accept the capture under review (a poor one; a bad one is refused with a message).
    Accept,
    /// Capture the pose under review again.
    Retry,
    /// Quit: abandon a session in progress (the log is kept), or leave a finished one.
    Quit,
}

/// A pose of the session.
#[derive(Debug, Clone, PartialEq)]
pub struct PoseStep {
    /// Its name.
    pub name: String,
    /// What the user does.
    pub instruction: String,
}

/// Where the session is.
#[derive(Debug, Clone, PartialEq)]
pub enum PosePhase {
    /// Waiting for the glove's first frame.
    WaitingGlove,
    /// The hand shows pose `pose`; the user copies it and settles until `capture_ns`.
    Settling {
        /// Index of the pose.
        pose: usize,
        /// 1-based attempt.
        attempt: u32,
        /// When the settling began.
        since_ns: i64,
        /// When the capture starts.
        capture_ns: i64,
    },
    /// Capturing until `end_ns`.
    Capturing {
        /// Index of the pose.
        pose: usize,
        /// 1-based attempt.
        attempt: u32,
        /// When the capture window opened.
        start_ns: i64,
        /// When it closes.
        end_ns: i64,
    },
    /// A poor or bad capture waits for the operator.
    Review {
        /// Index of the pose.
        pose: usize,
        /// 1-based attempt.
        attempt: u32,
    },
    /// Every pose is accepted; the fit runs.
    Fitting,
    /// The fit is done.
    Complete,
    /// The session or the fit failed; the reason.
    Failed(String),
}

/// A fit that wrote its profile, as the session hears of it.
#[derive(Debug, Clone, PartialEq)]
pub struct FitDone {
    /// What to say: where the profile went, and how the fit changed after a redo.
    pub lines: Vec<String>,
    /// The poses the fit could not match, worst first: (pose index, the sentence naming it).
    pub misfits: Vec<(usize, String)>,
}

/// Event logged when a pose is captured again after the fit.
pub const REDO_EVENT: &str = "calibration_redo";

/// What the session node must do.
#[derive(Debug, Clone, PartialEq)]
pub enum Effect {
    /// Send the hand to pose `k` (and keep re-sending it).
    Command(usize),
    /// Write an event into the session log at `at_ns`.
    Log {
        /// Log time.
        at_ns: i64,
        /// The event.
        event: Value,
    },
    /// Open the finished log again to add to it (a pose is captured again after the fit).
    ContinueLog,
    /// Every pose is accepted: finish the log at `at_ns` and fit it.
    Fit {
        /// Log time of the session's end.
        at_ns: i64,
    },
    /// Stop: the session is abandoned (`completed` false) or finished.
    Quit {
        /// Whether the session (and its fit) finished.
        completed: bool,
    },
}

/// One capture and what became of it.
#[derive(Debug, Clone, PartialEq)]
pub struct Attempt {
    /// Its measures.
    pub quality: CaptureQuality,
    /// Whether it is the pose's accepted capture.
    pub accepted: bool,
}

/// The session's timing and checks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SessionTiming {
    /// Time for the user to copy the pose and settle before each capture, seconds.
    pub settle_s: f64,
    /// Length of each capture, seconds.
    pub capture_s: f64,
}

/// The session.
#[derive(Debug, Clone)]
pub struct PoseSession {
    poses: Vec<PoseStep>,
    layout: KeypointLayout,
    thresholds: CaptureThresholds,
    timing: SessionTiming,
    policy: Policy,
    phase: PosePhase,
    attempts: Vec<Vec<Attempt>>,
    frames: Vec<Vec<Point3<f64>>>,
    settle_frames: usize,
    expected_frames: Option<usize>,
    fit_progress: Option<FitProgress>,
    last_capture: Option<(usize, usize)>,
    messages: VecDeque<String>,
    said: u64,
    /// After the fit: the pose the operator may capture again.
    redo_offer: Option<usize>,
    /// A pose is being captured again after the fit: its acceptance leads to the fit.
    redoing: bool,
}

fn ns(seconds: f64) -> i64 {
    (seconds * 1e9).round() as i64
}

impl PoseSession {
    /// A session over `poses`, in order.
    pub fn new(
        poses: Vec<PoseStep>,
        layout: KeypointLayout,
        thresholds: CaptureThresholds,
        timing: SessionTiming,
        policy: Policy,
    ) -> PoseSession {
        let attempts = vec![Vec::new(); poses.len()];
        PoseSession {
            poses,
            layout,
            thresholds,
            timing,
            policy,
            phase: PosePhase::WaitingGlove,
            attempts,
            frames: Vec::new(),
            settle_frames: 0,
            expected_frames: None,
            fit_progress: None,
            last_capture: None,
            messages: VecDeque::new(),
            said: 0,
            redo_offer: None,
            redoing: false,
        }
    }

    /// Where the session is.
    pub fn phase(&self) -> &PosePhase {
        &self.phase
    }

    /// The poses.
    pub fn poses(&self) -> &[PoseStep] {
        &self.poses
    }

    /// The captures of each pose so far.
    pub fn attempts(&self) -> &[Vec<Attempt>] {
        &self.attempts
    }

    /// The session's timing.
    pub fn timing(&self) -> SessionTiming {
        self.timing
    }

    /// Who decides about captures that are not good.
    pub fn policy(&self) -> Policy {
        self.policy
    }

    /// The fit's progress, once it runs.
    pub fn fit_progress(&self) -> Option<FitProgress> {
        self.fit_progress
    }

    /// After the fit, the pose the operator may capture again (`r`).
    pub fn redo_offer(&self) -> Option<usize> {
        self.redo_offer
    }

    /// Pose `k`'s accepted capture: the latest, when the pose was captured again after a fit.
    pub fn accepted(&self, k: usize) -> Option<&Attempt> {
        self.attempts[k].iter().rev().find(|a| a.accepted)
    }

    /// The capture judged last: (pose, index into its attempts).
    pub fn last_capture(&self) -> Option<(usize, usize)> {
        self.last_capture
    }

    /// Recent messages, oldest first.
    pub fn messages(&self) -> impl Iterator<Item = &str> {
        self.messages.iter().map(String::as_str)
    }

    /// Messages said so far (the line console prints the new ones).
    pub fn said(&self) -> u64 {
        self.said
    }

    /// Add a message.
    pub fn say(&mut self, text: impl Into<String>) {
        if self.messages.len() == MESSAGES_KEPT {
            self.messages.pop_front();
        }
        self.messages.push_back(text.into());
        self.said += 1;
    }

    /// A glove frame received at `now_ns` (already logged at that time).
    pub fn frame(&mut self, points: Vec<Point3<f64>>, now_ns: i64) -> Vec<Effect> {
        let mut effects = Vec::new();
        if self.phase == PosePhase::WaitingGlove {
            effects.push(Effect::Log {
                at_ns: now_ns,
                event: json!({"event": "start", "session": "calibration"}),
            });
            self.say("glove streaming: the session starts");
            effects.extend(self.begin_attempt(0, 1, now_ns));
        }
        effects.extend(self.tick(now_ns));
        match self.phase {
            PosePhase::Settling { .. } => self.settle_frames += 1,
            PosePhase::Capturing { .. } => self.frames.push(points),
            _ => {}
        }
        effects
    }

    /// Time passes: a settling ends, a capture closes.
    pub fn tick(&mut self, now_ns: i64) -> Vec<Effect> {
        let mut effects = Vec::new();
        match self.phase {
            PosePhase::Settling {
                pose,
                attempt,
                since_ns,
                capture_ns,
            } if now_ns >= capture_ns => {
                let settled_s = (now_ns - since_ns) as f64 * 1e-9;
                self.expected_frames = (self.settle_frames > 0 && settled_s > 0.0).then(|| {
                    (self.settle_frames as f64 / settled_s * self.timing.capture_s).round() as usize
                });
                self.frames.clear();
                self.phase = PosePhase::Capturing {
                    pose,
                    attempt,
                    start_ns: now_ns,
                    end_ns: now_ns + ns(self.timing.capture_s),
                };
                effects.push(self.log(
                    now_ns,
                    capture_event(&self.poses[pose].name, true),
                    attempt,
                ));
            }
            PosePhase::Capturing {
                pose,
                attempt,
                end_ns,
                ..
            } if now_ns >= end_ns => {
                let name = self.poses[pose].name.clone();
                effects.push(self.log(now_ns, capture_event(&name, false), attempt));
                let frames = std::mem::take(&mut self.frames);
                let quality = measure(
                    &name,
                    self.layout,
                    &frames,
                    &self.thresholds,
                    self.expected_frames,
                );
                let mut event = quality.to_json();
                event["event"] = QUALITY_EVENT.into();
                event["pose"] = name.clone().into();
                event["attempt"] = attempt.into();
                effects.push(Effect::Log {
                    at_ns: now_ns,
                    event,
                });
                self.say(format!("{name} capture {attempt}: {}", quality.meter()));
                let level = quality.level;
                self.attempts[pose].push(Attempt {
                    quality,
                    accepted: false,
                });
                self.last_capture = Some((pose, self.attempts[pose].len() - 1));
                effects.extend(self.judge(pose, attempt, level, now_ns));
            }
            _ => {}
        }
        effects
    }

    /// An operator action at `now_ns`.
    pub fn act(&mut self, action: CalibrationAction, now_ns: i64) -> Vec<Effect> {
        match (action, self.phase.clone()) {
            (CalibrationAction::Quit, PosePhase::Complete) => {
                vec![Effect::Quit { completed: true }]
            }
            // The session log is finished already: nothing to add to it.
            (CalibrationAction::Quit, PosePhase::Fitting | PosePhase::Failed(_)) => {
                vec![Effect::Quit { completed: false }]
            }
            (CalibrationAction::Quit, _) => self.quit_while_capturing(now_ns),
            (CalibrationAction::Retry, PosePhase::Review { pose, attempt }) => {
                let mut effects = vec![self.decision(pose, attempt, "retry", "operator", now_ns)];
                effects.extend(self.begin_attempt(pose, attempt + 1, now_ns));
                effects
            }
            (CalibrationAction::Accept, PosePhase::Review { pose, attempt }) => {
                let bad = self.attempts[pose]
                    .last()
                    .is_some_and(|a| a.quality.level == QualityLevel::Bad);
                if bad {
                    self.say(format!(
                        "a bad capture cannot be fitted: r captures {} again",
                        self.poses[pose].name
                    ));
                    return Vec::new();
                }
                self.accept(pose, attempt, "operator", now_ns)
            }
            (CalibrationAction::Retry, PosePhase::Complete) => self.redo(now_ns),
            (CalibrationAction::Accept | CalibrationAction::Retry, _) => {
                self.say("nothing to accept or retry now: captures are judged after they end");
                Vec::new()
            }
        }
    }

    /// The fit's progress.
    pub fn fit_progressed(&mut self, progress: FitProgress) {
        self.fit_progress = Some(progress);
    }

    /// The fit ended: `Ok` with what to say and the poses it could not match, or why it
    /// failed. With an operator, the worst pose not matched is offered for a redo.
    pub fn fit_finished(&mut self, outcome: Result<FitDone, String>) -> Vec<Effect> {
        match outcome {
            Ok(done) => {
                for line in done.lines {
                    self.say(line);
                }
                for (_, sentence) in &done.misfits {
                    self.say(sentence.clone());
                }
                self.redo_offer = match self.policy {
                    Policy::Operator => done.misfits.first().map(|(k, _)| *k),
                    Policy::Automatic { .. } => None,
                };
                if let Some(k) = self.redo_offer {
                    self.say(format!(
                        "r captures {} again and fits again; q keeps this fit",
                        self.poses[k].name
                    ));
                }
                self.phase = PosePhase::Complete;
            }
            Err(reason) => {
                self.say(format!("the fit failed: {reason}"));
                self.phase = PosePhase::Failed(reason);
            }
        }
        match self.policy {
            Policy::Automatic { .. } => vec![Effect::Quit {
                completed: self.phase == PosePhase::Complete,
            }],
            Policy::Operator => Vec::new(),
        }
    }

    /// `q` while a pose is being captured: the session is abandoned, or during a redo after
    /// the fit only the redo (the profile of that fit stays; the session counts as complete).
    fn quit_while_capturing(&mut self, now_ns: i64) -> Vec<Effect> {
        let (said, reason) = if self.redoing {
            (
                "quit: the pose is not captured again; the profile of the fit stays",
                "operator quit the redo",
            )
        } else {
            (
                "quit: the session is abandoned (its log is kept)",
                "operator quit",
            )
        };
        self.say(said);
        vec![
            Effect::Log {
                at_ns: now_ns,
                event: json!({"event": "abort", "reason": reason}),
            },
            Effect::Quit {
                completed: self.redoing,
            },
        ]
    }

    /// `r` after the fit: the pose offered is captured again (the log continued first).
    fn redo(&mut self, now_ns: i64) -> Vec<Effect> {
        let Some(k) = self.redo_offer.take() else {
            self.say("nothing to capture again: every pose fits; q quits");
            return Vec::new();
        };
        self.redoing = true;
        let name = self.poses[k].name.clone();
        let attempt = self.attempts[k].len() as u32 + 1;
        let mut effects = vec![
            Effect::ContinueLog,
            Effect::Log {
                at_ns: now_ns,
                event: json!({"event": REDO_EVENT, "pose": name, "attempt": attempt}),
            },
        ];
        self.say(format!("{name} is captured again, then the fit runs again"));
        effects.extend(self.begin_attempt(k, attempt, now_ns));
        effects
    }

    fn judge(
        &mut self,
        pose: usize,
        attempt: u32,
        level: QualityLevel,
        now_ns: i64,
    ) -> Vec<Effect> {
        match (level, self.policy) {
            (QualityLevel::Good, _) | (QualityLevel::Poor, Policy::Automatic { .. }) => {
                self.accept(pose, attempt, "auto", now_ns)
            }
            (QualityLevel::Bad, Policy::Automatic { max_attempts }) => {
                let name = self.poses[pose].name.clone();
                let mut effects = vec![self.decision(pose, attempt, "retry", "auto", now_ns)];
                if attempt >= max_attempts {
                    let reason = format!(
                        "pose '{name}': {attempt} bad captures in a row; check the glove and run the session again"
                    );
                    self.say(reason.clone());
                    effects.push(Effect::Log {
                        at_ns: now_ns,
                        event: json!({"event": "abort", "reason": reason}),
                    });
                    self.phase = PosePhase::Failed(reason);
                    effects.push(Effect::Quit { completed: false });
                    return effects;
                }
                self.say(format!("bad capture: {name} is captured again"));
                effects.extend(self.begin_attempt(pose, attempt + 1, now_ns));
                effects
            }
            (_, Policy::Operator) => {
                self.say(if level == QualityLevel::Bad {
                    "bad capture: r captures the pose again"
                } else {
                    "poor capture: space accepts it, r captures the pose again"
                });
                self.phase = PosePhase::Review { pose, attempt };
                Vec::new()
            }
        }
    }

    fn accept(&mut self, pose: usize, attempt: u32, by: &str, now_ns: i64) -> Vec<Effect> {
        let mut effects = vec![self.decision(pose, attempt, "accepted", by, now_ns)];
        if let Some(last) = self.attempts[pose].last_mut() {
            last.accepted = true;
        }
        if pose + 1 < self.poses.len() && !self.redoing {
            effects.extend(self.begin_attempt(pose + 1, 1, now_ns));
        } else {
            self.say(if self.redoing {
                "captured again: fitting again"
            } else {
                "all poses captured: fitting"
            });
            self.redoing = false;
            self.phase = PosePhase::Fitting;
            effects.push(Effect::Log {
                at_ns: now_ns,
                event: json!({"event": "stop", "summary": self.summary()}),
            });
            effects.push(Effect::Fit { at_ns: now_ns });
        }
        effects
    }

    fn begin_attempt(&mut self, pose: usize, attempt: u32, now_ns: i64) -> Vec<Effect> {
        self.phase = PosePhase::Settling {
            pose,
            attempt,
            since_ns: now_ns,
            capture_ns: now_ns + ns(self.timing.settle_s),
        };
        self.settle_frames = 0;
        let step = &self.poses[pose];
        let event = pose_event(&step.name, &step.instruction);
        let effects = vec![Effect::Command(pose), self.log(now_ns, event, attempt)];
        self.say(format!(
            "[{}/{}] {}{}: {}",
            pose + 1,
            self.poses.len(),
            step.name,
            if attempt > 1 {
                format!(" (capture {attempt})")
            } else {
                String::new()
            },
            step.instruction
        ));
        effects
    }

    fn log(&self, at_ns: i64, mut event: Value, attempt: u32) -> Effect {
        event["attempt"] = attempt.into();
        Effect::Log { at_ns, event }
    }

    fn decision(&self, pose: usize, attempt: u32, decision: &str, by: &str, now_ns: i64) -> Effect {
        Effect::Log {
            at_ns: now_ns,
            event: json!({
                "event": DECISION_EVENT,
                "pose": self.poses[pose].name,
                "attempt": attempt,
                "decision": decision,
                "by": by,
            }),
        }
    }

    fn summary(&self) -> Value {
        let per_pose: Vec<Value> = self
            .poses
            .iter()
            .zip(&self.attempts)
            .map(|(p, a)| {
                json!({
                    "pose": p.name,
                    "captures": a.len(),
                    "accepted": a.iter().rposition(|x| x.accepted).map(|i| i + 1),
                })
            })
            .collect();
        json!({ "poses": per_pose })
    }
}

#[cfg(test)]
#[path = "pose_session_tests.rs"]
mod tests;
