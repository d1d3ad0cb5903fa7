//! A whole calibration: captures in, the fitted transform and its before/after errors out.

use retarget::{CalibrationTransform, EmbodimentCatalog, HandModel, RetargetConfig};

use crate::capture::CapturedPose;
use crate::error::Error;
use crate::objective::{Evaluation, Objective};
use crate::optimiser::{Trace, bayesian_optimise, polish};
use crate::poses::PoseSet;
use crate::search_space::{Parameters, to_unit, transform};
use crate::settings::CalibrationSettings;

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
pub fn calibrate(
    inputs: FitInputs<'_>,
    captures: &[CapturedPose],
    progress: &mut dyn FnMut(FitProgress),
) -> Result<Calibration, Error> {
    inputs.settings.validate()?;
    let mut objective = Objective::new(
        inputs.model,
        inputs.config,
        inputs.catalog,
        inputs.poses,
        captures,
        inputs.settings.pinch_weight_rad_per_m,
    )?;
    let before = objective.evaluate(&CalibrationTransform::IDENTITY)?;
    let optimiser = &inputs.settings.optimiser;
    let budget = optimiser.evaluations + 2 * optimiser.polish_evaluations;
    let mut done = 0;
    let mut best = f64::INFINITY;
    let mut f = |x: &Parameters| -> Result<f64, Error> {
        let value = objective.evaluate(&transform(x))?.value;
        done += 1;
        best = best.min(value);
        progress(FitProgress { done, budget, best });
        Ok(value)
    };
    let bounds = &inputs.settings.bounds;
    let mut trace = bayesian_optimise(&mut f, bounds, optimiser)?;
    let no_evaluation = || Error::Optimiser("no evaluation was made".into());
    let (x, _) = trace.best().ok_or_else(no_evaluation)?;
    let polished = polish(&mut f, bounds, x, optimiser.polish_evaluations)?;
    let second = second_basin(&trace, bounds, &x);
    trace.evaluations.extend(polished.evaluations);
    if let Some(start) = second {
        let polished = polish(&mut f, bounds, start, optimiser.polish_evaluations)?;
        trace.evaluations.extend(polished.evaluations);
    }
    let (x, _) = trace.best().ok_or_else(no_evaluation)?;
    let fitted = transform(&x);
    let after = objective.evaluate(&fitted)?;
    Ok(Calibration {
        transform: fitted,
        before,
        after,
        trace,
    })
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
