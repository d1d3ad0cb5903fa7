//! Nelder–Mead downhill simplex in a box, for the three local searches of the calibration: the
//! [`polish`](crate::polish) of the objective, the Gaussian process's length scales (maximum
//! likelihood) and the refinement of the expected improvement's best candidates.
//!
//! A simplex of `D + 1` vertices `v₀ … v_D`, sorted by value (`v₀` best, `v_D` worst), moves
//! its worst vertex along the line through the centroid `c = (v₀ + … + v_{D−1}) / D` of the
//! others, `p(t) = c + t (v_D − c)`, each coordinate clamped into the box `[lo, hi]`:
//!
//! - reflection `p(−1)`; if it beats `v₀`, the expansion `p(−2)` is tried and the better of
//!   the two replaces `v_D`;
//! - if the reflection beats only `v_{D−1}`, it replaces `v_D`;
//! - otherwise a contraction, outside `p(−½)` when the reflection beat `v_D`, inside `p(½)`
//!   when it did not, replaces `v_D` if it beats both;
//! - otherwise the simplex shrinks halfway toward `v₀` (every other vertex re-evaluated).
//!
//! The function decides the budget: it returns `None` when no evaluation is left, and the
//! search stops there. The search also stops when the values of the sorted simplex span less
//! than `tolerance` (a tolerance of 0 never stops it: it runs until the budget is spent). An
//! error from the function stops the search and is returned as it is.

/// The function minimised: a point in, its value out, `None` when the budget is spent, or the
/// error that stops the search.
pub(crate) type Minimised<'a, const D: usize, E> =
    dyn FnMut(&[f64; D]) -> Result<Option<f64>, E> + 'a;

/// A vertex: a point and its value.
pub(crate) type Vertex<const D: usize> = ([f64; D], f64);

/// Minimise `f` from the simplex `start` (`D + 1` vertices, evaluated in order) within the
/// box `[lo, hi]` of every coordinate (see the module documentation). Returns the best vertex
/// evaluated (`None` when the budget allowed no evaluation).
pub(crate) fn nelder_mead<const D: usize, E>(
    f: &mut Minimised<'_, D, E>,
    start: &[[f64; D]],
    (lo, hi): (f64, f64),
    tolerance: f64,
) -> Result<Option<Vertex<D>>, E> {
    let mut simplex: Vec<Vertex<D>> = Vec::with_capacity(D + 1);
    for vertex in start.iter().take(D + 1) {
        let Some(y) = f(vertex)? else {
            return Ok(best_of(&simplex));
        };
        simplex.push((*vertex, y));
    }
    if simplex.len() < D + 1 {
        return Ok(best_of(&simplex));
    }
    loop {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        if simplex[D].1 - simplex[0].1 < tolerance {
            return Ok(Some(simplex[0]));
        }
        let Some(replacement) = step(f, &simplex, (lo, hi))? else {
            return Ok(best_of(&simplex));
        };
        match replacement {
            Step::Replace(vertex) => simplex[D] = vertex,
            Step::Shrink => {
                let best = simplex[0].0;
                for v in simplex.iter_mut().skip(1) {
                    let u: [f64; D] = std::array::from_fn(|i| best[i] + 0.5 * (v.0[i] - best[i]));
                    let Some(y) = f(&u)? else {
                        return Ok(best_of(&simplex));
                    };
                    *v = (u, y);
                }
            }
        }
    }
}

/// What one step does to the sorted simplex.
enum Step<const D: usize> {
    /// The worst vertex is replaced by this one.
    Replace(Vertex<D>),
    /// Nothing beat the worst vertex: shrink toward the best.
    Shrink,
}

