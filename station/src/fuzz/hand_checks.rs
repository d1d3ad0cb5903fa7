//! Invariants of the hand commands, checked on every output:
//!
//! - `hand_finite`: every joint target (and every `/hand/policy_output` value) is finite;
//! - `hand_limits`: every joint target is within the model's joint limits;
//! - `hand_rate`: a fresh command moves each joint at most `max_joint_speed_rad_s ×
//!   min(Δt, max_rate_dt_s)` from the previous command (the retargeter's rate bound), with
//!   `Δt` the station's time step: 40 ms after an engage from disengaged, else the source
//!   stamps' gap (the receive times' when a jump of the sender's clock was counted between
//!   the two frames' arrivals, or when the sender's clock had frozen: the frame ended a run of
//!   `FROZEN_CLOCK_AFTER` or more new frames each stamped no later than the one before, no
//!   jump among them), clamped to [0.1 ms, 0.5 s];
//! - `hand_newest_frame`: a fresh command comes from the newest new frame, once;
//! - `hand_held_is_last`: a repeated or held command is the last fresh one, unchanged;
//! - `hand_held_after_disengage`: while disengaged only the held command goes out (stamped
//!   with the station clock);
//! - `hand_stamp_order`: fresh commands' stamps never go back unless a jump of the sender's
//!   clock was counted between the two frames' arrivals; held ones carry the station clock.

use msgs::Time;
use retarget::Limits;

use super::tally::Tally;
use crate::hand_control::FROZEN_CLOCK_AFTER;
use crate::output_stage::HandMessages;
use crate::station::Station;
use crate::station_config::{ControlMode, StationConfig};
use crate::station_input::StationOutputs;
use crate::watchdog::DriveState;

/// Slack on the rate bound, radians (rounding only).
const RATE_SLACK_RAD: f64 = 1e-9;
/// The time step of the first command after an engage from disengaged, seconds.
const FIRST_DT_S: f64 = 0.04;
const DT_RANGE_S: (f64, f64) = (1e-4, 0.5);

/// A new frame not yet commanded.
#[derive(Debug, Clone, Copy)]
struct Pending {
    source_ns: i64,
    received_ns: i64,
    /// The station's count of the sender's clock jumps when the frame was taken.
    clock_jumps: u64,
    /// The sender's clock had frozen when the frame was taken.
    clock_frozen: bool,
}

/// The last fresh command.
#[derive(Debug, Clone)]
struct Fresh {
    q: Vec<f64>,
    source_ns: i64,
    received_ns: i64,
    clock_jumps: u64,
}

/// What the hand checks remember between steps.
#[derive(Debug, Clone)]
pub struct HandTrack {
    limits: Vec<Limits>,
    neutral: Vec<f64>,
    max_speed_rad_s: f64,
    max_rate_dt_s: f64,
    rate_mode: bool,
    pending: Option<Pending>,
    last: Option<Fresh>,
    /// The last new frame's source stamp, and the new frames in a row up to it whose stamp
    /// did not advance (no jump of the sender's clock at them).
    last_new_source_ns: Option<i64>,
    stalled_stamps: u32,
    /// No frame retargeted since the last engage from disengaged.
    first_after_engage: bool,
    last_held_ns: i64,
}

impl HandTrack {
    /// The checks for `station`, built from `config`.
    pub fn new(config: &StationConfig, station: &Station) -> HandTrack {
        let (limits, neutral) = station.retargeter().map_or((vec![], vec![]), |r| {
            (r.model().limits().collect(), r.neutral().to_vec())
        });
        HandTrack {
            limits,
            neutral,
            max_speed_rad_s: config.retarget.solver.max_joint_speed_rad_s,
            max_rate_dt_s: config.retarget.solver.max_rate_dt_s,
            rate_mode: config.control.mode == ControlMode::Rate,
            pending: None,
            last: None,
            last_new_source_ns: None,
            stalled_stamps: 0,
            first_after_engage: true,
            last_held_ns: i64::MIN,
        }
    }

    /// A new frame received at `received_ns`, stamped `source_ns`, taken when the station had
    /// counted `clock_jumps` jumps of the sender's clock (`jumped`: one at this frame).
    pub fn new_frame(
        &mut self,
        source_ns: i64,
        received_ns: i64,
        (clock_jumps, jumped): (u64, bool),
    ) {
        let stalled = !jumped && self.last_new_source_ns.is_some_and(|s| source_ns <= s);
        self.stalled_stamps = if stalled { self.stalled_stamps + 1 } else { 0 };
        self.last_new_source_ns = Some(source_ns);
        self.pending = Some(Pending {
            source_ns,
            received_ns,
            clock_jumps,
            clock_frozen: self.stalled_stamps >= FROZEN_CLOCK_AFTER,
        });
    }

    /// An engage was granted while disengaged.
    pub fn engaged(&mut self) {
        self.first_after_engage = true;
    }

