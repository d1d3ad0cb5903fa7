//! Minimising the objective over the search space: Bayesian optimisation (the project's own:
//! a Gaussian process with a constant mean and a Matérn 5/2 kernel whose length scales are
//! fitted by maximum likelihood at every iteration, `gaussian_process.rs`; expected
//! improvement as the acquisition, `expected_improvement.rs`; our seeded Latin hypercube as
//! the initial design) and, as the baseline it must beat, random search with the same budget.
//! A short Nelder–Mead [`polish`] sharpens the Bayesian optimum.
//!
//! The Bayesian search, `N` evaluations in all: the initial design's points are evaluated in
//! turn; then, until `N` evaluations are made, the process is fitted to every evaluation so
//! far (in the unit cube of the bounds; length scales searched from the previous fit's, and
//! every 10 iterations from fresh starts as well) and the point of largest expected
//! improvement is evaluated.

use crate::error::Error;
use crate::expected_improvement::next_point;
use crate::gaussian_process::GaussianProcess;
use crate::nelder_mead::nelder_mead;
use crate::search_space::{Parameters, box_bounds, initial_design, to_unit, uniform_points};
use crate::settings::{OptimiserSettings, ParameterBounds};

/// Every evaluation an optimiser made, in order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Trace {
    /// `(point, objective)` per evaluation.
    pub evaluations: Vec<(Parameters, f64)>,
}