/// Reflection, expansion or contraction of the sorted simplex's worst vertex (`None`: the
/// budget ran out).
fn step<const D: usize, E>(
    f: &mut Minimised<'_, D, E>,
    simplex: &[Vertex<D>],
    (lo, hi): (f64, f64),
) -> Result<Option<Step<D>>, E> {
    let worst = simplex[D];
    let centroid: [f64; D] =
        std::array::from_fn(|i| simplex[..D].iter().map(|v| v.0[i]).sum::<f64>() / D as f64);
    let along = |t: f64| -> [f64; D] {
        std::array::from_fn(|i| (centroid[i] + t * (worst.0[i] - centroid[i])).clamp(lo, hi))
    };
    let reflected = along(-1.0);
    let Some(yr) = f(&reflected)? else {
        return Ok(None);
    };
    if yr < simplex[0].1 {
        let expanded = along(-2.0);
        let Some(ye) = f(&expanded)? else {
            return Ok(None);
        };
        let better = if ye < yr {
            (expanded, ye)
        } else {
            (reflected, yr)
        };
        return Ok(Some(Step::Replace(better)));
    }
    if yr < simplex[D - 1].1 {
        return Ok(Some(Step::Replace((reflected, yr))));
    }
    let contracted = if yr < worst.1 {
        along(-0.5)
    } else {
        along(0.5)
    };
    let Some(yc) = f(&contracted)? else {
        return Ok(None);
    };
    Ok(Some(if yc < worst.1.min(yr) {
        Step::Replace((contracted, yc))
    } else {
        Step::Shrink
    }))
}

/// The best vertex of a (partial) simplex.
fn best_of<const D: usize>(simplex: &[Vertex<D>]) -> Option<Vertex<D>> {
    simplex.iter().copied().min_by(|a, b| a.1.total_cmp(&b.1))
}

/// A starting simplex at `x`: `x` and, per axis, `x` moved by `step` (backwards when that
/// would leave `[lo, hi]`).
pub(crate) fn simplex_at<const D: usize>(
    x: [f64; D],
    step: f64,
    (lo, hi): (f64, f64),
) -> Vec<[f64; D]> {
    let mut simplex = vec![x];
    for i in 0..D {
        let mut v = x;
        v[i] += if v[i] + step > hi && v[i] - step >= lo {
            -step
        } else {
            step
        };
        simplex.push(v);
    }
    simplex
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rosenbrock(x: &[f64; 2]) -> f64 {
        (1.0 - x[0]).powi(2) + 100.0 * (x[1] - x[0] * x[0]).powi(2)
    }

    #[test]
    fn finds_the_rosenbrock_valley_minimum_and_stops_at_its_tolerance() {
        let mut calls = 0;
        let mut f = |x: &[f64; 2]| -> Result<Option<f64>, ()> {
            calls += 1;
            Ok((calls <= 2000).then(|| rosenbrock(x)))
        };
        let start = simplex_at([-1.2, 1.0], 0.5, (-5.0, 5.0));
        let (x, y) = nelder_mead(&mut f, &start, (-5.0, 5.0), 1e-14)
            .unwrap()
            .unwrap();
        assert!(y < 1e-8, "{y} at {x:?}");
        assert!(calls < 2000, "stopped by its tolerance, not the budget");
    }

    #[test]
    fn stays_in_its_box_stops_at_the_budget_and_passes_errors_on() {
        let mut calls = 0;
        let mut f = |x: &[f64; 2]| -> Result<Option<f64>, &'static str> {
            assert!(x.iter().all(|c| (0.0..=1.0).contains(c)), "{x:?}");
            calls += 1;
            Ok((calls <= 50).then(|| (x[0] - 2.0).powi(2) + (x[1] + 1.0).powi(2)))
        };
        let start = simplex_at([0.5, 0.5], 0.1, (0.0, 1.0));
        let (x, _) = nelder_mead(&mut f, &start, (0.0, 1.0), 0.0)
            .unwrap()
            .unwrap();
        assert_eq!(calls, 51, "the budget, then the refused evaluation");
        assert!((x[0] - 1.0).abs() < 1e-3 && x[1].abs() < 1e-3, "{x:?}");
        let mut failing = |_: &[f64; 2]| -> Result<Option<f64>, &'static str> { Err("broken") };
        assert_eq!(
            nelder_mead(&mut failing, &start, (0.0, 1.0), 0.0),
            Err("broken")
        );
    }

    #[test]
    fn a_starting_simplex_steps_back_at_the_upper_bound() {
        let s = simplex_at([0.95, 0.2], 0.1, (0.0, 1.0));
        assert_eq!(
            s,
            vec![[0.95, 0.2], [0.85, 0.2], [0.95, 0.30000000000000004]]
        );
    }
}
