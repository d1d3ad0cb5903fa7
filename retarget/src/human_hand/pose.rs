//! [`HumanHandPose`]: joint angles of a human hand, radians, with named poses.
//!
//! Sign conventions (the same for both hands; the mirror is applied to the points):
//!
//! - every flexion is positive towards the palm; zero is the straight, flat hand;
//! - finger abduction is positive *away from the middle finger* (index towards the thumb,
//!   ring and little away from it); for the middle finger positive is towards the index;
//! - thumb CMC flexion moves the thumb metacarpal across the palm towards the little finger
//!   (in the palm plane), negative is radial abduction (the thumb opened sideways); thumb CMC
//!   abduction lifts it out of the palm plane towards the palm side (palmar abduction).
//!   Together they give opposition.
//!
//! Each angle has an anatomical range ([`JOINT_RANGES_RAD`], round numbers for an adult);
//! the named poses and the pinch solver stay inside it.

use serde::{Deserialize, Serialize};

use crate::finger::Finger;

/// Angles of the thumb, radians.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThumbAngles {
    /// CMC flexion: across the palm towards the little finger (in the palm plane).
    pub cmc_flexion_rad: f64,
    /// CMC (palmar) abduction: out of the palm plane towards the palm side.
    pub cmc_abduction_rad: f64,
    /// MCP flexion.
    pub mcp_flexion_rad: f64,
    /// IP flexion.
    pub ip_flexion_rad: f64,
}

/// Angles of one finger (index, middle, ring or little), radians.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FingerAngles {
    /// MCP flexion.
    pub mcp_flexion_rad: f64,
    /// MCP abduction, away from the middle finger (middle: towards the index).
    pub mcp_abduction_rad: f64,
    /// PIP flexion.
    pub pip_flexion_rad: f64,
    /// DIP flexion.
    pub dip_flexion_rad: f64,
}

/// All joint angles of a human hand, radians.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HumanHandPose {
    /// The thumb.
    pub thumb: ThumbAngles,
    /// Index, middle, ring, little (position `finger.index() − 1`).
    pub fingers: [FingerAngles; 4],
}

/// Number of angles in a [`HumanHandPose`] (4 per digit).
pub const POSE_ANGLES: usize = 20;

/// Name of each angle of [`HumanHandPose::to_array`], in that order.
pub const ANGLE_NAMES: [&str; POSE_ANGLES] = [
    "thumb_cmc_flexion",
    "thumb_cmc_abduction",
    "thumb_mcp_flexion",
    "thumb_ip_flexion",
    "index_mcp_flexion",
    "index_mcp_abduction",
    "index_pip_flexion",
    "index_dip_flexion",
    "middle_mcp_flexion",
    "middle_mcp_abduction",
    "middle_pip_flexion",
    "middle_dip_flexion",
    "ring_mcp_flexion",
    "ring_mcp_abduction",
    "ring_pip_flexion",
    "ring_dip_flexion",
    "little_mcp_flexion",
    "little_mcp_abduction",
    "little_pip_flexion",
    "little_dip_flexion",
];

const THUMB_RANGES: [(f64, f64); 4] = [(-0.5, 0.9), (-0.2, 1.2), (-0.2, 1.0), (-0.35, 1.4)];
const FINGER_RANGES: [(f64, f64); 4] = [(-0.35, 1.6), (-0.35, 0.45), (0.0, 1.9), (0.0, 1.4)];

/// Anatomical range `(lower, upper)` of each angle of [`HumanHandPose::to_array`], radians.
pub const JOINT_RANGES_RAD: [(f64, f64); POSE_ANGLES] = {
    let mut out = [(0.0, 0.0); POSE_ANGLES];
    let mut i = 0;
    while i < POSE_ANGLES {
        out[i] = if i < 4 {
            THUMB_RANGES[i]
        } else {
            FINGER_RANGES[i % 4]
        };
        i += 1;
    }
    out
};

/// A finger flexed by `mcp`, `pip`, `dip` radians, not abducted.
const fn flexed(mcp: f64, pip: f64, dip: f64) -> FingerAngles {
    FingerAngles {
        mcp_flexion_rad: mcp,
        mcp_abduction_rad: 0.0,
        pip_flexion_rad: pip,
        dip_flexion_rad: dip,
    }
}

