//! The synthetic-user study behind the calibration's acceptance figures (test and benchmark
//! share it): calibrate a synthetic user, compare the fit with the user's true transform, and
//! measure the joint error on held-out poses with and without the calibration.
//!
//! - **Reference.** The average hand in an aligned glove without noise, calibrated with a
//!   generous budget (120 Bayesian + 150 polish evaluations): `c₀·R₀`. A user's truth is
//!   [`SyntheticUser::true_transform`] of it.
//! - **Held-out poses.** Ten robot configurations that are none of the seven (blends of two
//!   calibration poses at 30–70 %), copied by the human hand model. Their ground truth is what
//!   the retargeter commands for the reference user under `c₀·R₀`: the command a perfectly
//!   calibrated user gets. A user performs them with their own hand size, misaligned glove and
//!   one frame of noise each; the error is the RMS over poses and free joints of the
//!   retargeter's command minus the ground truth, with no calibration and with the fitted one.

use nalgebra::Point3;
use retarget::human_hand::{HumanHandPose, HumanHandShape, SplitMix64, misalign};
use retarget::{CalibrationTransform, KeypointLayout, Retargeter};

use crate::capture::{CapturedPose, capture_pose};
use crate::error::Error;
use crate::fit::{Calibration, FitInputs, calibrate};
use crate::human_copy::{human_copies, human_copy};
use crate::objective::{Objective, cold_solve_config};
use crate::optimiser::random_search;
use crate::poses::POSE_NAMES;
use crate::schedule::CaptureSchedule;
use crate::search_space::transform;
use crate::settings::CalibrationSettings;
use crate::synthetic_user::SyntheticUser;

/// Glove rate of the simulated captures, Hz.
pub const CAPTURE_RATE_HZ: f64 = 25.0;

/// Held-out poses per user.
pub const HELD_OUT_POSES: usize = 10;

/// One user's outcome.
#[derive(Debug, Clone, PartialEq)]
pub struct UserOutcome {
    /// The user.
    pub user: SyntheticUser,
    /// The calibration.
    pub calibration: Calibration,
    /// The user's true transform.
    pub truth: CalibrationTransform,
    /// `fitted scale / true scale − 1`.
    pub scale_error: f64,
    /// Angle of `R_fittedᵀ · R_true`, degrees.
    pub rotation_error_deg: f64,
    /// Held-out joint RMS error with no calibration, radians.
    pub held_out_before_rad: f64,
    /// Held-out joint RMS error with the fitted calibration, radians.
    pub held_out_after_rad: f64,
}

/// The study's fixed parts: the copies, the reference calibration, the held-out poses.
pub struct Study<'a> {
    inputs: FitInputs<'a>,
    schedule: CaptureSchedule,
    copies: [HumanHandPose; 7],
    reference: CalibrationTransform,
    held_out: Vec<(HumanHandPose, Vec<f64>)>,
}

impl std::fmt::Debug for Study<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Study")
            .field("reference", &self.reference)
            .field("held_out", &self.held_out.len())
            .finish()
    }
}

