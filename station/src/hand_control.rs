//! The hand side of the station: which glove frames are taken, when the retargeter runs, and
//! the command it gave.
//!
//! A keypoint frame goes through the source order (late frames are turned away), the frame
//! gate (repeats and implausible frames) and the watchdog (freshness); a new frame is kept as
//! the pending one, and `HandControl::command` retargets it. The time step handed to the
//! retargeter comes from the frames' own stamps (their senders' clocks), so frames delivered
//! together by a busy network keep the spacing at which they were captured; after a jump of the
//! sender's clock (at any frame taken since the last retargeted one, a repeat or a superseded
//! frame included) the receive times stand in for one step.

use std::collections::BTreeMap;

use nalgebra::Point3;
use retarget::{Retargeter, SolveStatus};
use serde::Serialize;

use crate::frame_gate::{FrameGate, GateDecision, Rejection};
use crate::source_order::{SourceOrder, StampOrder};
use crate::watchdog::{DriveState, Watchdog};

/// Longest time step handed to the retargeter, seconds (its rate limit caps it anyway).
const MAX_DT_S: f64 = 0.5;
/// Shortest time step handed to the retargeter, seconds.
const MIN_DT_S: f64 = 1e-4;
/// Time step of the first frame after engage, seconds (the glove's ~25 Hz).
const FIRST_DT_S: f64 = 0.04;

/// New frames in a row stamped no later than the new frame before them after which the
/// sender's clock counts as frozen: time steps and the command ceiling then go by receive
/// times until its stamps advance again. (Taken by their equal stamps, the frames would be
/// [`MIN_DT_S`] apart, and the joint-speed limit would all but stop the hand.)
pub const FROZEN_CLOCK_AFTER: u32 = 3;

/// The time step the retargeter is given for a frame stamped `next_ns` after the frame it
/// last solved, stamped `previous_ns` (the sender's stamps, or the receive times across a
/// clock jump): their difference, within [`MIN_DT_S`, `MAX_DT_S`]. Frames stamped a
/// microsecond apart are a microsecond apart to the joint-speed limit too.
pub fn time_step_between(previous_ns: i64, next_ns: i64) -> f64 {
    // The sender's stamps may lie anywhere in i64 (saturated; clamped anyway).
    (next_ns.saturating_sub(previous_ns) as f64 * 1e-9).clamp(MIN_DT_S, MAX_DT_S)
}

/// A keypoint frame as the station received it.
#[derive(Debug, Clone, PartialEq)]
pub struct KeypointFrame {
    /// The keypoints, metres, in the layout's order.
    pub points: Vec<Point3<f64>>,
    /// The sender's stamp (the DDS source time; the receive time when the sender gives none),
    /// nanoseconds.
    pub source_ns: i64,
}

/// The hand command in force.
#[derive(Debug, Clone, PartialEq)]
pub struct HandCommand {
    /// Joint targets, radians, in the model's degree-of-freedom order.
    pub q: Vec<f64>,
    /// True when this repeats an earlier command (held, no fresh frame).
    pub held: bool,
    /// Receive time of the keypoint frame behind the command, nanoseconds.
    pub frame_received_ns: i64,
    /// Source stamp of the keypoint frame behind the command, nanoseconds.
    pub frame_source_ns: i64,
}

/// The QP work of the last solve: which method ran, how often, how many iterations.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct QpReport {
    /// QPs the exact active-set method solved.
    pub active_set: u32,
    /// QPs Clarabel solved (every QP with `solver.qp_method = "clarabel"`; otherwise the
    /// active set's fallbacks).
    pub clarabel: u32,
    /// Active-set changes plus interior-point iterations, over the frame's QPs.
    pub iterations: u32,
    /// Clarabel's own solve time, microseconds (the active set keeps no clock: the station's
    /// step time is measured by the application around the whole step).
    pub clarabel_time_us: f64,
}

