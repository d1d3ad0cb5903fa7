//! Synthetic users for the evaluation set: the project's simulated glove (a kinematic human
//! hand, [`retarget::human_hand`]) worn by users the defaults were never tuned on. Each user
//! has a hand size, its own proportions ([`HandVariation`]: thumb ±15 %, index and middle
//! ±10 %, palm breadth ±10 %, the thumb's base moved, the glove's tip markers ±5 mm off the
//! tips), a glove turned on the hand and keypoint jitter, all drawn from a seed, and performs
//! a task-like sequence (grasp, release, pinches) or the four pinches in turn, in the lab's
//! 21-point layout at the Rokoko glove's 25 distinct frames per second. Unlike the transformed
//! copies of a real recording, here the human pinches are known to be real thumb-to-finger
//! contacts of the simulated hand (its fingertips touch; the glove reports their markers).

use nalgebra::{Rotation3, Unit, Vector3};
use retarget::KeypointLayout;
use retarget::human_hand::{
    HandVariation, HumanHandShape, Motion, MotionKind, SimGlove, SplitMix64, VariationRanges,
};

use super::variants::TimedFrame;

/// Frames per second of a synthetic recording (the Rokoko glove's distinct frames).
pub const RATE_HZ: f64 = 25.0;
/// Length of a synthetic recording, seconds.
pub const DURATION_S: f64 = 30.0;
/// Hand scales drawn, relative to the average hand.
pub const SCALE_RANGE: (f64, f64) = (0.85, 1.15);
/// Largest angle the glove is turned on the hand, degrees (about a random axis).
pub const MAX_TURN_DEG: f64 = 10.0;
/// The fractional part of the golden ratio (low-discrepancy steps between users' sizes).
const GOLDEN_FRACTION: f64 = 0.618_033_988_749_895;
/// Keypoint jitter, standard deviation per coordinate, metres.
pub const JITTER_M: f64 = 0.001;

/// One synthetic user and what they do.
#[derive(Debug, Clone, PartialEq)]
pub struct SyntheticUser {
    /// Name for the recording's file: `synthetic-<k>-<motion>-s<scale>`.
    pub name: String,
    /// Hand scale.
    pub scale: f64,
    /// Angle the glove is turned on the hand, degrees.
    pub turn_deg: f64,
    /// The hand's proportions.
    pub variation: HandVariation,
    /// The frames, from time 0.
    pub frames: Vec<TimedFrame>,
}

/// The layout synthetic recordings are written in.
pub const LAYOUT: KeypointLayout = KeypointLayout::Lab21;

/// User `k` of the stream seeded `seed` (odd users do the task-like sequence, even ones the
/// pinches).
pub fn synthetic_user(seed: u64, k: u64) -> Result<SyntheticUser, retarget::Error> {
    let mut rng = SplitMix64::keyed(seed, k);
    // Golden-ratio steps from a seeded start: any few consecutive users spread over the range.
    let start = SplitMix64::new(seed).next_f64();
    let spread = (start + k as f64 * GOLDEN_FRACTION).fract();
    let scale = SCALE_RANGE.0 + (SCALE_RANGE.1 - SCALE_RANGE.0) * spread;
    let axis = Vector3::new(
        rng.next_gaussian(),
        rng.next_gaussian(),
        rng.next_gaussian(),
    );
    let turn_deg = MAX_TURN_DEG * (2.0 * rng.next_f64() - 1.0);
    let turn = match Unit::try_new(axis, 1e-9) {
        Some(axis) => Rotation3::from_axis_angle(&axis, turn_deg.to_radians()),
        None => Rotation3::identity(),
    };
    let kind = if k % 2 == 1 {
        MotionKind::TaskLike
    } else {
        MotionKind::Pinches
    };
    let variation = HandVariation::draw(&mut rng, &VariationRanges::DEFAULT);
    let shape = variation.apply(HumanHandShape::average().scaled(scale));
    let motion = Motion::new(kind, kind.default_period_s(), &shape)?;
    let glove = SimGlove::new(shape, motion, LAYOUT)?
        .with_misalignment(turn)
        .with_jitter(JITTER_M, rng.next_u64())?;
    let count = (DURATION_S * RATE_HZ) as i64;
    let frames = (0..count)
        .map(|i| {
            let t_s = i as f64 / RATE_HZ;
            TimedFrame {
                t_ns: (t_s * 1e9).round() as i64,
                points: glove.frame(t_s).0,
            }
        })
        .collect();
    let motion_name = match kind {
        MotionKind::TaskLike => "tasklike",
        _ => "pinches",
    };
    Ok(SyntheticUser {
        name: format!("synthetic-{k}-{motion_name}-s{scale:.2}"),
        scale,
        turn_deg,
        variation,
        frames,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn users_are_reproducible_distinct_and_within_their_ranges() {
        let a = synthetic_user(7, 1).unwrap();
        assert_eq!(a, synthetic_user(7, 1).unwrap());
        let b = synthetic_user(7, 2).unwrap();
        assert_ne!(a.scale, b.scale);
        for u in [&a, &b] {
            assert!((SCALE_RANGE.0..=SCALE_RANGE.1).contains(&u.scale));
            assert!(u.turn_deg.abs() <= MAX_TURN_DEG);
            assert_eq!(u.frames.len(), 750);
            assert!(u.frames.iter().all(|f| f.points.len() == LAYOUT.len()));
        }
        assert!(a.name.contains("tasklike") && b.name.contains("pinches"));
        assert_ne!(a.variation, b.variation);
        assert!((0.85..=1.15).contains(&a.variation.thumb_length));
        assert_eq!(a.frames[1].t_ns, 40_000_000);
    }
}
