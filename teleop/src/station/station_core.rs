//! The station's control step, synchronous and clock-free: frames in, commands out.
//!
//! The ROS adapter feeds it keypoint frames with their receive times (and their senders' source
//! stamps) and calls [`StationCore::tick`] at the configured rate (or on every new frame); tests
//! drive it directly. It owns the source order, the frame gate, the watchdog and the
//! retargeter, and keeps the counters the status topic reports.

use std::collections::BTreeMap;

use nalgebra::Point3;
use retarget::{Retargeter, SolveStatus};
use serde::Serialize;

use crate::station::frame_gate::{FrameGate, Rejection, Verdict};
use crate::station::source_order::{SourceOrder, StampOrder};
use crate::station::watchdog::{DriveState, Watchdog};

/// Longest time step handed to the retargeter, seconds (its rate limit caps it anyway).
const MAX_DT_S: f64 = 0.5;
/// Shortest time step handed to the retargeter, seconds.
const MIN_DT_S: f64 = 1e-4;

/// The hand command of one tick.
#[derive(Debug, Clone, PartialEq)]
pub struct HandCommand {
    /// Joint targets, radians, in the model's degree-of-freedom order.
    pub q: Vec<f64>,
    /// True when this repeats an earlier command (held, no fresh frame).
    pub held: bool,
    /// Receive time of the keypoint frame behind the command, nanoseconds.
    pub frame_received_ns: i64,
}

/// Counters and the latest solver figures, for the status topic.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Counters {
    /// New (changed, accepted) keypoint frames.
    pub frames_new: u64,
    /// Repeated frames (same keypoints as the last accepted one).
    pub frames_repeated: u64,
    /// Rejected frames by reason.
    pub rejected: BTreeMap<String, u64>,
    /// Frames whose sender's clock had jumped (back beyond the reorder window, or ahead beyond
    /// what the receive clock explains); they were accepted.
    pub source_clock_jumps: u64,
    /// Frames retargeted.
    pub solves: u64,
    /// Solves that ended on the step budget.
    pub solves_step_limit: u64,
    /// Solves with a failed QP (best iterate used).
    pub solves_qp_failed: u64,
    /// Interior-point time of the last solve, microseconds.
    pub last_qp_time_us: f64,
    /// Mean palm-to-tip error of the last solve, millimetres.
    pub last_tip_error_mm: f64,
}

/// What one tick produced.
#[derive(Debug, Clone, PartialEq)]
pub struct Tick {
    /// The drive state after this tick.
    pub state: DriveState,
    /// The hand command to publish, if any.
    pub hand: Option<HandCommand>,
}

/// The control step.
#[derive(Debug)]
pub struct StationCore {
    retargeter: Retargeter,
    order: SourceOrder,
    gate: FrameGate,
    watchdog: Watchdog,
    pending: Option<(Vec<Point3<f64>>, i64)>,
    last_solved_ns: Option<i64>,
    last_command: Option<HandCommand>,
    counters: Counters,
}

impl StationCore {
    /// A station around a configured retargeter, gate and watchdog.
    pub fn new(retargeter: Retargeter, gate: FrameGate, watchdog: Watchdog) -> StationCore {
        let mut counters = Counters::default();
        for reason in Rejection::ALL {
            counters.rejected.insert(rejection_name(reason).into(), 0);
        }
        StationCore {
            retargeter,
            order: SourceOrder::new(gate.config().reorder_window_ms),
            gate,
            watchdog,
            pending: None,
            last_solved_ns: None,
            last_command: None,
            counters,
        }
    }

    /// The retargeter (model, configuration).
    pub fn retargeter(&self) -> &Retargeter {
        &self.retargeter
    }

    /// The counters.
    pub fn counters(&self) -> &Counters {
        &self.counters
    }

    /// The drive state as of the last tick.
    pub fn state(&self) -> DriveState {
        self.watchdog.state()
    }

    /// Age of the newest frame at `now_ns`.
    pub fn input_age_ns(&self, now_ns: i64) -> Option<i64> {
        self.watchdog.age_ns(now_ns)
    }

    /// A keypoint frame without a source stamp arrived at `received_ns`.
    pub fn on_keypoints(&mut self, points: &[Point3<f64>], received_ns: i64) -> Verdict {
        self.on_stamped_keypoints(points, None, received_ns)
    }