/// Counters and the latest solver figures, for the status topic.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Counters {
    /// New (changed, accepted) keypoint frames.
    pub frames_new: u64,
    /// Repeated frames (same keypoints as the last accepted one).
    pub frames_repeated: u64,
    /// New frames in which one point leapt alone (a tracker's outlier) and was put back where
    /// the rest of the hand predicts it; also counted in `frames_new`.
    pub frames_repaired: u64,
    /// Rejected frames by reason.
    pub rejected: BTreeMap<String, u64>,
    /// Frames whose sender's clock had jumped (back beyond the reorder window, or ahead beyond
    /// what the receive clock explains); they were accepted.
    pub source_clock_jumps: u64,
    /// New frames timed by their receive times because the sender's stamps had stopped
    /// advancing (`FROZEN_CLOCK_AFTER`).
    pub frames_timed_by_receipt: u64,
    /// New frames replaced by a newer one before they were retargeted (above the command-rate
    /// ceiling, or between two ticks with `mode = "rate"`).
    pub frames_superseded: u64,
    /// Frames retargeted.
    pub solves: u64,
    /// Solves that ended on the step budget.
    pub solves_step_limit: u64,
    /// Solves with a failed QP (best iterate used).
    pub solves_qp_failed: u64,
    /// The QP work of the last solve.
    pub last_qp: QpReport,
    /// Mean palm-to-tip error of the last solve, millimetres.
    pub last_tip_error_mm: f64,
}

/// The frame taken and not yet retargeted.
#[derive(Debug, Clone)]
struct PendingFrame {
    frame: KeypointFrame,
    received_ns: i64,
    /// The sender's clock jumps counted when it was taken: more than at the last retargeted
    /// frame, and the two frames' stamps cannot be compared (the jump may have come at this
    /// frame, or at a repeat or a superseded frame between the two).
    clock_jumps: u64,
    /// The sender's clock was frozen when it was taken: its time step goes by receive times.
    clock_frozen: bool,
}

/// The hand side of the station.
#[derive(Debug)]
pub struct HandControl {
    /// `None` in a human study: frames are judged and timed, never retargeted.
    retargeter: Option<Retargeter>,
    order: SourceOrder,
    gate: FrameGate,
    watchdog: Watchdog,
    pending: Option<PendingFrame>,
    /// (source, receive) times of the last retargeted frame, and the sender's clock jumps
    /// counted when it was taken.
    last_solved: Option<(i64, i64, u64)>,
    last_command: Option<HandCommand>,
    /// (source, receive) times of the gate's reference (the last new frame), and the sender's
    /// clock jumps counted when it was taken.
    gate_reference: Option<(i64, i64, u64)>,
    /// New frames in a row whose stamp did not advance past the new frame before them.
    stalled_stamps: u32,
    counters: Counters,
}

impl HandControl {
    /// Hand control around a configured retargeter (none for a human study), gate and
    /// watchdog.
    pub fn new(retargeter: Option<Retargeter>, gate: FrameGate, watchdog: Watchdog) -> HandControl {
        let mut counters = Counters::default();
        for reason in Rejection::ALL {
            counters.rejected.insert(reason.name().into(), 0);
        }
        HandControl {
            retargeter,
            order: SourceOrder::new(gate.config().reorder_window_ms),
            gate,
            watchdog,
            pending: None,
            last_solved: None,
            last_command: None,
            gate_reference: None,
            stalled_stamps: 0,
            counters,
        }
    }

    /// The retargeter (model, configuration); `None` in a human study.
    pub fn retargeter(&self) -> Option<&Retargeter> {
        self.retargeter.as_ref()
    }

    /// The counters.
    pub fn counters(&self) -> &Counters {
        &self.counters
    }

    /// The drive state as of the last update.
    pub fn state(&self) -> DriveState {
        self.watchdog.state()
    }

