//! The station: one state machine, driven by [`Station::step`] with an input and its receive
//! time, giving back the messages to send. No clock, no I/O: the ROS node, the
//! re-simulation, the evaluation and the consoles feed it and carry out what it returns, so a
//! recorded run (every input with its receive time) re-simulates to the same commands.
//!
//! ```text
//!  input (receive time)        what happens
//!  ───────────────────────     ──────────────────────────────────────────────────────────────
//!  keypoint frame              source order → frame gate → watchdog; a new frame is pending;
//!                              auto-engage (once); on_arrival: retarget it now unless it is
//!                              stamped within 1/max_command_rate_hz of the last commanded one
//!  wrist pose, arm feedback    kept (an invalid wrist pose is counted and ignored)
//!  tick (control.rate_hz)      watchdog; rate mode: retarget the pending frame or repeat the
//!                              command; on_arrival: retarget a frame the ceiling held back;
//!                              held/disengaged: repeat the held command; the arm steps
//!  engage, disengage           the watchdog's operator side
//!  arm blocked                 no arm targets while another publisher drives the arm topic
//! ```
//!
//! In a human study (embodiment [`HUMAN_EMBODIMENT`](crate::HUMAN_EMBODIMENT)) there is no
//! robot: frames still pass the source order, frame gate and watchdog (the status shows the
//! glove's rate, age and rejections), but nothing engages, nothing is retargeted and no hand
//! or arm message is sent.

use msgs::Pose;
use retarget::{CalibrationTransform, HandModel, Retargeter};
use serde::Serialize;

use crate::arm::Constraint;
use crate::convert::pose_to_isometry;
use crate::frame_gate::{FrameGate, GateDecision};
use crate::hand_control::{Counters, HandCommand, HandControl, KeypointFrame};
use crate::input_gap::{GapMeter, InputGap};
use crate::output_stage::{ArmInputs, ArmStep, OutputStage};
use crate::rate_meter::RateMeter;
use crate::retargeter_setup::build_retargeter;
use crate::station_config::{ControlConfig, ControlMode, StationConfig};
use crate::station_error::StationError;
use crate::station_input::{ControlInput, Notice, StationInput, StationOutputs};
use crate::watchdog::{DriveState, Watchdog};

/// Window of the status rates, seconds.
const RATE_WINDOW_S: f64 = 1.0;

/// What the station sent and refused, beyond the hand's counters.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Totals {
    /// Hand commands sent (fresh, repeated and held).
    pub hand_commands: u64,
    /// Hand commands repeated because the glove input went stale (held, not yet disengaged):
    /// each is a control step the glove did not drive.
    pub held_commands: u64,
    /// Arm targets sent.
    pub arm_targets: u64,
    /// Wrist poses refused (non-finite, non-unit quaternion).
    pub wrist_rejected: u64,
    /// Arm steps refused by the arm mapping, by reason (the arm held: nothing was sent).
    pub arm_refused: std::collections::BTreeMap<String, u64>,
    /// Times the arm clutch could not engage.
    pub arm_engage_failed: u64,
}

/// Rates over the last second.
#[derive(Debug, Clone)]
struct Meters {
    input: RateMeter,
    gaps: GapMeter,
    repeat: RateMeter,
    output: RateMeter,
}

/// The station's part of the status topic (the application adds what only it knows:
/// listeners, publish failures, step times).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StationStatus {
    /// The drive state.
    pub state: DriveState,
    /// New glove frames per second.
    pub input_rate_hz: f64,
    /// Repeated glove frames per second.
    pub repeat_rate_hz: f64,
    /// Hand commands per second.
    pub output_rate_hz: f64,
    /// Age of the newest new frame, milliseconds.
    pub input_age_ms: Option<f64>,
    /// The longest gap between new frames so far, as received and as sent ([`InputGap`]).
    pub longest_input_gap: Option<InputGap>,
    /// Whether the sender's stamps have stopped advancing: frames are timed by their receive
    /// times until they advance again (`counters.frames_timed_by_receipt`).
    pub source_clock_frozen: bool,
    /// Frame and solver counters.
    pub counters: Counters,
    /// What was sent and refused.
    #[serde(flatten)]
    pub totals: Totals,
    /// The arm.
    pub arm: ArmStatus,
}

/// The arm's part of the status.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ArmStatus {
    /// Whether the station drives an arm.
    pub enabled: bool,
    /// Whether the arm clutch is engaged.
    pub engaged: bool,
    /// Whether another publisher drives the arm command topic.
    pub second_publisher: bool,
    /// The task constraint.
    pub constraint: Constraint,
}

/// The station.
#[derive(Debug)]
pub struct Station {
    hand: HandControl,
    output: OutputStage,
    arm_inputs: ArmInputs,
    control: ControlConfig,
    /// False in a human study: no retargeting, no engaging, no hand or arm messages.
    drives_robot: bool,
    auto_engage_pending: bool,
    meters: Meters,
    totals: Totals,
}

