//! A whole calibration: captures in, the fitted transform and its before/after errors out.

use retarget::{CalibrationTransform, EmbodimentCatalog, HandModel, RetargetConfig};

use crate::capture::CapturedPose;
use crate::digit_scales::SEARCH_EVALUATIONS_PER_DIGIT;
use crate::error::Error;
use crate::objective::{Evaluation, Objective};
use crate::optimiser::{Trace, bayesian_optimise, polish};
use crate::poses::PoseSet;
use crate::search_space::{Parameters, to_unit, transform};
use crate::settings::{CalibrationModel, CalibrationSettings};

/// What the fit reports after each evaluation (for a progress bar).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitProgress {
    /// Evaluations done.
    pub done: usize,
    /// Evaluations in the budget.
    pub budget: usize,
    /// Best objective so far, radians.
    pub best: f64,
}

/// The result of a calibration.
#[derive(Debug, Clone, PartialEq)]
pub struct Calibration {
    /// The fitted transform.
    pub transform: CalibrationTransform,
    /// The objective with no calibration (identity transform).
    pub before: Evaluation,
    /// The objective with the fitted transform.
    pub after: Evaluation,
    /// Every evaluation made: the Bayesian optimisation's, then the polish's.
    pub trace: Trace,
    /// The model fitted.
    pub model: CalibrationModel,
    /// Evaluations of the per-digit search (0 for the global model).
    pub digit_evaluations: usize,
}

impl Calibration {
    /// Every objective evaluation the fit made.
    pub fn evaluations(&self) -> usize {
        self.trace.evaluations.len() + self.digit_evaluations
    }
}

/// Everything a fit needs besides the captures.
#[derive(Debug, Clone, Copy)]
pub struct FitInputs<'a> {
    /// The robot hand.
    pub model: &'a HandModel,
    /// The station's retargeting configuration.
    pub config: &'a RetargetConfig,
    /// The embodiment catalog the configuration names its embodiment from.
    pub catalog: &'a EmbodimentCatalog,
    /// The seven poses with their ground truth.
    pub poses: &'a PoseSet,
    /// Bounds, budget, weights.
    pub settings: &'a CalibrationSettings,
}

/// Owned fit inputs for the built-in setup: the ORCA v1 right hand, the default retargeting
/// configuration, the built-in embodiments, the ORCA v1 poses, the default settings.
#[derive(Debug, Clone)]
pub struct BuiltinInputs {
    /// The ORCA v1 right hand.
    pub model: HandModel,
    /// The default retargeting configuration.
    pub config: RetargetConfig,
    /// The built-in embodiment catalog.
    pub catalog: EmbodimentCatalog,
    /// The ORCA v1 poses.
    pub poses: PoseSet,
    /// The default settings.
    pub settings: CalibrationSettings,
}

impl BuiltinInputs {
    /// The built-in setup.
    pub fn orca_v1() -> BuiltinInputs {
        BuiltinInputs {
            model: HandModel::orca_v1_right(),
            config: RetargetConfig::default(),
            catalog: EmbodimentCatalog::builtin(),
            poses: PoseSet::orca_v1(),
            settings: CalibrationSettings::default(),
        }
    }

    /// Borrowed as fit inputs.
    pub fn inputs(&self) -> FitInputs<'_> {
        FitInputs {
            model: &self.model,
            config: &self.config,
            catalog: &self.catalog,
            poses: &self.poses,
            settings: &self.settings,
        }
    }
}

/// Fit the calibration transform to `captures` by Bayesian optimisation and Nelder–Mead
/// polishes of its best point and of the best point of another basin (at least 0.15 away in
/// the unit cube; this second polish recovered 3 of the 9 synthetic users whose rotation
/// the first alone missed by more than 3°), calling `progress` after every evaluation.
///
/// `cancelled` is asked before every evaluation and once more before returning: when it says
/// true the fit stops there with [`Error::Interrupted`] and returns nothing of what it found
/// (the caller decides what cancels, e.g. Ctrl-C; pass `&|| false` for a fit that cannot be
/// cancelled).
pub fn calibrate(
    inputs: FitInputs<'_>,
    captures: &[CapturedPose],
    progress: &mut dyn FnMut(FitProgress),
    cancelled: &dyn Fn() -> bool,
) -> Result<Calibration, Error> {
    inputs.settings.validate()?;
    let not_cancelled = || {
        if cancelled() {
            Err(Error::Interrupted)
        } else {
            Ok(())
        }
    };
    let mut objective = Objective::new(
        inputs.model,
        inputs.config,
        inputs.catalog,
        inputs.poses,
        captures,
        inputs.settings.pinch_weight_rad_per_m,
    )?;
    not_cancelled()?;
    let before = objective.evaluate(&CalibrationTransform::IDENTITY)?;
    let optimiser = &inputs.settings.optimiser;
    let model = inputs.settings.model;
    let digit_budget = match model {
        CalibrationModel::Global => 0,
        CalibrationModel::PerDigit => 5 * SEARCH_EVALUATIONS_PER_DIGIT,
    };
    let budget = optimiser.evaluations + 2 * optimiser.polish_evaluations + digit_budget;
    let mut done = 0;
    let mut best = f64::INFINITY;
    let mut f = |x: &Parameters| -> Result<f64, Error> {
        not_cancelled()?;
        let value = objective.evaluate(&transform(x))?.value;
        done += 1;
        best = best.min(value);
        progress(FitProgress { done, budget, best });
        Ok(value)
    };
    let bounds = &inputs.settings.bounds;
    let trace = bayesian_optimise(&mut f, bounds, optimiser)?;
    let trace = polish_twice(&mut f, bounds, trace, optimiser.polish_evaluations)?;
    not_cancelled()?;
    let (x, _) = trace.best().ok_or_else(no_evaluation)?;
    let mut fitted = transform(&x);
    let mut after = objective.evaluate(&fitted)?;
    let mut digit_evaluations = 0;
    if model == CalibrationModel::PerDigit {
        not_cancelled()?;
        let (per_digit, made) = objective.digit_scales_searched(&fitted, cancelled)?;
        digit_evaluations = made;
        let with_digits = objective.evaluate(&per_digit)?;
        if with_digits.value < after.value {
            (fitted, after) = (per_digit, with_digits);
        }
        let best = after.value;
        progress(FitProgress {
            done: budget,
            budget,
            best,
        });
    }
    not_cancelled()?;
    Ok(Calibration {
        transform: fitted,
        before,
        after,
        trace,
        model,
        digit_evaluations,
    })
}