impl HumanHandPose {
    /// Open, flat hand: every angle zero (fingers straight and together, the thumb straight
    /// in its rest direction, 25° from the fingers and slightly palmar).
    pub const fn open() -> HumanHandPose {
        HumanHandPose {
            thumb: ThumbAngles {
                cmc_flexion_rad: 0.0,
                cmc_abduction_rad: 0.0,
                mcp_flexion_rad: 0.0,
                ip_flexion_rad: 0.0,
            },
            fingers: [flexed(0.0, 0.0, 0.0); 4],
        }
    }

    /// Open hand with the fingers spread and the thumb opened sideways.
    pub const fn open_spread() -> HumanHandPose {
        let mut pose = HumanHandPose::open();
        pose.thumb.cmc_flexion_rad = -0.4;
        pose.thumb.cmc_abduction_rad = 0.15;
        pose.fingers[0].mcp_abduction_rad = 0.3;
        pose.fingers[1].mcp_abduction_rad = 0.05;
        pose.fingers[2].mcp_abduction_rad = 0.22;
        pose.fingers[3].mcp_abduction_rad = 0.4;
        pose
    }

    /// Closed fist: fingers curled into the palm (tips 1–2 cm in front of it), the thumb
    /// folded across the curled fingers' middle phalanges.
    pub const fn fist() -> HumanHandPose {
        HumanHandPose {
            thumb: ThumbAngles {
                cmc_flexion_rad: 0.2,
                cmc_abduction_rad: 0.25,
                mcp_flexion_rad: 0.8,
                ip_flexion_rad: 0.6,
            },
            fingers: [flexed(1.45, 1.75, 1.1); 4],
        }
    }

    /// Relaxed hand: fingers slightly flexed, as when resting (also the non-pinching
    /// fingers of [`crate::human_hand::pinch_pose`]).
    pub const fn relaxed() -> HumanHandPose {
        HumanHandPose {
            thumb: ThumbAngles {
                cmc_flexion_rad: 0.1,
                cmc_abduction_rad: 0.2,
                mcp_flexion_rad: 0.1,
                ip_flexion_rad: 0.1,
            },
            fingers: [flexed(0.2, 0.25, 0.15); 4],
        }
    }

    /// Power grasp of a cylinder of roughly 4 cm diameter: fingers wrapped halfway, thumb
    /// opposed around the other side.
    pub const fn cylinder_grasp() -> HumanHandPose {
        HumanHandPose {
            thumb: ThumbAngles {
                cmc_flexion_rad: 0.3,
                cmc_abduction_rad: 0.85,
                mcp_flexion_rad: 0.3,
                ip_flexion_rad: 0.25,
            },
            fingers: [flexed(0.85, 1.05, 0.6); 4],
        }
    }

    /// The angles of `finger` (index, middle, ring, little), or `None` for the thumb.
    pub fn finger(&self, finger: Finger) -> Option<&FingerAngles> {
        finger.index().checked_sub(1).map(|i| &self.fingers[i])
    }

    /// Mutable angles of `finger`, or `None` for the thumb.
    pub fn finger_mut(&mut self, finger: Finger) -> Option<&mut FingerAngles> {
        finger.index().checked_sub(1).map(|i| &mut self.fingers[i])
    }

    /// The angles as a flat array, in the order of [`ANGLE_NAMES`].
    pub fn to_array(&self) -> [f64; POSE_ANGLES] {
        let t = &self.thumb;
        let mut out = [0.0; POSE_ANGLES];
        out[..4].copy_from_slice(&[
            t.cmc_flexion_rad,
            t.cmc_abduction_rad,
            t.mcp_flexion_rad,
            t.ip_flexion_rad,
        ]);
        for (i, f) in self.fingers.iter().enumerate() {
            out[4 + 4 * i..8 + 4 * i].copy_from_slice(&[
                f.mcp_flexion_rad,
                f.mcp_abduction_rad,
                f.pip_flexion_rad,
                f.dip_flexion_rad,
            ]);
        }
        out
    }