    /// Check the hand output of one step.
    pub fn check(
        &mut self,
        outputs: &StationOutputs,
        ctx: (u64, i64, bool),
        station: &Station,
        tally: &mut Tally,
    ) {
        let (step, now_ns, disengaged) = ctx;
        let Some(hand) = &outputs.hand else { return };
        let q = &hand.joint_state.position;
        self.check_values(step, hand, tally);
        let fresh = outputs.fresh_frame_received_ns.is_some();
        tally.count(if fresh {
            "out.hand.fresh"
        } else {
            "out.hand.repeated_or_held"
        });
        if disengaged {
            tally.check(step, "hand_held_after_disengage", !fresh, || {
                "a fresh hand command while disengaged".into()
            });
        }
        if fresh {
            self.check_fresh(step, outputs, tally);
            return;
        }
        let stamp_ns = hand.joint_state.header.stamp.to_nanos();
        let last = self.last.as_ref();
        tally.check(
            step,
            "hand_held_is_last",
            last.is_some_and(|l| &l.q == q),
            || format!("repeated {q:?}, last fresh {:?}", last.map(|l| &l.q)),
        );
        let repeat_engaged =
            self.rate_mode && !disengaged && station.state() == DriveState::Engaged;
        let expected = match (repeat_engaged, last) {
            (true, Some(l)) => l.source_ns,
            _ => now_ns,
        };
        tally.check(
            step,
            "hand_stamp_order",
            stamp(expected) == hand.joint_state.header.stamp,
            || format!("repeated command stamped {stamp_ns}, expected {expected}"),
        );
        if !repeat_engaged {
            tally.check(
                step,
                "hand_stamp_order",
                stamp_ns >= self.last_held_ns,
                || {
                    format!(
                        "held stamp {stamp_ns} before the previous {}",
                        self.last_held_ns
                    )
                },
            );
            self.last_held_ns = stamp_ns;
        }
    }

    fn check_values(&self, step: u64, hand: &HandMessages, tally: &mut Tally) {
        let q = &hand.joint_state.position;
        let policy_finite = hand
            .policy
            .as_ref()
            .is_none_or(|p| p.data.iter().all(|v| v.is_finite()));
        tally.check(
            step,
            "hand_finite",
            policy_finite && q.len() == self.limits.len() && q.iter().all(|v| v.is_finite()),
            || format!("{q:?}"),
        );
        let within = q.iter().zip(&self.limits).all(|(v, l)| l.contains(*v));
        tally.check(step, "hand_limits", within, || {
            format!("{q:?} outside the limits")
        });
    }

    fn check_fresh(&mut self, step: u64, outputs: &StationOutputs, tally: &mut Tally) {
        let Some(hand) = &outputs.hand else { return };
        let q = &hand.joint_state.position;
        let pending = self.pending.take();
        let newest = pending.is_some_and(|p| {
            Some(p.received_ns) == outputs.fresh_frame_received_ns
                && stamp(p.source_ns) == hand.joint_state.header.stamp
        });
        tally.check(step, "hand_newest_frame", newest, || {
            format!(
                "fresh command from {:?}, newest new frame {pending:?}",
                outputs.fresh_frame_received_ns
            )
        });
        let Some(pending) = pending else { return };
        let dt_s = self.time_step_s(&pending);
        let reach = self.max_speed_rad_s * dt_s.min(self.max_rate_dt_s) + RATE_SLACK_RAD;
        let previous = self.last.as_ref().map_or(&self.neutral, |l| &l.q);
        let worst = q
            .iter()
            .zip(previous)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        tally.check(step, "hand_rate", worst <= reach, || {
            format!("a joint moved {worst} rad, bound {reach} rad (dt {dt_s} s)")
        });
        if let Some(last) = &self.last {
            let back = pending.source_ns < last.source_ns;
            let jumped = pending.clock_jumps > last.clock_jumps;
            tally.check(step, "hand_stamp_order", !back || jumped, || {
                format!(
                    "fresh stamp {} after {} without a clock jump",
                    pending.source_ns, last.source_ns
                )
            });
        }
        self.last = Some(Fresh {
            q: q.clone(),
            source_ns: pending.source_ns,
            received_ns: pending.received_ns,
            clock_jumps: pending.clock_jumps,
        });
        self.first_after_engage = false;
    }

    /// The time step the station hands the retargeter for `pending`, seconds.
    fn time_step_s(&self, pending: &Pending) -> f64 {
        let step_ns = match &self.last {
            None => return FIRST_DT_S,
            Some(_) if self.first_after_engage => return FIRST_DT_S,
            Some(l) if pending.clock_jumps > l.clock_jumps || pending.clock_frozen => {
                i128::from(pending.received_ns) - i128::from(l.received_ns)
            }
            Some(l) => i128::from(pending.source_ns) - i128::from(l.source_ns),
        };
        (step_ns as f64 * 1e-9).clamp(DT_RANGE_S.0, DT_RANGE_S.1)
    }
}

fn stamp(ns: i64) -> Time {
    Time::from_nanos(ns)
}
