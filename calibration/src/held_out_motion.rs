//! A synthetic user's held-out motion: the four pinches in turn, a motion the fit never saw
//! (it sees the seven held poses only), both as the user's glove reports it and as the hand
//! holds it. The glove's report carries the user's misalignment, the tip markers' offsets
//! and jitter; the hand as held has none of them. A calibration serves the second: with the
//! glove turned on the hand, a robot that copies the report copies the misalignment too.

use nalgebra::Point3;
use retarget::KeypointLayout;
use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove};

use crate::error::Error;
use crate::synthetic_user::SyntheticUser;

/// Frames per second of the held-out motion (the Rokoko glove's distinct frames).
pub const HELD_OUT_RATE_HZ: f64 = 25.0;
/// Length of the held-out motion, seconds.
pub const HELD_OUT_DURATION_S: f64 = 30.0;
/// The glove's jitter in the held-out motion, standard deviation per coordinate, metres.
pub const HELD_OUT_JITTER_M: f64 = 0.001;

/// One frame of the held-out motion, in the layout asked for, metres, the hand at the glove
/// frame's origin.
#[derive(Debug, Clone, PartialEq)]
pub struct HeldOutFrame {
    /// Capture time from the motion's start, nanoseconds.
    pub t_ns: i64,
    /// What the glove reports.
    pub reported: Vec<Point3<f64>>,
    /// Where the hand is: no misalignment, no tip-marker offset, no jitter.
    pub as_held: Vec<Point3<f64>>,
}

/// `user`'s held-out motion in `layout`.
pub fn held_out_pinches(
    user: &SyntheticUser,
    layout: KeypointLayout,
) -> Result<Vec<HeldOutFrame>, Error> {
    let shape = user.shape();
    let kind = MotionKind::Pinches;
    let motion = Motion::new(kind, kind.default_period_s(), &shape)?;
    let glove = SimGlove::new(shape, motion.clone(), layout)?
        .with_misalignment(user.misalignment())
        .with_jitter(HELD_OUT_JITTER_M, user.seed ^ 0x5EED)?;
    let hand = HumanHandShape {
        tip_markers_m: [[0.0; 3]; 5],
        ..shape
    };
    let held = SimGlove::new(hand, motion, layout)?;
    let count = (HELD_OUT_DURATION_S * HELD_OUT_RATE_HZ).round() as u32;
    Ok((0..count)
        .map(|i| {
            let t_s = f64::from(i) / HELD_OUT_RATE_HZ;
            HeldOutFrame {
                t_ns: (t_s * 1e9).round() as i64,
                reported: glove.frame(t_s).0,
                as_held: held.frame(t_s).0,
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_report_differs_from_the_hand_by_the_glove_alone() {
        let user = SyntheticUser::random_non_uniform(3);
        let frames = held_out_pinches(&user, KeypointLayout::Lab21).unwrap();
        assert_eq!(frames.len(), 750);
        assert_eq!(frames[1].t_ns, 40_000_000);
        // The wrist is a palm landmark: only jitter moves it.
        let wrist = KeypointLayout::Lab21.wrist();
        let f = &frames[100];
        assert!((f.reported[wrist] - f.as_held[wrist]).norm() < 0.01);
        // A fingertip is turned with the glove: centimetres off for a turn of degrees.
        let tip = *KeypointLayout::Lab21
            .chain(retarget::Finger::Index)
            .last()
            .unwrap();
        let off: f64 = frames
            .iter()
            .map(|f| (f.reported[tip] - f.as_held[tip]).norm())
            .sum::<f64>()
            / frames.len() as f64;
        assert!(off > 0.005, "index tip {off} m off");
        let aligned = SyntheticUser {
            glove_rpy_rad: [0.0; 3],
            noise_sd_m: 0.0,
            variation: retarget::human_hand::HandVariation::NONE,
            ..user
        };
        let same = held_out_pinches(&aligned, KeypointLayout::Lab21).unwrap();
        let jitter_only = (same[100].reported[tip] - same[100].as_held[tip]).norm();
        assert!(jitter_only < 0.006, "{jitter_only}");
    }
}
