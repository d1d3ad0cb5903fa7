//! Synthetic users for testing and benchmarking the calibration, generated with the project's
//! own human hand model: a hand of some size, a glove whose finger sensors are misaligned with
//! its palm by a rotation, and keypoint noise.
//!
//! The user copies the seven calibration poses from the robot hand
//! ([`human_copies`](crate::human_copies)) with the simulated glove's calibration-poses
//! motion ([`Motion::calibration_poses`]); every key
//! vector the retargeter reads is then `R_g · s · v` for the average hand's `v` (hand scale
//! `s`, misalignment `R_g`), plus noise. If the reference transform `c₀·R₀` calibrates the
//! average, aligned hand, the transform that makes this user look like it is
//! `(c₀ / s) · R₀ · R_gᵀ`: that is the truth a calibration should recover.

use nalgebra::{Point3, Rotation3};
use retarget::human_hand::{
    HandVariation, HumanHandPose, HumanHandShape, Motion, SimGlove, SplitMix64, VariationRanges,
    WristSway,
};
use retarget::{CalibrationTransform, KeypointLayout};

use crate::error::Error;
use crate::schedule::CaptureSchedule;

/// A synthetic user.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SyntheticUser {
    /// Hand size relative to the model's average hand.
    pub hand_scale: f64,
    /// Glove misalignment as roll, pitch, yaw about the palm axes, radians.
    pub glove_rpy_rad: [f64; 3],
    /// Keypoint noise, standard deviation per axis, metres.
    pub noise_sd_m: f64,
    /// Seed of the noise.
    pub seed: u64,
    /// The hand's proportions ([`HandVariation::NONE`]: a uniformly scaled average hand, for
    /// which [`SyntheticUser::true_transform`] is exact).
    pub variation: HandVariation,
}

/// The population of the acceptance test: hand sizes 0.8–1.25×, misalignment up to ±20°
/// about each axis, 2 mm noise.
pub const POPULATION_SCALE: (f64, f64) = (0.8, 1.25);
/// Largest misalignment about each axis in the population, degrees.
pub const POPULATION_ANGLE_DEG: f64 = 20.0;
/// Keypoint noise of the population, metres.
pub const POPULATION_NOISE_M: f64 = 0.002;

/// The pose a user who does not follow the hand holds while pose `k` (capture order) is
/// captured: the previous one; at the first pose, the open hand (the user has not started).
/// The wrongly held pose of the fit check's benchmark and of `--simulate-wrong-pose`.
pub fn wrongly_held_pose(k: usize) -> usize {
    match k {
        0 => crate::poses::POSE_NAMES
            .iter()
            .position(|p| *p == "open")
            .unwrap_or(0),
        k => k - 1,
    }
}

impl SyntheticUser {
    /// A user drawn from the acceptance population, deterministic in `seed`.
    pub fn random(seed: u64) -> SyntheticUser {
        let mut rng = SplitMix64::keyed(seed, 0x5EED_CA1B);
        let (lo, hi) = POPULATION_SCALE;
        let hand_scale = lo + (hi - lo) * rng.next_f64();
        let a = POPULATION_ANGLE_DEG.to_radians();
        let glove_rpy_rad = std::array::from_fn(|_| a * (2.0 * rng.next_f64() - 1.0));
        SyntheticUser {
            hand_scale,
            glove_rpy_rad,
            noise_sd_m: POPULATION_NOISE_M,
            seed,
            variation: HandVariation::NONE,
        }
    }

    /// A user of the acceptance population whose hand also has its own proportions
    /// ([`HandVariation`] with its default ranges), deterministic in `seed`. A global scale
    /// and rotation cannot fit such a hand exactly: [`SyntheticUser::true_transform`] gives the
    /// one for its size and glove, the best a global model can aim at.
    pub fn random_non_uniform(seed: u64) -> SyntheticUser {
        let mut rng = SplitMix64::keyed(seed, 0x0DD_5A9E);
        SyntheticUser {
            variation: HandVariation::draw(&mut rng, &VariationRanges::DEFAULT),
            ..SyntheticUser::random(seed)
        }
    }

    /// The average hand in an aligned glove without noise: the reference user.
    pub fn reference() -> SyntheticUser {
        SyntheticUser {
            hand_scale: 1.0,
            glove_rpy_rad: [0.0; 3],
            noise_sd_m: 0.0,
            seed: 0,
            variation: HandVariation::NONE,
        }
    }

    /// The user's hand: the average hand at their size, with their proportions.
    pub fn shape(&self) -> HumanHandShape {
        self.variation
            .apply(HumanHandShape::average().scaled(self.hand_scale))
    }