impl<'a> Study<'a> {
    /// Set the study up: copy the poses, calibrate the reference user, build the held-out
    /// poses and their ground truth.
    pub fn new(inputs: FitInputs<'a>) -> Result<Study<'a>, Error> {
        let schedule = CaptureSchedule::default();
        let copies = human_copies(inputs.model, inputs.poses)?;
        let mut generous = inputs.settings.clone();
        generous.optimiser.evaluations = 120;
        generous.optimiser.polish_evaluations = 150;
        let mut study = Study {
            inputs,
            schedule,
            copies,
            reference: CalibrationTransform::IDENTITY,
            held_out: Vec::new(),
        };
        let captures = study.captures(&SyntheticUser::reference())?;
        let reference_fit = calibrate(
            FitInputs {
                settings: &generous,
                ..inputs
            },
            &captures,
            &mut |_| {},
            &|| false,
        )?;
        study.reference = reference_fit.transform;
        let model = inputs.model;
        let shape = HumanHandShape::average();
        let layout = inputs.config.layout;
        let mut retargeter = study.retargeter()?;
        retargeter.set_calibration(study.reference)?;
        let configs: Vec<Vec<f64>> = inputs
            .poses
            .poses
            .iter()
            .map(|p| p.joint_vector(model))
            .collect::<Result<_, _>>()?;
        for j in 0..HELD_OUT_POSES {
            let (a, b) = (&configs[j % 7], &configs[(3 * j + 1) % 7]);
            let t = 0.3 + 0.4 * (j as f64 / (HELD_OUT_POSES - 1) as f64);
            let q: Vec<f64> = a.iter().zip(b).map(|(x, y)| x + t * (y - x)).collect();
            let pose = human_copy(&shape, model, &q)?;
            retargeter.reset();
            let truth = retargeter.retarget(&shape.keypoints(&pose, layout), 1.0)?.q;
            study.held_out.push((pose, truth));
        }
        Ok(study)
    }

    /// The reference user's calibration `c₀·R₀`.
    pub fn reference(&self) -> &CalibrationTransform {
        &self.reference
    }

    fn retargeter(&self) -> Result<Retargeter, Error> {
        Ok(Retargeter::new(
            self.inputs.model.clone(),
            cold_solve_config(self.inputs.config),
            self.inputs.catalog,
        )?)
    }

    /// The user's seven accepted captures.
    pub fn captures(&self, user: &SyntheticUser) -> Result<Vec<CapturedPose>, Error> {
        let layout = self.inputs.config.layout;
        POSE_NAMES
            .iter()
            .enumerate()
            .map(|(k, name)| {
                let frames =
                    user.capture_frames(layout, &self.schedule, &self.copies, k, CAPTURE_RATE_HZ)?;
                capture_pose(
                    name,
                    layout,
                    frames.iter().map(Vec::as_slice),
                    &self.inputs.settings.capture,
                )
            })
            .collect()
    }

    /// Calibrate `user` and measure the outcome.
    pub fn run_user(&self, user: &SyntheticUser) -> Result<UserOutcome, Error> {
        self.run_user_with(user, self.inputs.settings)
    }

    /// Calibrate `user` with `settings` (another model or budget; the reference and the
    /// held-out truth stay the study's) and measure the outcome.
    pub fn run_user_with(
        &self,
        user: &SyntheticUser,
        settings: &CalibrationSettings,
    ) -> Result<UserOutcome, Error> {
        let captures = self.captures(user)?;
        let inputs = FitInputs {
            settings,
            ..self.inputs
        };
        let calibration = calibrate(inputs, &captures, &mut |_| {}, &|| false)?;
        let truth = user.true_transform(&self.reference);
        let fitted = calibration.transform;
        let held_out_before_rad = self.held_out_error(user, &CalibrationTransform::IDENTITY)?;
        let held_out_after_rad = self.held_out_error(user, &fitted)?;
        Ok(UserOutcome {
            user: *user,
            scale_error: fitted.scale / truth.scale - 1.0,
            rotation_error_deg: (fitted.rotation().inverse() * truth.rotation())
                .angle()
                .to_degrees(),
            truth,
            calibration,
            held_out_before_rad,
            held_out_after_rad,
        })
    }

    /// Best objective found for `user` by Bayesian optimisation and by random search, each
    /// with the Bayesian budget (no polish).
    pub fn bayes_vs_random(&self, user: &SyntheticUser) -> Result<(f64, f64), Error> {
        let captures = self.captures(user)?;
        let settings = self.inputs.settings;
        let mut objective = Objective::new(
            self.inputs.model,
            self.inputs.config,
            self.inputs.catalog,
            self.inputs.poses,
            &captures,
            settings.pinch_weight_rad_per_m,
        )?;
        let mut f =
            |x: &[f64; 4]| -> Result<f64, Error> { Ok(objective.evaluate(&transform(x))?.value) };
        let o = &settings.optimiser;
        let bayes = crate::optimiser::bayesian_optimise(&mut f, &settings.bounds, o)?;
        let random = random_search(&mut f, &settings.bounds, o.evaluations, o.seed)?;
        let best = |t: &crate::optimiser::Trace| t.best().map_or(f64::INFINITY, |b| b.1);
        Ok((best(&bayes), best(&random)))
    }

    fn held_out_error(
        &self,
        user: &SyntheticUser,
        calibration: &CalibrationTransform,
    ) -> Result<f64, Error> {
        let layout: KeypointLayout = self.inputs.config.layout;
        let shape = user.shape();
        let mut retargeter = self.retargeter()?;
        retargeter.set_calibration(*calibration)?;
        let mut noise = SplitMix64::keyed(user.seed, 0x0004_E1D0_u64);
        let (mut sum_sq, mut count) = (0.0, 0usize);
        for (pose, truth) in &self.held_out {
            let mut points: Vec<Point3<f64>> = shape.keypoints(pose, layout);
            misalign(&mut points, layout, &user.misalignment());
            for p in &mut points {
                for c in p.coords.iter_mut() {
                    *c += user.noise_sd_m * noise.next_gaussian();
                }
            }
            retargeter.reset();
            let q = retargeter.retarget(&points, 1.0)?.q;
            for &i in retargeter.free_dofs() {
                sum_sq += (q[i] - truth[i]).powi(2);
                count += 1;
            }
        }
        Ok((sum_sq / count.max(1) as f64).sqrt())
    }
}
