//! Scripted hand motions: poses as pure, periodic, C¹ functions of time.
//!
//! A motion is a cycle of `cycle_s` seconds split into segments. Segment `i` lasts the
//! fraction `wᵢ` of the cycle and moves from the previous segment's key pose `Kᵢ₋₁` to its own
//! `Kᵢ` (the first segment starts from the last one's, so the cycle closes):
//!
//! ```text
//! u = (t / cycle_s) mod 1,    v = progress of u within segment i ∈ [0, 1)
//! pose(t) = lerp(Kᵢ₋₁, Kᵢ, 3v² − 2v³)
//! ```
//!
//! The smoothstep `3v² − 2v³` has zero slope at both ends, so every segment starts and ends
//! at rest: the pose is continuous with a continuous first derivative (C¹) everywhere,
//! including the wrap of the cycle, and `pose(t + cycle_s) = pose(t)`. A segment whose key
//! pose equals the previous one is a hold.
//!
//! | motion | cycle | segments (fractions of the cycle) |
//! |---|---|---|
//! | [`Motion::OpenClose`] | `period_s` | open → fist 0.4, hold 0.1, → open 0.4, hold 0.1 |
//! | [`Motion::Abduction`] | `period_s` | open → spread 0.4, hold 0.1, → open 0.4, hold 0.1 |
//! | [`Motion::Pinches`] | `4 · period_s` | per finger (index, middle, ring, little), in quarters: open → pinch 0.35, hold 0.3, → open 0.35 |
//! | [`Motion::TaskLike`] | `period_s` | grasp a cylinder and hold, release, index pinch and hold, release with the fingers spread, middle pinch and hold, release |
//! | [`Motion::CalibrationPoses`] | `7 · period_s` | the seven calibration poses in capture order (pinch index, middle, ring, little; open; open spread; fist), per pose: move 0.35, hold 0.65 |
//!
//! Pinch poses depend on the hand's proportions (not its scale), so the motions that use them
//! carry them, solved once by [`pinch_pose`] with a [`PINCH_GAP_M`] gap.

use serde::{Deserialize, Serialize};

use super::pinch::pinch_pose;
use super::pose::HumanHandPose;
use super::shape::HumanHandShape;
use crate::error::Error;
use crate::finger::Finger;

/// Thumb-tip to fingertip gap of the scripted pinches, metres (pads touching: glove tip
/// points sit a few millimetres apart).
pub const PINCH_GAP_M: f64 = 0.005;

/// Shortest period accepted, seconds.
pub const MIN_PERIOD_S: f64 = 0.2;

/// The kinds of scripted motion, as a configuration names them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MotionKind {
    /// Open hand to fist and back.
    OpenClose,
    /// The four thumb–finger pinches in turn.
    Pinches,
    /// Fingers spread and closed.
    Abduction,
    /// Grasp, release, pinches: a task-like sequence.
    TaskLike,
    /// The seven calibration poses in turn, each moved to and held.
    CalibrationPoses,
}

impl MotionKind {
    /// All kinds.
    pub const ALL: [MotionKind; 5] = [
        MotionKind::OpenClose,
        MotionKind::Pinches,
        MotionKind::Abduction,
        MotionKind::TaskLike,
        MotionKind::CalibrationPoses,
    ];

    /// A comfortable default period, seconds (for [`MotionKind::Pinches`]: per pinch; for
    /// [`MotionKind::CalibrationPoses`]: per pose).
    pub const fn default_period_s(self) -> f64 {
        match self {
            MotionKind::CalibrationPoses => 2.5,
            MotionKind::OpenClose => 4.0,
            MotionKind::Pinches => 2.5,
            MotionKind::Abduction => 3.0,
            MotionKind::TaskLike => 12.0,
        }
    }
}

/// A key pose of a scripted motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum KeyPose {
    /// [`HumanHandPose::open`].
    Open,
    /// [`HumanHandPose::open_spread`].
    OpenSpread,
    /// [`HumanHandPose::fist`].
    Fist,
    /// [`HumanHandPose::cylinder_grasp`].
    CylinderGrasp,
    /// The thumb pinching this finger.
    Pinch(Finger),
}

/// Where a motion is at some time: moving from one key pose to another (or holding one).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionPhase {
    /// The key pose the segment starts from.
    pub from: KeyPose,
    /// The key pose the segment ends at (`from == to`: a hold).
    pub to: KeyPose,
    /// Progress through the segment, in `[0, 1)`.
    pub progress: f64,
}