    /// The glove misalignment.
    pub fn misalignment(&self) -> Rotation3<f64> {
        let [r, p, y] = self.glove_rpy_rad;
        Rotation3::from_euler_angles(r, p, y)
    }

    /// The user's simulated glove performing `poses` (the human versions of the seven
    /// calibration poses, see [`human_copies`](crate::human_copies)) on `schedule`, with a
    /// gently swaying wrist.
    pub fn glove(
        &self,
        layout: KeypointLayout,
        schedule: &CaptureSchedule,
        poses: &[HumanHandPose; 7],
    ) -> Result<SimGlove, Error> {
        let shape = self.shape();
        let motion = Motion::calibration_poses(*poses, schedule.slot_s)?;
        Ok(SimGlove::new(shape, motion, layout)?
            .with_wrist_sway(WristSway::GENTLE)?
            .with_misalignment(self.misalignment())
            .with_jitter(self.noise_sd_m, self.seed)?)
    }

    /// The frames of pose `k`'s capture window at `rate_hz`.
    pub fn capture_frames(
        &self,
        layout: KeypointLayout,
        schedule: &CaptureSchedule,
        poses: &[HumanHandPose; 7],
        k: usize,
        rate_hz: f64,
    ) -> Result<Vec<Vec<Point3<f64>>>, Error> {
        let glove = self.glove(layout, schedule, poses)?;
        let (start, end) = schedule.capture_window(k);
        let count = ((end - start) * rate_hz).floor() as usize;
        Ok((0..count)
            .map(|i| glove.frame(start + i as f64 / rate_hz).0)
            .collect())
    }

    /// The transform that calibrates this user, given the reference user's calibration.
    pub fn true_transform(&self, reference: &CalibrationTransform) -> CalibrationTransform {
        let rotation = reference.rotation() * self.misalignment().inverse();
        let (roll_rad, pitch_rad, yaw_rad) = rotation.euler_angles();
        CalibrationTransform {
            scale: reference.scale / self.hand_scale,
            roll_rad,
            pitch_rad,
            yaw_rad,
            digit_scale: [1.0; 5],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn the_true_transform_maps_the_user_onto_the_reference() {
        let user = SyntheticUser::random(11);
        let reference = CalibrationTransform {
            scale: 0.97,
            roll_rad: 0.02,
            pitch_rad: -0.03,
            yaw_rad: 0.05,
            ..CalibrationTransform::IDENTITY
        };
        let truth = user.true_transform(&reference);
        let v = Vector3::new(0.01, 0.08, 0.02);
        let seen = user.misalignment() * v * user.hand_scale;
        assert!((truth.apply(&seen) - reference.apply(&v)).norm() < 1e-12);
    }

    #[test]
    fn the_wrongly_held_pose_is_the_previous_one_or_the_open_hand_first() {
        let open = crate::poses::POSE_NAMES
            .iter()
            .position(|p| *p == "open")
            .unwrap();
        assert_eq!(wrongly_held_pose(0), open);
        assert_eq!(crate::poses::POSE_NAMES[wrongly_held_pose(0)], "open");
        assert_eq!(open, 4, "the capture order's open hand");
        for k in 1..crate::poses::POSE_NAMES.len() {
            assert_eq!(wrongly_held_pose(k), k - 1);
        }
    }

    #[test]
    fn the_population_spans_its_ranges() {
        let users: Vec<_> = (0..200).map(SyntheticUser::random).collect();
        let scales: Vec<f64> = users.iter().map(|u| u.hand_scale).collect();
        assert!(scales.iter().all(|s| (0.8..=1.25).contains(s)));
        assert!(scales.iter().any(|&s| s < 0.85) && scales.iter().any(|&s| s > 1.2));
        let a = 20f64.to_radians();
        assert!(
            users
                .iter()
                .all(|u| u.glove_rpy_rad.iter().all(|x| x.abs() <= a))
        );
        assert_eq!(SyntheticUser::random(5), SyntheticUser::random(5));
    }

    #[test]
    fn a_non_uniform_user_is_the_same_user_with_its_own_proportions() {
        let (plain, varied) = (
            SyntheticUser::random(9),
            SyntheticUser::random_non_uniform(9),
        );
        assert_eq!(plain.variation, HandVariation::NONE);
        assert_ne!(varied.variation, HandVariation::NONE);
        assert_eq!(
            SyntheticUser {
                variation: HandVariation::NONE,
                ..varied
            },
            plain
        );
        assert!((0.85..=1.15).contains(&varied.variation.thumb_length));
        assert_eq!(varied, SyntheticUser::random_non_uniform(9));
    }
}