    /// The pose from a flat array in the order of [`ANGLE_NAMES`].
    pub fn from_array(a: &[f64; POSE_ANGLES]) -> HumanHandPose {
        HumanHandPose {
            thumb: ThumbAngles {
                cmc_flexion_rad: a[0],
                cmc_abduction_rad: a[1],
                mcp_flexion_rad: a[2],
                ip_flexion_rad: a[3],
            },
            fingers: std::array::from_fn(|i| FingerAngles {
                mcp_flexion_rad: a[4 + 4 * i],
                mcp_abduction_rad: a[5 + 4 * i],
                pip_flexion_rad: a[6 + 4 * i],
                dip_flexion_rad: a[7 + 4 * i],
            }),
        }
    }

    /// Linear interpolation of every angle: `a` at `t = 0`, `b` at `t = 1`.
    pub fn lerp(a: &HumanHandPose, b: &HumanHandPose, t: f64) -> HumanHandPose {
        let (a, b) = (a.to_array(), b.to_array());
        HumanHandPose::from_array(&std::array::from_fn(|i| a[i] + t * (b[i] - a[i])))
    }

    /// Every angle clamped into [`JOINT_RANGES_RAD`].
    pub fn clamped(&self) -> HumanHandPose {
        let a = self.to_array();
        HumanHandPose::from_array(&std::array::from_fn(|i| {
            a[i].clamp(JOINT_RANGES_RAD[i].0, JOINT_RANGES_RAD[i].1)
        }))
    }

    /// Whether every angle lies within [`JOINT_RANGES_RAD`] (inclusive).
    pub fn within_ranges(&self) -> bool {
        self.to_array()
            .iter()
            .zip(JOINT_RANGES_RAD)
            .all(|(v, (lo, hi))| (lo..=hi).contains(v))
    }

    /// Largest absolute angle difference to `other`, radians.
    pub fn max_difference_rad(&self, other: &HumanHandPose) -> f64 {
        self.to_array()
            .iter()
            .zip(other.to_array())
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn named_poses_are_within_the_ranges() {
        for pose in [
            HumanHandPose::open(),
            HumanHandPose::open_spread(),
            HumanHandPose::fist(),
            HumanHandPose::relaxed(),
            HumanHandPose::cylinder_grasp(),
        ] {
            assert!(pose.within_ranges(), "{pose:?}");
        }
        assert_eq!(JOINT_RANGES_RAD[5], FINGER_RANGES[1], "index abduction");
        assert_eq!(JOINT_RANGES_RAD[1], THUMB_RANGES[1], "thumb abduction");
    }

    #[test]
    fn array_round_trip_follows_the_names() {
        let mut pose = HumanHandPose::open();
        pose.finger_mut(Finger::Ring).unwrap().pip_flexion_rad = 0.7;
        pose.thumb.ip_flexion_rad = 0.3;
        let a = pose.to_array();
        assert_eq!(
            a[ANGLE_NAMES
                .iter()
                .position(|n| *n == "ring_pip_flexion")
                .unwrap()],
            0.7
        );
        assert_eq!(
            a[ANGLE_NAMES
                .iter()
                .position(|n| *n == "thumb_ip_flexion")
                .unwrap()],
            0.3
        );
        assert_eq!(HumanHandPose::from_array(&a), pose);
        assert!(pose.finger(Finger::Thumb).is_none());
    }

    #[test]
    fn lerp_hits_both_ends_and_the_middle() {
        let (a, b) = (HumanHandPose::open(), HumanHandPose::fist());
        assert_eq!(HumanHandPose::lerp(&a, &b, 0.0), a);
        assert!(HumanHandPose::lerp(&a, &b, 1.0).max_difference_rad(&b) < 1e-15);
        let mid = HumanHandPose::lerp(&a, &b, 0.5);
        assert!((mid.fingers[2].pip_flexion_rad - 0.875).abs() < 1e-15);
        let wild = HumanHandPose::from_array(&[5.0; POSE_ANGLES]);
        assert!(!wild.within_ranges());
        assert!(wild.clamped().within_ranges());
    }
}