impl Trace {
    /// The best evaluation (lowest objective), if any.
    pub fn best(&self) -> Option<(Parameters, f64)> {
        self.evaluations
            .iter()
            .copied()
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// The best objective after each evaluation.
    pub fn best_so_far(&self) -> Vec<f64> {
        let mut best = f64::INFINITY;
        self.evaluations
            .iter()
            .map(|&(_, y)| {
                best = best.min(y);
                best
            })
            .collect()
    }
}

/// The objective as the optimisers see it: a point in, a value out (or the error that stops
/// the optimisation).
pub type ObjectiveFn<'a> = dyn FnMut(&Parameters) -> Result<f64, Error> + 'a;

/// Bayesian optimisation of `f` within `bounds`, `settings.evaluations` evaluations in all
/// (the initial design's `settings.initial_design` included), deterministic in
/// `settings.seed`.
///
/// An error from `f` ([`Error::Interrupted`] included) stops the search at that evaluation
/// and is returned as it is, and so does a value that is not finite or a Gaussian process
/// that cannot be fitted ([`Error::Optimiser`]). Either way no trace is returned: a cut
/// search is never passed off as a finished one.
pub fn bayesian_optimise(
    f: &mut ObjectiveFn<'_>,
    bounds: &ParameterBounds,
    settings: &OptimiserSettings,
) -> Result<Trace, Error> {
    let mut trace = Trace::default();
    let design = initial_design(bounds, settings.initial_design, settings.seed);
    for point in design.into_iter().take(settings.evaluations) {
        evaluate(f, &mut trace, point)?;
    }
    let mut length_scales = None;
    let iterations = settings.evaluations.saturating_sub(trace.evaluations.len());
    for iteration in 0..iterations {
        let fresh = iteration.is_multiple_of(FRESH_FIT_EVERY);
        let (point, fitted) = propose(&trace, bounds, length_scales, fresh, settings.seed)?;
        length_scales = Some(fitted);
        evaluate(f, &mut trace, point)?;
    }
    Ok(trace)
}

/// Every how many iterations the length scales are also searched from the fresh starts (in
/// between, from the previous fit's only).
const FRESH_FIT_EVERY: usize = 10;

/// Evaluate `f` at `point` into `trace`; a value that is not finite is an error.
fn evaluate(f: &mut ObjectiveFn<'_>, trace: &mut Trace, point: Parameters) -> Result<(), Error> {
    let value = f(&point)?;
    if !value.is_finite() {
        return Err(Error::Optimiser(format!(
            "the objective is {value} at {point:?}"
        )));
    }
    trace.evaluations.push((point, value));
    Ok(())
}

/// The next point of the Bayesian search after the evaluations of `trace`, and the fitted
/// length scales (the next fit's start): the process fitted from `previous` (and from the
/// fresh starts too when `fresh`), its expected improvement maximised.
fn propose(
    trace: &Trace,
    bounds: &ParameterBounds,
    previous: Option<[f64; 4]>,
    fresh: bool,
    seed: u64,
) -> Result<(Parameters, [f64; 4]), Error> {
    let points: Vec<[f64; 4]> = trace
        .evaluations
        .iter()
        .map(|(x, _)| to_unit(bounds, x))
        .collect();
    let values: Vec<f64> = trace.evaluations.iter().map(|e| e.1).collect();
    let gp = GaussianProcess::fit(&points, &values, previous, fresh)?;
    let best = points
        .iter()
        .zip(&values)
        .min_by(|a, b| a.1.total_cmp(b.1))
        .map(|(u, y)| (*u, *y))
        .ok_or_else(|| Error::Optimiser("the initial design is empty".into()))?;
    let u = next_point(&gp, &points, best, seed);
    let b = box_bounds(bounds);
    let x = std::array::from_fn(|i| b[i].0 + u[i] * (b[i].1 - b[i].0));
    Ok((x, gp.length_scales()))
}

/// Nelder–Mead from `start` within `bounds`, `evaluations` evaluations at most: sharpens the
/// optimum the Bayesian search found (its Gaussian process locates the basin quickly but
/// refines it slowly). Works in the unit cube (each parameter divided by its range), starts
/// from a simplex of 3 % of the range per axis, clamps every vertex into the bounds. Returns
/// the evaluations it made.
pub fn polish(
    f: &mut ObjectiveFn<'_>,
    bounds: &ParameterBounds,
    start: Parameters,
    evaluations: usize,
) -> Result<Trace, Error> {
    let b = box_bounds(bounds);
    let to_x = |u: &[f64; 4]| -> Parameters {
        std::array::from_fn(|i| b[i].0 + u[i].clamp(0.0, 1.0) * (b[i].1 - b[i].0))
    };
    let u0 = to_unit(bounds, &start);
    let mut trace = Trace::default();
    let mut eval = |u: &[f64; 4], trace: &mut Trace| -> Result<Option<f64>, Error> {
        if trace.evaluations.len() >= evaluations {
            return Ok(None);
        }
        let x = to_x(u);
        let y = f(&x)?;
        trace.evaluations.push((x, y));
        Ok(Some(y))
    };
    let simplex: Vec<[f64; 4]> = (0..5)
        .map(|k| {
            let mut u = u0;
            if k > 0 {
                let i = k - 1;
                u[i] += if u[i] > 0.97 { -0.03 } else { 0.03 };
            }
            u
        })
        .collect();
    nelder_mead(&mut |u| eval(u, &mut trace), &simplex, (0.0, 1.0), 0.0)?;
    Ok(trace)
}

/// Random search: `evaluations` points uniformly in `bounds`, the first the uncalibrated
/// default (as in the Bayesian design). Deterministic in `seed`.
pub fn random_search(
    f: &mut ObjectiveFn<'_>,
    bounds: &ParameterBounds,
    evaluations: usize,
    seed: u64,
) -> Result<Trace, Error> {
    let mut points = uniform_points(bounds, evaluations, seed);
    if let Some(first) = points.first_mut() {
        *first = crate::search_space::identity_point(bounds);
    }
    let mut trace = Trace::default();
    for point in points {
        let value = f(&point)?;
        trace.evaluations.push((point, value));
    }
    Ok(trace)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A smooth bowl with its minimum at `[1.1, 0.1, -0.2, 0.15]`.
    fn bowl(x: &Parameters) -> Result<f64, Error> {
        let t = [1.1, 0.1, -0.2, 0.15];
        Ok(x.iter()
            .zip(t)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            .sqrt())
    }

    #[test]
    fn bayesian_optimisation_finds_a_bowl_minimum_within_budget_and_repeatably() {
        let settings = OptimiserSettings {
            evaluations: 30,
            polish_evaluations: 0,
            initial_design: 10,
            seed: 3,
        };
        let bounds = ParameterBounds::default();
        let trace = bayesian_optimise(&mut bowl, &bounds, &settings).unwrap();
        assert_eq!(trace.evaluations.len(), 30);
        let (x, y) = trace.best().unwrap();
        assert!(y < 0.05, "best {y} at {x:?}");
        let again = bayesian_optimise(&mut bowl, &bounds, &settings).unwrap();
        assert_eq!(again, trace, "a fixed seed repeats the calibration");
    }

    #[test]
    fn an_objective_error_stops_the_optimisation() {
        let mut calls = 0;
        let mut failing = |_: &Parameters| -> Result<f64, Error> {
            calls += 1;
            if calls > 3 {
                Err(Error::Optimiser("broken".into()))
            } else {
                Ok(1.0)
            }
        };
        let settings = OptimiserSettings {
            evaluations: 20,
            polish_evaluations: 0,
            initial_design: 8,
            seed: 1,
        };
        let e =
            bayesian_optimise(&mut failing, &ParameterBounds::default(), &settings).unwrap_err();
        assert!(e.to_string().contains("broken"), "{e}");
        assert_eq!(calls, 4, "no evaluation after the failure");
    }

    #[test]
    fn an_interrupt_after_the_initial_design_stops_the_search_at_once_with_no_trace() {
        let mut calls = 0;
        let mut cut = |x: &Parameters| -> Result<f64, Error> {
            calls += 1;
            if calls > 12 {
                Err(Error::Interrupted)
            } else {
                bowl(x)
            }
        };
        let settings = OptimiserSettings {
            evaluations: 40,
            polish_evaluations: 0,
            initial_design: 8,
            seed: 1,
        };
        let e = bayesian_optimise(&mut cut, &ParameterBounds::default(), &settings).unwrap_err();
        assert_eq!(e, Error::Interrupted);
        assert_eq!(calls, 13, "no evaluation after the interrupt");
    }

    #[test]
    fn a_gaussian_process_that_cannot_be_fitted_is_an_optimiser_error_with_no_trace() {
        // Bounds of zero width: the scale axis of the unit cube is 0 / 0, so no correlation
        // matrix factorises, whatever the jitter.
        let bounds = ParameterBounds {
            scale_min: 1.0,
            scale_max: 1.0,
            ..ParameterBounds::default()
        };
        let mut calls = 0;
        let mut counted = |x: &Parameters| -> Result<f64, Error> {
            calls += 1;
            bowl(x)
        };
        let settings = OptimiserSettings {
            evaluations: 20,
            polish_evaluations: 0,
            initial_design: 8,
            seed: 1,
        };
        let e = bayesian_optimise(&mut counted, &bounds, &settings).unwrap_err();
        assert!(
            matches!(&e, Error::Optimiser(m) if m.contains("Gaussian process cannot be fitted")),
            "{e}"
        );
        assert_eq!(calls, 8, "the initial design, then no evaluation");
    }

    #[test]
    fn an_interrupt_in_the_polish_stops_it_with_no_trace() {
        let mut calls = 0;
        let mut cut = |x: &Parameters| -> Result<f64, Error> {
            calls += 1;
            if calls > 7 {
                Err(Error::Interrupted)
            } else {
                bowl(x)
            }
        };
        let bounds = ParameterBounds::default();
        let e = polish(&mut cut, &bounds, [1.05, 0.0, -0.1, 0.1], 80).unwrap_err();
        assert_eq!(e, Error::Interrupted);
        assert_eq!(calls, 8);
    }

    #[test]
    fn polish_descends_to_a_bowl_minimum_from_nearby() {
        let bounds = ParameterBounds::default();
        let trace = polish(&mut bowl, &bounds, [1.05, 0.0, -0.1, 0.1], 80).unwrap();
        assert_eq!(trace.evaluations.len(), 80);
        let (_, y) = trace.best().unwrap();
        assert!(y < 0.005, "{y}");
    }

    #[test]
    fn random_search_spends_its_budget_and_starts_at_the_default() {
        let trace = random_search(&mut bowl, &ParameterBounds::default(), 25, 9).unwrap();
        assert_eq!(trace.evaluations.len(), 25);
        assert_eq!(trace.evaluations[0].0, [1.0, 0.0, 0.0, 0.0]);
        let best = trace.best_so_far();
        assert!(best.windows(2).all(|w| w[1] <= w[0]));
    }
}