/// A scripted motion: see the module documentation.
#[derive(Debug, Clone, PartialEq)]
pub enum Motion {
    /// Open to fist and back.
    OpenClose {
        /// Cycle length, seconds.
        period_s: f64,
    },
    /// Thumb–index, –middle, –ring, –little pinches in turn.
    Pinches {
        /// Time per pinch, seconds (the cycle is four times longer).
        period_s: f64,
        /// The pinch poses for index, middle, ring, little.
        poses: [HumanHandPose; 4],
    },
    /// Fingers spread and back together.
    Abduction {
        /// Cycle length, seconds.
        period_s: f64,
    },
    /// A task-like sequence of grasp, release and pinches.
    TaskLike {
        /// Cycle length, seconds.
        period_s: f64,
        /// The pinch poses for index, middle, ring, little.
        pinches: [HumanHandPose; 4],
    },
    /// The seven calibration poses in capture order, each moved to and held.
    CalibrationPoses {
        /// Time per pose, seconds (the cycle is seven times longer).
        period_s: f64,
        /// The poses: pinch index, middle, ring, little; open; open spread; closed.
        poses: Box<[HumanHandPose; 7]>,
    },
}

use KeyPose::{CylinderGrasp, Fist, Open, OpenSpread, Pinch};

const OPEN_CLOSE: [(f64, KeyPose); 4] = [(0.4, Fist), (0.1, Fist), (0.4, Open), (0.1, Open)];

const ABDUCTION: [(f64, KeyPose); 4] = [
    (0.4, OpenSpread),
    (0.1, OpenSpread),
    (0.4, Open),
    (0.1, Open),
];

const PINCHES: [(f64, KeyPose); 12] = {
    let fingers = Finger::OPPOSING;
    let mut out = [(0.0, Open); 12];
    let mut k = 0;
    while k < 4 {
        out[3 * k] = (0.35 / 4.0, Pinch(fingers[k]));
        out[3 * k + 1] = (0.3 / 4.0, Pinch(fingers[k]));
        out[3 * k + 2] = (0.35 / 4.0, Open);
        k += 1;
    }
    out
};

const TASK_LIKE: [(f64, KeyPose); 11] = [
    (0.10, CylinderGrasp),
    (0.15, CylinderGrasp),
    (0.08, Open),
    (0.10, Pinch(Finger::Index)),
    (0.12, Pinch(Finger::Index)),
    (0.08, OpenSpread),
    (0.05, OpenSpread),
    (0.10, Pinch(Finger::Middle)),
    (0.10, Pinch(Finger::Middle)),
    (0.07, Open),
    (0.05, Open),
];

/// Share of each calibration pose's slot spent moving to it (the rest is the hold).
pub const CALIBRATION_MOVE_SHARE: f64 = 0.35;

/// The key poses of [`Motion::CalibrationPoses`], in capture order.
const CALIBRATION_KEYS: [KeyPose; 7] = [
    Pinch(Finger::Index),
    Pinch(Finger::Middle),
    Pinch(Finger::Ring),
    Pinch(Finger::Little),
    Open,
    OpenSpread,
    Fist,
];

const CALIBRATION_POSES: [(f64, KeyPose); 14] = {
    let keys = CALIBRATION_KEYS;
    let mut out = [(0.0, Open); 14];
    let mut k = 0;
    while k < 7 {
        out[2 * k] = (CALIBRATION_MOVE_SHARE / 7.0, keys[k]);
        out[2 * k + 1] = ((1.0 - CALIBRATION_MOVE_SHARE) / 7.0, keys[k]);
        k += 1;
    }
    out
};

/// `Err` for a period below [`MIN_PERIOD_S`] or not finite.
fn check_period(period_s: f64) -> Result<(), Error> {
    if period_s.is_finite() && period_s >= MIN_PERIOD_S {
        Ok(())
    } else {
        Err(Error::ConfigRange {
            key: "motion.period_s".into(),
            value: period_s.to_string(),
            allowed: format!("must be at least {MIN_PERIOD_S} s"),
        })
    }
}

/// The smoothstep `3v² − 2v³`: 0 → 1 with zero slope at both ends.
fn smoothstep(v: f64) -> f64 {
    v * v * (3.0 - 2.0 * v)
}