impl Station {
    /// A station for `config` driving `model`, with a user's calibration if given. Checks the
    /// configuration first.
    pub fn new(
        config: &StationConfig,
        model: HandModel,
        calibration: Option<CalibrationTransform>,
    ) -> Result<Station, StationError> {
        config.validate()?;
        let output = OutputStage::new(config, &model)?;
        let drives_robot = config.drives_robot();
        let retargeter = if drives_robot {
            Some(
                build_retargeter(model, config.retarget.clone(), calibration)
                    .map_err(|e| StationError::Retargeter(e.into_cause()))?,
            )
        } else {
            None
        };
        let hand = HandControl::new(
            retargeter,
            FrameGate::new(config.retarget.layout, config.gate.clone()),
            Watchdog::new(config.watchdog.clone()),
        );
        Ok(Station {
            hand,
            output,
            arm_inputs: ArmInputs {
                glove_wrist: None,
                robot_pose: None,
                blocked: false,
            },
            control: config.control.clone(),
            drives_robot,
            auto_engage_pending: config.control.auto_engage && drives_robot,
            meters: Meters {
                input: RateMeter::new(RATE_WINDOW_S),
                gaps: GapMeter::default(),
                repeat: RateMeter::new(RATE_WINDOW_S),
                output: RateMeter::new(RATE_WINDOW_S),
            },
            totals: Totals::default(),
        })
    }

    /// The retargeter (model, configuration); `None` in a human study.
    pub fn retargeter(&self) -> Option<&Retargeter> {
        self.hand.retargeter()
    }

    /// Whether this station drives a robot (false in a human study, embodiment
    /// [`HUMAN_EMBODIMENT`](crate::HUMAN_EMBODIMENT)).
    pub fn drives_robot(&self) -> bool {
        self.drives_robot
    }

    /// The hand's counters.
    pub fn counters(&self) -> &Counters {
        self.hand.counters()
    }

    /// What was sent and refused.
    pub fn totals(&self) -> &Totals {
        &self.totals
    }

    /// The drive state.
    pub fn state(&self) -> DriveState {
        self.hand.state()
    }

    /// The hand command in force (the last one computed), if any.
    pub fn command_in_force(&self) -> Option<&HandCommand> {
        self.hand.last_command()
    }

    /// Whether arm targets are withheld (another publisher drives the arm topic).
    pub fn arm_blocked(&self) -> bool {
        self.arm_inputs.blocked
    }

    /// The longest gap between new frames so far, as received and as sent.
    pub fn longest_input_gap(&self) -> Option<InputGap> {
        self.meters.gaps.longest()
    }

    /// Age of the newest new frame at `now_ns`.
    pub fn input_age_ns(&self, now_ns: i64) -> Option<i64> {
        self.hand.input_age_ns(now_ns)
    }

    /// One step: `input`, received at `now_ns` (nanoseconds on the application's one clock).
    pub fn step(&mut self, input: StationInput, now_ns: i64) -> StationOutputs {
        match input {
            StationInput::Keypoints(frame) => self.on_keypoints(frame, now_ns),
            StationInput::Wrist(pose) => {
                self.on_wrist(&pose);
                StationOutputs::default()
            }
            StationInput::ArmFeedback(pose) => {
                if let Some(robot) = pose_to_isometry(&pose) {
                    self.arm_inputs.robot_pose = Some(robot);
                }
                StationOutputs::default()
            }
            StationInput::Control(control) => self.on_control(control, now_ns),
        }
    }

    /// The status at `now_ns`.
    pub fn status(&mut self, now_ns: i64) -> StationStatus {
        StationStatus {
            state: self.hand.state(),
            input_rate_hz: self.meters.input.rate_hz(now_ns),
            repeat_rate_hz: self.meters.repeat.rate_hz(now_ns),
            output_rate_hz: self.meters.output.rate_hz(now_ns),
            input_age_ms: self.hand.input_age_ns(now_ns).map(|a| a as f64 * 1e-6),
            longest_input_gap: self.meters.gaps.longest(),
            source_clock_frozen: self.hand.source_clock_frozen(),
            counters: self.hand.counters().clone(),
            totals: self.totals.clone(),
            arm: ArmStatus {
                enabled: self.drives_robot && self.output.arm_enabled(),
                engaged: self.output.arm().is_engaged(),
                second_publisher: self.arm_inputs.blocked,
                constraint: self.output.arm().constraint(),
            },
        }
    }

    fn on_wrist(&mut self, pose: &Pose) {
        match pose_to_isometry(pose) {
            Some(wrist) => self.arm_inputs.glove_wrist = Some(wrist),
            // The last valid pose stays: the arm holds where it is.
            None => self.totals.wrist_rejected += 1,
        }
    }

