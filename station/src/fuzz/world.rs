//! The station's hostile world: the glove's sender (its clock jumps, its frames duplicated,
//! reordered, bursty or broken), the wrist tracker, the arm's feedback, the operator, the
//! station's timer and its own clock (monotonic, with gaps of up to seconds). Each call of
//! [`World::next`] gives one input and its receive time.

use std::collections::VecDeque;

use msgs::{Point, Pose};

use super::hostile::{hostile_points, hostile_pose, random_unit_quaternion};
use super::plausible_hand::PlausibleHand;
use super::rng::FuzzRng;
use super::tally::Tally;
use crate::arm::WorkspaceBox;
use crate::convert::isometry_to_pose;
use crate::hand_control::KeypointFrame;
use crate::station_input::{ControlInput, StationInput};

const MS: i64 = 1_000_000;
const HOUR: i64 = 3_600_000 * MS;
/// Frames kept for duplicates and replays.
const HISTORY: usize = 32;

/// Frames captured in the past and delivered at once.
#[derive(Debug, Clone, Copy)]
struct Burst {
    left: u32,
    spacing_ns: i64,
}

/// Everything around the station.
#[derive(Debug, Clone)]
pub struct World {
    rng: FuzzRng,
    hand: PlausibleHand,
    workspace: WorkspaceBox,
    start_ns: i64,
    now_ns: i64,
    sender_offset_ns: i64,
    sent: VecDeque<KeypointFrame>,
    burst: Option<Burst>,
    blocked: bool,
}

impl World {
    /// A world for `seed`, around a station whose arm works in `workspace`; the station clock
    /// starts at `start_ns`.
    pub fn new(seed: u64, hand: PlausibleHand, workspace: WorkspaceBox, start_ns: i64) -> World {
        World {
            rng: FuzzRng::new(seed),
            hand,
            workspace,
            start_ns,
            now_ns: start_ns,
            sender_offset_ns: 0,
            sent: VecDeque::with_capacity(HISTORY),
            burst: None,
            blocked: false,
        }
    }

    /// The next input and its receive time; `tally` counts what the world did.
    pub fn next(&mut self, tally: &mut Tally) -> (StationInput, i64) {
        self.advance_clock(tally);
        let r = self.rng.unit();
        let input = if self.burst.is_some() || r < 0.55 {
            tally.count("in.frame");
            StationInput::Keypoints(self.frame(tally))
        } else if r < 0.65 {
            StationInput::Wrist(self.wrist(tally))
        } else if r < 0.68 {
            StationInput::ArmFeedback(self.arm_feedback(tally))
        } else if r < 0.9 {
            tally.count("in.tick");
            StationInput::Control(ControlInput::Tick)
        } else {
            StationInput::Control(self.operator(tally))
        };
        (input, self.now_ns)
    }

    fn advance_clock(&mut self, tally: &mut Tally) {
        if self.burst.is_some() {
            return;
        }
        let r = self.rng.unit();
        let gap = if r < 0.2 {
            0
        } else if r < 0.8 {
            self.rng.int(0, 10 * MS)
        } else if r < 0.982 {
            self.rng.int(10 * MS, 40 * MS)
        } else if r < 0.997 {
            tally.count("clock.station_gap_150ms_to_1s");
            // Most of them between the default hold (150 ms) and disengage (500 ms) timeouts,
            // so that a tick in the gap finds the station holding.
            match self.rng.unit() < 0.6 {
                true => self.rng.int(150 * MS, 450 * MS),
                false => self.rng.int(450 * MS, 1000 * MS),
            }
        } else {
            tally.count("clock.station_gap_1s_to_5s");
            self.rng.int(1000 * MS, 5000 * MS)
        };
        self.now_ns += gap;
    }

    /// One keypoint frame: plausible, from a burst, duplicated, replayed or hostile.
    fn frame(&mut self, tally: &mut Tally) -> KeypointFrame {
        self.sender_clock(tally);
        let frame = if let Some(burst) = self.burst.as_mut() {
            burst.left -= 1;
            let capture_ns = self.now_ns - i64::from(burst.left) * burst.spacing_ns;
            if burst.left == 0 {
                self.burst = None;
            }
            tally.count("frame.burst");
            self.captured(capture_ns)
        } else {
            self.frame_of_kind(tally)
        };
        if self.sent.len() == HISTORY {
            self.sent.pop_front();
        }
        self.sent.push_back(frame.clone());
        frame
    }