/// The segment of `table` (fractions summing to 1) at cycle position `u ∈ [0, 1)`.
fn phase_in(table: &[(f64, KeyPose)], u: f64) -> MotionPhase {
    let mut start = 0.0;
    let mut from = table.last().map_or(Open, |&(_, k)| k);
    for (i, &(width, to)) in table.iter().enumerate() {
        if u < start + width || i + 1 == table.len() {
            return MotionPhase {
                from,
                to,
                progress: ((u - start) / width).clamp(0.0, 1.0),
            };
        }
        start += width;
        from = to;
    }
    MotionPhase {
        from: Open,
        to: Open,
        progress: 0.0,
    }
}

impl Motion {
    /// A motion of `kind`: `period_s` is the cycle length (for [`MotionKind::Pinches`], the
    /// time per pinch); pinch poses are solved for `shape`. `Err` for a period below
    /// [`MIN_PERIOD_S`] or not finite, or an invalid shape.
    pub fn new(kind: MotionKind, period_s: f64, shape: &HumanHandShape) -> Result<Motion, Error> {
        check_period(period_s)?;
        let pinches = || -> Result<[HumanHandPose; 4], Error> {
            let mut poses = [HumanHandPose::open(); 4];
            for (pose, finger) in poses.iter_mut().zip(Finger::OPPOSING) {
                *pose = pinch_pose(shape, finger, PINCH_GAP_M)?.pose;
            }
            Ok(poses)
        };
        Ok(match kind {
            MotionKind::OpenClose => Motion::OpenClose { period_s },
            MotionKind::Abduction => Motion::Abduction { period_s },
            MotionKind::Pinches => Motion::Pinches {
                period_s,
                poses: pinches()?,
            },
            MotionKind::TaskLike => Motion::TaskLike {
                period_s,
                pinches: pinches()?,
            },
            MotionKind::CalibrationPoses => {
                let p = pinches()?;
                Motion::CalibrationPoses {
                    period_s,
                    poses: Box::new([
                        p[0],
                        p[1],
                        p[2],
                        p[3],
                        HumanHandPose::open(),
                        HumanHandPose::open_spread(),
                        HumanHandPose::fist(),
                    ]),
                }
            }
        })
    }

    /// The calibration poses motion with the user's own version of each pose (pinch index,
    /// middle, ring, little; open; open spread; closed), `period_s` per pose. `Err` for a
    /// period below [`MIN_PERIOD_S`] or a pose outside the joint ranges.
    pub fn calibration_poses(poses: [HumanHandPose; 7], period_s: f64) -> Result<Motion, Error> {
        check_period(period_s)?;
        if let Some(k) = poses.iter().position(|p| !p.within_ranges()) {
            return Err(Error::ConfigRange {
                key: format!("motion.poses[{k}]"),
                value: "out of range".into(),
                allowed: "every angle within JOINT_RANGES_RAD".into(),
            });
        }
        Ok(Motion::CalibrationPoses {
            period_s,
            poses: Box::new(poses),
        })
    }

    /// Which kind of motion this is.
    pub const fn kind(&self) -> MotionKind {
        match self {
            Motion::OpenClose { .. } => MotionKind::OpenClose,
            Motion::Pinches { .. } => MotionKind::Pinches,
            Motion::Abduction { .. } => MotionKind::Abduction,
            Motion::TaskLike { .. } => MotionKind::TaskLike,
            Motion::CalibrationPoses { .. } => MotionKind::CalibrationPoses,
        }
    }

    /// Length of one full cycle, seconds.
    pub fn cycle_s(&self) -> f64 {
        match self {
            Motion::Pinches { period_s, .. } => 4.0 * period_s,
            Motion::CalibrationPoses { period_s, .. } => 7.0 * period_s,
            Motion::OpenClose { period_s }
            | Motion::Abduction { period_s }
            | Motion::TaskLike { period_s, .. } => *period_s,
        }
    }