    /// Age of the newest frame at `now_ns`.
    pub fn input_age_ns(&self, now_ns: i64) -> Option<i64> {
        self.watchdog.age_ns(now_ns)
    }

    /// The command in force (the last one computed), if any.
    pub fn last_command(&self) -> Option<&HandCommand> {
        self.last_command.as_ref()
    }

    /// Source stamp of the last retargeted frame.
    pub fn last_solved_source_ns(&self) -> Option<i64> {
        self.last_solved.map(|(source, _, _)| source)
    }

    /// A keypoint frame arrived at `received_ns`. A frame stamped before the newest accepted
    /// one is late and rejected (`out_of_order`); a jump of the sender's clock is counted and
    /// followed (see [`source_order`](crate::source_order)). Then the frame gate decides; a new
    /// frame becomes the pending one (replacing one not yet retargeted).
    pub fn take_frame(&mut self, frame: KeypointFrame, received_ns: i64) -> GateDecision {
        let stamp = self.order.check(frame.source_ns, received_ns);
        if stamp == StampOrder::Late {
            self.count_rejection(Rejection::OutOfOrder);
            return GateDecision::Rejected(Rejection::OutOfOrder);
        }
        let since_ns = self.since_gate_reference(&frame, stamp, received_ns);
        let verdict = self.gate.judge_after(&frame.points, since_ns);
        let mut frame = frame;
        if verdict == GateDecision::Repaired {
            self.counters.frames_repaired += 1;
            if let Some(fixed) = self.gate.last_accepted() {
                frame.points = fixed.to_vec();
            }
        }
        match verdict {
            GateDecision::New | GateDecision::Repaired => {
                self.count_stalled_stamp(&frame, stamp);
                self.accept_stamp(&frame, stamp, received_ns);
                self.gate_reference = Some((
                    frame.source_ns,
                    received_ns,
                    self.counters.source_clock_jumps,
                ));
                self.counters.frames_new += 1;
                self.watchdog.frame(received_ns);
                if self.pending.is_some() {
                    self.counters.frames_superseded += 1;
                }
                let clock_frozen = self.source_clock_frozen();
                if clock_frozen {
                    self.counters.frames_timed_by_receipt += 1;
                }
                self.pending = Some(PendingFrame {
                    frame,
                    received_ns,
                    clock_jumps: self.counters.source_clock_jumps,
                    clock_frozen,
                });
            }
            GateDecision::Repeat => {
                self.accept_stamp(&frame, stamp, received_ns);
                self.counters.frames_repeated += 1;
            }
            GateDecision::Rejected(reason) => self.count_rejection(reason),
        }
        verdict
    }

    /// The time since the gate's reference frame: by the sender's stamps, or by the receive
    /// times when the sender's clock jumped at this frame or since the reference (the stamps
    /// cannot be compared then; compared anyway, a frame after a jump back was judged as one
    /// interval after the reference however long ago that was, and a hand that had moved on
    /// stayed rejected as jumps for as long as the sender's clock ran behind).
    fn since_gate_reference(
        &self,
        frame: &KeypointFrame,
        stamp: StampOrder,
        received_ns: i64,
    ) -> Option<i64> {
        let (source, received, jumps) = self.gate_reference?;
        Some(
            if stamp == StampOrder::ClockJump || self.counters.source_clock_jumps > jumps {
                received_ns.saturating_sub(received)
            } else {
                frame.source_ns.saturating_sub(source)
            },
        )
    }

    /// A new frame stamped no later than the new frame before it (a jump aside) extends the
    /// run of stalled stamps; any other ends it.
    fn count_stalled_stamp(&mut self, frame: &KeypointFrame, stamp: StampOrder) {
        let stalled = stamp != StampOrder::ClockJump
            && self
                .gate_reference
                .is_some_and(|(source, _, _)| frame.source_ns <= source);
        self.stalled_stamps = if stalled {
            self.stalled_stamps.saturating_add(1)
        } else {
            0
        };
    }

