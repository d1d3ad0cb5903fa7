//! Minimising the objective over the search space: Bayesian optimisation (egobox: a Gaussian
//! process with a constant mean and a Matérn 5/2 kernel whose length scales are fitted by
//! maximum likelihood at every iteration, expected improvement as the acquisition, our seeded
//! Latin hypercube as the initial design) and, as the baseline it must beat, random search
//! with the same budget. A short Nelder–Mead [`polish`] sharpens the Bayesian optimum.

use std::cell::RefCell;

use egobox_ego::{
    CorrelationSpec, EgoError, EgorBuilder, InfillStrategy, RegressionSpec, TerminationReason,
    TerminationStatus,
};
use ndarray::{Array2, ArrayView2};

use crate::error::Error;
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

/// Bayesian optimisation of `f` within `bounds`, `settings.evaluations` evaluations in all.
///
/// An error from `f` ([`Error::Interrupted`] included) stops the search at that evaluation
/// and is returned as it is; an interrupt egobox reports itself (its own Ctrl-C handler, when
/// no other was installed first) is [`Error::Interrupted`]. Either way no trace is returned:
/// a cut search is never passed off as a finished one.
pub fn bayesian_optimise(
    f: &mut ObjectiveFn<'_>,
    bounds: &ParameterBounds,
    settings: &OptimiserSettings,
) -> Result<Trace, Error> {
    let design = initial_design(bounds, settings.initial_design, settings.seed);
    let doe = Array2::from_shape_fn((design.len(), 4), |(i, j)| design[i][j]);
    let limits = box_bounds(bounds);
    let xlimits = Array2::from_shape_fn(
        (4, 2),
        |(i, j)| {
            if j == 0 { limits[i].0 } else { limits[i].1 }
        },
    );
    let state = RefCell::new((Trace::default(), None::<Error>, f));
    let budget = settings.evaluations;
    let objective = |x: &ArrayView2<f64>| -> Result<Array2<f64>, &'static str> {
        let mut guard = state.borrow_mut();
        let (trace, failure, f) = &mut *guard;
        let mut y = Array2::zeros((x.nrows(), 1));
        for (row, out) in x.rows().into_iter().zip(y.iter_mut()) {
            let point: Parameters = std::array::from_fn(|i| row[i]);
            if trace.evaluations.len() >= budget {
                // The budget is spent: the optimiser finishes its iteration on a flat value.
                *out = f64::MAX.sqrt();
                continue;
            }
            match f(&point) {
                Ok(v) if v.is_finite() => {
                    trace.evaluations.push((point, v));
                    *out = v;
                }
                Ok(v) => {
                    *failure = Some(Error::Optimiser(format!(
                        "the objective is {v} at {point:?}"
                    )));
                    return Err(OBJECTIVE_FAILED);
                }
                Err(e) => {
                    *failure = Some(e);
                    return Err(OBJECTIVE_FAILED);
                }
            }
        }
        Ok(y)
    };
    let iterations = settings.evaluations.saturating_sub(design.len());
    // egobox panics when its Gaussian process cannot be trained: contain it and report it as
    // an error.
    let run = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        EgorBuilder::optimize(objective)
            .configure(|config| {
                config
                    .doe(&doe)
                    .max_iters(iterations)
                    .infill_strategy(InfillStrategy::EI)
                    // An objective error ends the search at once (no further iteration).
                    .stop_on_error(true)
                    .seed(settings.seed)
                    .configure_gp(|gp| {
                        gp.regression_spec(RegressionSpec::CONSTANT)
                            .correlation_spec(CorrelationSpec::MATERN52)
                    })
            })
            .min_within(&xlimits)
            .and_then(|egor| egor.run())
            .map(|result| result.state.termination_status)
    }));
    let (trace, failure, _) = state.into_inner();
    search_outcome(trace, failure, run)
}

/// What the objective tells egobox when it fails (the error itself is kept aside).
const OBJECTIVE_FAILED: &str = "the objective failed";

/// The Bayesian search's result from how it ended (`run`: egobox's result, or its panic as
/// `catch_unwind` returns it): the objective's own error first, then egobox's interrupt, its
/// error or its panic; otherwise the trace.
fn search_outcome(
    trace: Trace,
    failure: Option<Error>,
    run: Result<Result<TerminationStatus, EgoError>, Box<dyn std::any::Any + Send>>,
) -> Result<Trace, Error> {
    match (failure, run) {
        (Some(e), _) => Err(e),
        (None, Ok(Ok(TerminationStatus::Terminated(TerminationReason::Interrupt)))) => {
            Err(Error::Interrupted)
        }
        (None, Ok(Ok(_))) => Ok(trace),
        (None, Ok(Err(e))) => Err(Error::Optimiser(e.to_string())),
        (None, Err(_)) => Err(Error::Optimiser(
            "the Gaussian process could not be trained on the evaluations".into(),
        )),
    }
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
    let mut simplex: Vec<([f64; 4], f64)> = Vec::with_capacity(5);
    for k in 0..5 {
        let mut u = u0;
        if k > 0 {
            let i = k - 1;
            u[i] += if u[i] > 0.97 { -0.03 } else { 0.03 };
        }
        let Some(y) = eval(&u, &mut trace)? else {
            return Ok(trace);
        };
        simplex.push((u, y));
    }
    loop {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let worst = simplex[4];
        let centroid: [f64; 4] =
            std::array::from_fn(|i| simplex[..4].iter().map(|v| v.0[i]).sum::<f64>() / 4.0);
        let along = |t: f64| -> [f64; 4] {
            std::array::from_fn(|i| (centroid[i] + t * (worst.0[i] - centroid[i])).clamp(0.0, 1.0))
        };
        let reflected = along(-1.0);
        let Some(yr) = eval(&reflected, &mut trace)? else {
            return Ok(trace);
        };
        if yr < simplex[0].1 {
            let expanded = along(-2.0);
            let Some(ye) = eval(&expanded, &mut trace)? else {
                return Ok(trace);
            };
            simplex[4] = if ye < yr {
                (expanded, ye)
            } else {
                (reflected, yr)
            };
        } else if yr < simplex[3].1 {
            simplex[4] = (reflected, yr);
        } else {
            let contracted = if yr < worst.1 {
                along(-0.5)
            } else {
                along(0.5)
            };
            let Some(yc) = eval(&contracted, &mut trace)? else {
                return Ok(trace);
            };
            if yc < worst.1.min(yr) {
                simplex[4] = (contracted, yc);
            } else {
                let best = simplex[0].0;
                for v in simplex.iter_mut().skip(1) {
                    let u: [f64; 4] = std::array::from_fn(|i| best[i] + 0.5 * (v.0[i] - best[i]));
                    let Some(y) = eval(&u, &mut trace)? else {
                        return Ok(trace);
                    };
                    *v = (u, y);
                }
            }
        }
    }
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
    fn egobox_reporting_its_own_interrupt_is_an_interrupt_not_a_result() {
        let trace = Trace {
            evaluations: vec![([1.0, 0.0, 0.0, 0.0], 0.5)],
        };
        let status = |reason| Ok(Ok(TerminationStatus::Terminated(reason)));
        assert_eq!(
            search_outcome(trace.clone(), None, status(TerminationReason::Interrupt)),
            Err(Error::Interrupted)
        );
        assert_eq!(
            search_outcome(
                trace.clone(),
                None,
                status(TerminationReason::MaxItersReached)
            ),
            Ok(trace)
        );
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