    fn table(&self) -> &'static [(f64, KeyPose)] {
        match self {
            Motion::OpenClose { .. } => &OPEN_CLOSE,
            Motion::Pinches { .. } => &PINCHES,
            Motion::Abduction { .. } => &ABDUCTION,
            Motion::TaskLike { .. } => &TASK_LIKE,
            Motion::CalibrationPoses { .. } => &CALIBRATION_POSES,
        }
    }

    /// The segment the motion is in at time `t_s` (any real time; the motion is periodic).
    pub fn phase(&self, t_s: f64) -> MotionPhase {
        phase_in(self.table(), (t_s / self.cycle_s()).rem_euclid(1.0))
    }

    /// The angles of a key pose in this motion.
    pub fn key_pose(&self, key: KeyPose) -> HumanHandPose {
        if let Motion::CalibrationPoses { poses, .. } = self {
            return CALIBRATION_KEYS
                .iter()
                .position(|&k| k == key)
                .map_or_else(HumanHandPose::open, |i| poses[i]);
        }
        match key {
            Open => HumanHandPose::open(),
            OpenSpread => HumanHandPose::open_spread(),
            Fist => HumanHandPose::fist(),
            CylinderGrasp => HumanHandPose::cylinder_grasp(),
            Pinch(finger) => match self {
                Motion::Pinches { poses, .. } | Motion::TaskLike { pinches: poses, .. } => finger
                    .index()
                    .checked_sub(1)
                    .map_or_else(HumanHandPose::open, |i| poses[i]),
                _ => HumanHandPose::open(),
            },
        }
    }

    /// The hand pose at time `t_s`, seconds.
    pub fn sample(&self, t_s: f64) -> HumanHandPose {
        let phase = self.phase(t_s);
        HumanHandPose::lerp(
            &self.key_pose(phase.from),
            &self.key_pose(phase.to),
            smoothstep(phase.progress),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_cover_the_cycle_and_close_it() {
        for table in [
            &OPEN_CLOSE[..],
            &ABDUCTION,
            &PINCHES,
            &TASK_LIKE,
            &CALIBRATION_POSES,
        ] {
            let total: f64 = table.iter().map(|(w, _)| w).sum();
            assert!((total - 1.0).abs() < 1e-12, "{total}");
            assert!(table.iter().all(|&(w, _)| w > 0.0));
            let phase = phase_in(table, 0.0);
            let first = if std::ptr::eq(table, &CALIBRATION_POSES[..]) {
                Fist
            } else {
                Open
            };
            assert_eq!(phase.from, first, "each cycle starts where it ends");
        }
    }

    #[test]
    fn calibration_poses_hold_each_pose_in_capture_order() {
        let shape = HumanHandShape::average();
        let motion = Motion::new(MotionKind::CalibrationPoses, 2.0, &shape).unwrap();
        assert_eq!(motion.cycle_s(), 14.0);
        for (k, key) in CALIBRATION_KEYS.into_iter().enumerate() {
            let hold = motion.phase(2.0 * k as f64 + 1.5);
            assert_eq!((hold.from, hold.to), (key, key), "pose {k}");
            let pose = motion.sample(2.0 * k as f64 + 1.9);
            assert!(pose.max_difference_rad(&motion.key_pose(key)) < 1e-12);
        }
    }

    #[test]
    fn phases_follow_the_table() {
        let shape = HumanHandShape::average();
        let m = Motion::new(MotionKind::Pinches, 2.0, &shape).unwrap();
        assert_eq!(m.cycle_s(), 8.0);
        // Middle of the hold of the second pinch: 2 s + (0.35 + 0.15) · 2 s.
        let p = m.phase(3.0);
        assert_eq!(
            (p.from, p.to),
            (Pinch(Finger::Middle), Pinch(Finger::Middle))
        );
        assert_eq!(m.sample(3.0), m.key_pose(Pinch(Finger::Middle)));
        assert_eq!(m.sample(3.0 + 8.0 * 5.0), m.sample(3.0), "periodic");
        let o = Motion::new(MotionKind::OpenClose, 4.0, &shape).unwrap();
        assert_eq!(o.sample(0.0), HumanHandPose::open());
        assert!(o.sample(1.8).max_difference_rad(&HumanHandPose::fist()) < 1e-12);
        assert!(Motion::new(MotionKind::OpenClose, 0.0, &shape).is_err());
        assert!(Motion::new(MotionKind::Abduction, f64::NAN, &shape).is_err());
    }

    #[test]
    fn kinds_parse_from_snake_case() {
        #[derive(Deserialize)]
        struct W {
            motion: MotionKind,
        }
        let w: W = toml::from_str("motion = \"task_like\"").unwrap();
        assert_eq!(w.motion, MotionKind::TaskLike);
        for kind in MotionKind::ALL {
            let m = Motion::new(kind, kind.default_period_s(), &HumanHandShape::average());
            assert_eq!(m.unwrap().kind(), kind);
        }
    }
}