    /// Whether the sender's stamps have stopped advancing ([`FROZEN_CLOCK_AFTER`] new frames
    /// in a row): time steps and the command ceiling go by receive times.
    pub fn source_clock_frozen(&self) -> bool {
        self.stalled_stamps >= FROZEN_CLOCK_AFTER
    }

    /// Receive time of the last retargeted frame.
    pub fn last_solved_received_ns(&self) -> Option<i64> {
        self.last_solved.map(|(_, received, _)| received)
    }

    fn accept_stamp(&mut self, frame: &KeypointFrame, stamp: StampOrder, received_ns: i64) {
        self.order.accept(frame.source_ns, received_ns);
        if stamp == StampOrder::ClockJump {
            self.counters.source_clock_jumps += 1;
        }
    }

    /// The operator engages; granted with fresh input. Returns whether engaged.
    pub fn engage(&mut self, now_ns: i64) -> bool {
        let was = self.watchdog.state();
        let engaged = self.watchdog.engage(now_ns);
        if engaged && was == DriveState::Disengaged {
            // Resume from the last command, not from a stale time step.
            self.last_solved = None;
        }
        engaged
    }

    /// The operator disengages.
    pub fn disengage(&mut self) {
        self.watchdog.disengage();
    }

    /// Advance the watchdog to `now_ns`; a frame taken while not engaged is dropped.
    pub fn update(&mut self, now_ns: i64) -> DriveState {
        let state = self.watchdog.update(now_ns);
        if state != DriveState::Engaged {
            self.pending = None;
        }
        state
    }

    /// Retarget the pending frame, if any (call after [`update`](Self::update) said engaged).
    /// `None` when there is none or the retargeter refused it (counted).
    pub fn command_pending(&mut self) -> Option<HandCommand> {
        let pending = self.pending.take()?;
        self.solve(&pending)
    }

    /// The last command, marked held.
    pub fn held(&self) -> Option<HandCommand> {
        self.last_command.as_ref().map(|c| HandCommand {
            held: true,
            ..c.clone()
        })
    }

    fn time_step_s(&self, pending: &PendingFrame) -> f64 {
        match self.last_solved {
            None => FIRST_DT_S,
            Some((_, received, jumps)) if pending.clock_jumps > jumps || pending.clock_frozen => {
                time_step_between(received, pending.received_ns)
            }
            Some((source, _, _)) => time_step_between(source, pending.frame.source_ns),
        }
    }

    fn solve(&mut self, pending: &PendingFrame) -> Option<HandCommand> {
        let dt_s = self.time_step_s(pending);
        let retargeter = self.retargeter.as_mut()?;
        let Ok(solution) = retargeter.retarget(&pending.frame.points, dt_s) else {
            self.count_rejection(Rejection::Retargeter);
            return None;
        };
        self.last_solved = Some((
            pending.frame.source_ns,
            pending.received_ns,
            pending.clock_jumps,
        ));
        let counters = &mut self.counters;
        counters.solves += 1;
        match solution.status {
            SolveStatus::StepLimit => counters.solves_step_limit += 1,
            SolveStatus::QpFailed(_) => counters.solves_qp_failed += 1,
            SolveStatus::Converged => {}
        }
        counters.last_qp = QpReport {
            active_set: solution.qp_active_set,
            clarabel: solution.qp_clarabel,
            iterations: solution.qp_iterations,
            clarabel_time_us: solution.qp_time_s * 1e6,
        };
        counters.last_tip_error_mm = solution.tip_error_m * 1e3;
        let command = HandCommand {
            q: solution.q,
            held: false,
            frame_received_ns: pending.received_ns,
            frame_source_ns: pending.frame.source_ns,
        };
        self.last_command = Some(command.clone());
        Some(command)
    }

    fn count_rejection(&mut self, reason: Rejection) {
        *self
            .counters
            .rejected
            .entry(reason.name().into())
            .or_default() += 1;
    }
}