    fn on_keypoints(&mut self, frame: KeypointFrame, now_ns: i64) -> StationOutputs {
        let source_ns = frame.source_ns;
        let verdict = self.hand.take_frame(frame, now_ns);
        let mut outputs = StationOutputs {
            verdict: Some(verdict),
            ..StationOutputs::default()
        };
        match verdict {
            GateDecision::New | GateDecision::Repaired => {
                self.meters.input.record(now_ns);
                self.meters.gaps.record(now_ns, source_ns);
                if self.auto_engage_pending && self.hand.engage(now_ns) {
                    self.auto_engage_pending = false;
                }
                if self.control.mode == ControlMode::OnArrival
                    && self.under_ceiling(source_ns, now_ns)
                    && self.hand.update(now_ns) == DriveState::Engaged
                {
                    self.command_fresh(now_ns, &mut outputs);
                }
            }
            GateDecision::Repeat => self.meters.repeat.record(now_ns),
            GateDecision::Rejected(_) => {}
        }
        outputs
    }

    /// Whether a frame stamped `source_ns` may be commanded now: at least
    /// `1 / max_command_rate_hz` after the last commanded frame by the senders' stamps (a
    /// backwards stamp, after a sender's clock jump, always may). Stamps are the sender's and
    /// may lie anywhere in `i64`: the difference saturates. While the sender's clock is frozen
    /// the receive times count instead.
    fn under_ceiling(&self, source_ns: i64, received_ns: i64) -> bool {
        let min_interval_ns = (1e9 / self.control.max_command_rate_hz) as i64;
        if self.hand.source_clock_frozen() {
            return self
                .hand
                .last_solved_received_ns()
                .is_none_or(|last| received_ns.saturating_sub(last) >= min_interval_ns);
        }
        self.hand.last_solved_source_ns().is_none_or(|last| {
            source_ns.saturating_sub(last) >= min_interval_ns || source_ns < last
        })
    }

    fn on_control(&mut self, control: ControlInput, now_ns: i64) -> StationOutputs {
        let mut outputs = StationOutputs::default();
        match control {
            ControlInput::Tick => self.on_tick(now_ns, &mut outputs),
            ControlInput::Engage => {
                if self.drives_robot {
                    self.hand.engage(now_ns);
                }
            }
            ControlInput::Disengage => {
                self.hand.disengage();
                self.output.disengage();
            }
            ControlInput::ArmBlocked { blocked } => {
                if blocked && !self.arm_inputs.blocked {
                    outputs.notices.push(Notice::ArmBlocked);
                }
                self.arm_inputs.blocked = blocked;
            }
        }
        outputs
    }

    fn on_tick(&mut self, now_ns: i64, outputs: &mut StationOutputs) {
        let state = self.hand.update(now_ns);
        if !self.drives_robot {
            return;
        }
        match (state, self.control.mode) {
            (DriveState::Engaged, ControlMode::Rate) => {
                if !self.command_fresh(now_ns, outputs) {
                    self.send_hand(self.hand.last_command().cloned(), now_ns, outputs);
                }
            }
            (DriveState::Engaged, ControlMode::OnArrival) => {
                // A frame the ceiling held back, if no newer one came since.
                self.command_fresh(now_ns, outputs);
            }
            (DriveState::Held | DriveState::Disengaged, _) => {
                let held = self.hand.held();
                if state == DriveState::Held && held.is_some() {
                    self.totals.held_commands += 1;
                }
                self.send_hand(held, now_ns, outputs);
            }
        }
        self.step_arm(state, now_ns, outputs);
    }

    /// Retarget the pending frame, if any, and send the command; whether one was sent. The
    /// caller has advanced the watchdog and found the station engaged.
    fn command_fresh(&mut self, now_ns: i64, outputs: &mut StationOutputs) -> bool {
        let Some(command) = self.hand.command_pending() else {
            return false;
        };
        outputs.fresh_frame_received_ns = Some(command.frame_received_ns);
        self.send_hand(Some(command), now_ns, outputs);
        true
    }

    fn send_hand(
        &mut self,
        command: Option<HandCommand>,
        now_ns: i64,
        outputs: &mut StationOutputs,
    ) {
        if let Some(command) = command {
            outputs.hand = Some(self.output.hand_messages(&command, now_ns));
            self.totals.hand_commands += 1;
            self.meters.output.record(now_ns);
        }
    }

    fn step_arm(&mut self, state: DriveState, now_ns: i64, outputs: &mut StationOutputs) {
        let (step, engage_error) = self.output.arm_step(state, self.arm_inputs, now_ns);
        if let Some(error) = engage_error {
            self.totals.arm_engage_failed += 1;
            outputs.notices.push(Notice::ArmNotEngaged(error));
        }
        match step {
            ArmStep::Idle => {}
            ArmStep::Target(target) => {
                self.totals.arm_targets += 1;
                outputs.arm = Some(target);
            }
            ArmStep::Refused(error) => {
                *self
                    .totals
                    .arm_refused
                    .entry(error.name().to_string())
                    .or_default() += 1;
            }
        }
    }
}

#[cfg(test)]
#[path = "station_tests.rs"]
mod tests;