fn no_evaluation() -> Error {
    Error::Optimiser("no evaluation was made".into())
}

/// The Bayesian `trace` extended by the polish of its best point and, when there is one, of
/// the best point of a second basin ([`second_basin`]).
fn polish_twice(
    f: &mut crate::optimiser::ObjectiveFn<'_>,
    bounds: &crate::settings::ParameterBounds,
    mut trace: Trace,
    evaluations: usize,
) -> Result<Trace, Error> {
    let (x, _) = trace.best().ok_or_else(no_evaluation)?;
    let polished = polish(f, bounds, x, evaluations)?;
    let second = second_basin(&trace, bounds, &x);
    trace.evaluations.extend(polished.evaluations);
    if let Some(start) = second {
        let polished = polish(f, bounds, start, evaluations)?;
        trace.evaluations.extend(polished.evaluations);
    }
    Ok(trace)
}

/// The best evaluated point at least 0.15 (unit-cube distance) from `best`.
fn second_basin(
    trace: &Trace,
    bounds: &crate::settings::ParameterBounds,
    best: &Parameters,
) -> Option<Parameters> {
    let unit = |x: &Parameters| to_unit(bounds, x);
    let ub = unit(best);
    trace
        .evaluations
        .iter()
        .filter(|(x, _)| {
            let u = unit(x);
            u.iter()
                .zip(&ub)
                .map(|(a, c)| (a - c).powi(2))
                .sum::<f64>()
                .sqrt()
                > 0.15
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|e| e.0)
}

#[cfg(test)]
mod tests {
    use std::cell::Cell;

    use super::*;
    use crate::schedule::CaptureSchedule;
    use crate::synthetic_study::CAPTURE_RATE_HZ;
    use crate::synthetic_user::SyntheticUser;
    use crate::{POSE_NAMES, capture_pose, human_copies};

    /// A small budget: 12 Bayesian evaluations, 2 × 10 polish.
    fn small() -> BuiltinInputs {
        let mut builtin = BuiltinInputs::orca_v1();
        builtin.settings.optimiser.evaluations = 12;
        builtin.settings.optimiser.initial_design = 6;
        builtin.settings.optimiser.polish_evaluations = 10;
        builtin
    }

    /// A synthetic user's seven captures.
    fn captures(inputs: FitInputs<'_>) -> Vec<CapturedPose> {
        let copies = human_copies(inputs.model, inputs.poses).unwrap();
        let user = SyntheticUser::random(4);
        let layout = inputs.config.layout;
        let schedule = CaptureSchedule::default();
        POSE_NAMES
            .iter()
            .enumerate()
            .map(|(k, name)| {
                let frames = user
                    .capture_frames(layout, &schedule, &copies, k, CAPTURE_RATE_HZ)
                    .unwrap();
                let frames = frames.iter().map(Vec::as_slice);
                capture_pose(name, layout, frames, &inputs.settings.capture).unwrap()
            })
            .collect()
    }

    /// Fits with a cancel that turns true once `after` evaluations are done; returns the
    /// result and the evaluations made.
    fn fit_cancelled_after(after: usize) -> (Result<Calibration, Error>, usize) {
        let builtin = small();
        let inputs = builtin.inputs();
        let captures = captures(inputs);
        let done = Cell::new(0);
        let fit = calibrate(inputs, &captures, &mut |p| done.set(p.done), &|| {
            done.get() >= after
        });
        (fit, done.get())
    }

    #[test]
    fn a_fit_left_alone_spends_its_budget() {
        let (fit, done) = fit_cancelled_after(usize::MAX);
        let fit = fit.unwrap();
        assert_eq!(done, fit.trace.evaluations.len());
        assert!(done > 12, "the polish ran too: {done}");
    }

    #[test]
    fn a_fit_cancelled_before_it_starts_evaluates_nothing() {
        let (fit, done) = fit_cancelled_after(0);
        assert_eq!(fit.unwrap_err(), Error::Interrupted);
        assert_eq!(done, 0);
    }

    #[test]
    fn a_fit_cancelled_in_the_bayesian_search_stops_there_with_no_result() {
        for after in [3, 9] {
            let (fit, done) = fit_cancelled_after(after);
            assert_eq!(
                fit.unwrap_err(),
                Error::Interrupted,
                "cancelled after {after}"
            );
            assert_eq!(done, after, "no evaluation after the cancel");
        }
    }

    #[test]
    fn a_fit_cancelled_in_the_polish_stops_there_with_no_result() {
        for after in [14, 25] {
            let (fit, done) = fit_cancelled_after(after);
            assert_eq!(
                fit.unwrap_err(),
                Error::Interrupted,
                "cancelled after {after}"
            );
            assert_eq!(done, after, "no evaluation after the cancel");
        }
    }
}