    /// A keypoint frame stamped `source_ns` by its sender (the DDS source time, when there is
    /// one) arrived at `received_ns`. A frame stamped before the newest accepted one is late
    /// and rejected (`out_of_order`); a jump of the sender's clock is counted and followed
    /// (see [`source_order`](crate::station::source_order)). Then the frame gate decides.
    pub fn on_stamped_keypoints(
        &mut self,
        points: &[Point3<f64>],
        source_ns: Option<i64>,
        received_ns: i64,
    ) -> Verdict {
        let order = source_ns.map(|s| (s, self.order.check(s, received_ns)));
        if let Some((_, StampOrder::Late)) = order {
            self.count_rejection(Rejection::OutOfOrder);
            return Verdict::Rejected(Rejection::OutOfOrder);
        }
        let verdict = self.gate.judge(points);
        if let (Some((source, stamp)), Verdict::New | Verdict::Repeat) = (order, verdict) {
            self.order.accept(source, received_ns);
            if stamp == StampOrder::ClockJump {
                self.counters.source_clock_jumps += 1;
            }
        }
        match verdict {
            Verdict::New => {
                self.counters.frames_new += 1;
                self.watchdog.frame(received_ns);
                self.pending = Some((points.to_vec(), received_ns));
            }
            Verdict::Repeat => self.counters.frames_repeated += 1,
            Verdict::Rejected(reason) => self.count_rejection(reason),
        }
        verdict
    }

    /// The operator engages; granted with fresh input. Returns whether engaged.
    pub fn engage(&mut self, now_ns: i64) -> bool {
        let engaged = self.watchdog.engage(now_ns);
        if engaged {
            // Resume from the last command, not from a stale time step.
            self.last_solved_ns = None;
        }
        engaged
    }

    /// The operator disengages.
    pub fn disengage(&mut self) {
        self.watchdog.disengage();
    }

    /// One control step at `now_ns`.
    pub fn tick(&mut self, now_ns: i64) -> Tick {
        let state = self.watchdog.update(now_ns);
        let hand = match state {
            DriveState::Engaged => match self.pending.take() {
                Some((points, received_ns)) => {
                    self.solve(&points, received_ns).or_else(|| self.held())
                }
                None => self.last_command.clone(),
            },
            DriveState::Held | DriveState::Disengaged => {
                self.pending = None;
                self.held()
            }
        };
        Tick { state, hand }
    }

    fn held(&self) -> Option<HandCommand> {
        self.last_command.as_ref().map(|c| HandCommand {
            held: true,
            ..c.clone()
        })
    }

    fn solve(&mut self, points: &[Point3<f64>], received_ns: i64) -> Option<HandCommand> {
        let dt_s = self
            .last_solved_ns
            .map_or(0.04, |t| (received_ns - t) as f64 * 1e-9)
            .clamp(MIN_DT_S, MAX_DT_S);
        match self.retargeter.retarget(points, dt_s) {
            Ok(solution) => {
                self.last_solved_ns = Some(received_ns);
                self.counters.solves += 1;
                match solution.status {
                    SolveStatus::StepLimit => self.counters.solves_step_limit += 1,
                    SolveStatus::QpFailed(_) => self.counters.solves_qp_failed += 1,
                    SolveStatus::Converged => {}
                }
                self.counters.last_qp_time_us = solution.qp_time_s * 1e6;
                self.counters.last_tip_error_mm = solution.tip_error_m * 1e3;
                let command = HandCommand {
                    q: solution.q,
                    held: false,
                    frame_received_ns: received_ns,
                };
                self.last_command = Some(command.clone());
                Some(command)
            }
            Err(_) => {
                self.count_rejection(Rejection::Retargeter);
                None
            }
        }
    }

    fn count_rejection(&mut self, reason: Rejection) {
        *self
            .counters
            .rejected
            .entry(rejection_name(reason).into())
            .or_default() += 1;
    }
}