    fn frame_of_kind(&mut self, tally: &mut Tally) -> KeypointFrame {
        let r = self.rng.unit();
        let capture_ns = self.now_ns - self.rng.int(0, 3 * MS);
        if r < 0.7 {
            if self.rng.chance(0.01) {
                let left = self.rng.int(5, 60) as u32;
                let spacing_ns = self.rng.int(2 * MS, 10 * MS);
                self.burst = Some(Burst { left, spacing_ns });
                tally.count("frame.burst_started");
            }
            tally.count("frame.valid");
            return self.captured(capture_ns);
        }
        let last = self.sent.back().cloned();
        match (r, last) {
            (r, Some(last)) if r < 0.76 => {
                tally.count("frame.duplicate");
                last
            }
            (r, Some(last)) if r < 0.8 => {
                tally.count("frame.duplicate_restamped");
                KeypointFrame {
                    source_ns: capture_ns.saturating_add(self.sender_offset_ns),
                    ..last
                }
            }
            (r, Some(_)) if r < 0.84 => {
                tally.count("frame.replayed_older");
                self.sent[self.rng.below(self.sent.len())].clone()
            }
            _ => {
                let valid = self.captured(capture_ns);
                let (points, kind) = hostile_points(&mut self.rng, &valid.points);
                tally.count("frame.hostile");
                tally.count(kind);
                KeypointFrame { points, ..valid }
            }
        }
    }

    /// The plausible hand's frame captured at `capture_ns` on the station clock, stamped by
    /// the sender's clock.
    fn captured(&self, capture_ns: i64) -> KeypointFrame {
        let (points, _) = self.hand.frame(self.hand_time_s(capture_ns));
        KeypointFrame {
            points,
            source_ns: capture_ns.saturating_add(self.sender_offset_ns),
        }
    }

    fn hand_time_s(&self, ns: i64) -> f64 {
        (ns - self.start_ns) as f64 * 1e-9
    }

    /// The sender's clock: jumps of hours either way, small backward steps, a wild stamp.
    fn sender_clock(&mut self, tally: &mut Tally) {
        let r = self.rng.unit();
        if r < 0.002 {
            self.sender_offset_ns += self.rng.int(HOUR, 3 * HOUR);
            tally.count("clock.sender_jump_ahead");
        } else if r < 0.004 {
            self.sender_offset_ns -= self.rng.int(HOUR, 3 * HOUR);
            tally.count("clock.sender_jump_back");
        } else if r < 0.006 {
            self.sender_offset_ns -= self.rng.int(20 * MS, 240 * MS);
            tally.count("clock.sender_step_back");
        } else if r < 0.007 {
            let wild = [i64::MIN, i64::MAX, 0, -1, self.rng.next_u64() as i64];
            self.sender_offset_ns = self.rng.pick(&wild).wrapping_sub(self.now_ns);
            tally.count("clock.sender_wild");
        }
    }

    fn wrist(&mut self, tally: &mut Tally) -> Pose {
        let (_, wrist) = self.hand.frame(self.hand_time_s(self.now_ns));
        let valid = isometry_to_pose(&wrist);
        if self.rng.chance(0.85) {
            tally.count("in.wrist.valid");
            return valid;
        }
        tally.count("in.wrist.hostile");
        let (pose, kind) = hostile_pose(&mut self.rng, &valid);
        tally.count(kind);
        pose
    }

    fn arm_feedback(&mut self, tally: &mut Tally) -> Pose {
        let (lo, hi) = (self.workspace.min_m, self.workspace.max_m);
        let inside = Point {
            x: self.rng.range(lo.x, hi.x),
            y: self.rng.range(lo.y, hi.y),
            z: self.rng.range(lo.z, hi.z),
        };
        let valid = Pose {
            position: inside,
            orientation: random_unit_quaternion(&mut self.rng),
        };
        if self.rng.chance(0.7) {
            tally.count("in.arm_feedback.valid");
            return valid;
        }
        tally.count("in.arm_feedback.hostile");
        let (pose, kind) = hostile_pose(&mut self.rng, &valid);
        tally.count(kind);
        pose
    }

    fn operator(&mut self, tally: &mut Tally) -> ControlInput {
        let r = self.rng.unit();
        if r < 0.6 {
            tally.count("in.engage");
            ControlInput::Engage
        } else if r < 0.72 {
            tally.count("in.disengage");
            ControlInput::Disengage
        } else if r < 0.78 {
            self.blocked = !self.blocked && self.rng.chance(0.4);
            tally.count(if self.blocked {
                "in.arm_blocked"
            } else {
                "in.arm_unblocked"
            });
            ControlInput::ArmBlocked {
                blocked: self.blocked,
            }
        } else {
            tally.count("in.tick");
            ControlInput::Tick
        }
    }
}