/// Name of a rejection reason in the status.
pub fn rejection_name(reason: Rejection) -> &'static str {
    match reason {
        Rejection::WrongSize => "wrong_size",
        Rejection::NonFinite => "non_finite",
        Rejection::BoneLength => "bone_length",
        Rejection::Jump => "jump",
        Rejection::Retargeter => "retargeter",
        Rejection::OutOfOrder => "out_of_order",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::station::frame_gate::GateConfig;
    use crate::station::watchdog::WatchdogConfig;
    use retarget::{EmbodimentCatalog, HandModel, KeypointLayout, RetargetConfig};

    const MS: i64 = 1_000_000;

    fn station() -> (HandModel, StationCore) {
        let model = HandModel::orca_v1_right();
        let retargeter = Retargeter::new(
            model.clone(),
            RetargetConfig::default(),
            &EmbodimentCatalog::builtin(),
        )
        .unwrap();
        let core = StationCore::new(
            retargeter,
            FrameGate::new(KeypointLayout::Lab22, GateConfig::default()),
            Watchdog::new(WatchdogConfig::default()),
        );
        (model, core)
    }

    fn frame(model: &HandModel, index_mcp: f64) -> Vec<Point3<f64>> {
        let mut q = model.zero_pose();
        q[model.dof_index("index_mcp").unwrap()] = index_mcp;
        model.synthetic_keypoints(&model.forward_new(&q).unwrap(), KeypointLayout::Lab22)
    }

    #[test]
    fn nothing_moves_before_engage_then_commands_follow_new_frames() {
        let (model, mut core) = station();
        assert_eq!(core.on_keypoints(&frame(&model, 0.2), 0), Verdict::New);
        let tick = core.tick(MS);
        assert_eq!(tick.state, DriveState::Disengaged);
        assert_eq!(tick.hand, None);
        assert!(core.engage(2 * MS));
        core.on_keypoints(&frame(&model, 0.3), 40 * MS);
        let tick = core.tick(41 * MS);
        let hand = tick.hand.unwrap();
        assert!(!hand.held);
        assert_eq!(hand.frame_received_ns, 40 * MS);
        // Repeats are counted, not solved again.
        core.on_keypoints(&frame(&model, 0.3), 45 * MS);
        assert_eq!(core.counters().frames_repeated, 1);
        assert_eq!(core.counters().solves, 1);
    }

    #[test]
    fn stale_input_holds_the_last_command_then_disengages() {
        let (model, mut core) = station();
        core.on_keypoints(&frame(&model, 0.2), 0);
        core.engage(MS);
        let first = core.tick(2 * MS).hand.unwrap();
        let held = core.tick(200 * MS);
        assert_eq!(held.state, DriveState::Held);
        assert_eq!(held.hand.as_ref().unwrap().q, first.q);
        assert!(held.hand.unwrap().held);
        assert_eq!(core.tick(1100 * MS).state, DriveState::Disengaged);
        // Fresh input alone does not resume.
        core.on_keypoints(&frame(&model, 0.5), 1200 * MS);
        let tick = core.tick(1201 * MS);
        assert_eq!(tick.state, DriveState::Disengaged);
        assert_eq!(tick.hand.unwrap().q, first.q);
    }

    #[test]
    fn malformed_frames_are_counted_and_change_nothing() {
        let (model, mut core) = station();
        core.on_keypoints(&frame(&model, 0.2), 0);
        core.engage(MS);
        let before = core.tick(2 * MS).hand.unwrap();
        let mut nan = frame(&model, 0.4);
        nan[5].x = f64::NAN;
        core.on_keypoints(&nan, 10 * MS);
        core.on_keypoints(&nan[..21], 11 * MS);
        let after = core.tick(12 * MS).hand.unwrap();
        assert_eq!(after.q, before.q);
        assert_eq!(core.counters().rejected["non_finite"], 1);
        assert_eq!(core.counters().rejected["wrong_size"], 1);
    }

    #[test]
    fn late_frames_are_rejected_and_clock_jumps_followed() {
        let (model, mut core) = station();
        let stamped = |core: &mut StationCore, q: f64, source_ms: i64, received_ms: i64| {
            core.on_stamped_keypoints(&frame(&model, q), Some(source_ms * MS), received_ms * MS)
        };
        assert_eq!(stamped(&mut core, 0.2, 100, 0), Verdict::New);
        core.engage(MS);
        let first = core.tick(2 * MS).hand.unwrap();
        assert_eq!(stamped(&mut core, 0.3, 120, 20), Verdict::New);
        // Sent before the frame at 120: late, whatever its keypoints.
        assert_eq!(
            stamped(&mut core, 0.4, 110, 21),
            Verdict::Rejected(Rejection::OutOfOrder)
        );
        let tick = core.tick(22 * MS).hand.unwrap();
        assert_eq!(
            tick.frame_received_ns,
            20 * MS,
            "the late frame was not solved"
        );
        assert_ne!(tick.q, first.q);
        assert_eq!(core.counters().rejected["out_of_order"], 1);
        // The same stamp again with the same keypoints: a repeat, not late.
        assert_eq!(stamped(&mut core, 0.3, 120, 23), Verdict::Repeat);
        // The sender's clock jumps back an hour: followed, counted.
        assert_eq!(stamped(&mut core, 0.35, 140 - 3_600_000, 40), Verdict::New);
        assert_eq!(core.counters().source_clock_jumps, 1);
        assert_eq!(stamped(&mut core, 0.4, 160 - 3_600_000, 60), Verdict::New);
        assert_eq!(core.counters().rejected["out_of_order"], 1);
        assert_eq!(core.tick(61 * MS).state, DriveState::Engaged);
    }
}
