//! The Bayesian optimiser's acquisition: the expected improvement of the Gaussian process,
//! maximised by a seeded multistart.
//!
//! **Expected improvement.** With the process's prediction `Y(u) ~ N(m(u), s(u)²)` and the
//! best value so far `f*`, the expected improvement of evaluating at `u` (minimisation) is
//!
//! ```text
//! EI(u) = E[max(f* − Y(u), 0)] = s · h(z),   z = (f* − m) / s,   h(z) = φ(z) + z Φ(z)
//! ```
//!
//! (`φ`, `Φ`: standard normal density and distribution). Far from the best value `EI`
//! underflows, so it is compared as `ln EI = ln s + ln h(z)`:
//!
//! - for `z ≥ −2.5`, `h` directly, with `Φ(−t) = ½ − φ(t) Σₖ t^{2k+1} / (2k+1)!!` for
//!   `0 ≤ t ≤ 2.5` (and `Φ(t) = 1 − Φ(−t)`);
//! - for `z = −t < −2.5`, Laplace's continued fraction of the Mills ratio,
//!   `Φ(−t) = φ(t) / f₀` with `f_k = t + (k+1) / f_{k+1}` (truncated at `f₆₀ = t`, exact to 10⁻¹⁴ from `t = 2.5` on), which
//!   gives `h(−t) = φ(t) (1 − t / f₀) = φ(t) / (f₀ f₁)` without cancellation. Far tails use
//!   the same fraction for `Φ` itself.
//!
//! **Multistart.** 512 points uniform in the unit cube and 64 Gaussian steps (standard
//! deviation 0.05 per axis, clamped into the cube) from the best point so far, drawn from
//! [`SplitMix64`] keyed by the seed and the number of evaluations (so a fixed seed repeats the
//! search); the four with the largest `ln EI` are refined by Nelder–Mead (steps of 0.02, 60
//! evaluations each). The refined point with the largest `ln EI` is proposed unless it lies
//! within 10⁻⁶ of an evaluated point; then the next one, then the best such candidate, and
//! if every one does, the candidate farthest from all evaluated points.

use std::convert::Infallible;
use std::f64::consts::PI;

use retarget::human_hand::SplitMix64;

use crate::gaussian_process::{GaussianProcess, UnitPoint};
use crate::nelder_mead::{nelder_mead, simplex_at};

const UNIFORM_CANDIDATES: usize = 512;
const LOCAL_CANDIDATES: usize = 64;
const LOCAL_SD: f64 = 0.05;
const REFINED: usize = 4;
const REFINE_STEP: f64 = 0.02;
const REFINE_EVALUATIONS: usize = 60;
/// The closest a proposal may come to an evaluated point (unit cube).
const MIN_SEPARATION: f64 = 1e-6;
/// Terms of the continued fraction (exact to 10⁻¹⁴ from `TAIL` on).
const FRACTION_TERMS: usize = 60;
/// Where `ln h` switches to the continued fraction.
const TAIL: f64 = 2.5;

/// The next point to evaluate (unit cube): the expected improvement's maximum over the
/// multistart (module documentation). `evaluated` holds every evaluated point and `best` the
/// best one with its value; `seed` is the search's.
pub(crate) fn next_point(
    gp: &GaussianProcess,
    evaluated: &[UnitPoint],
    best: (UnitPoint, f64),
    seed: u64,
) -> UnitPoint {
    let score = |u: &UnitPoint| ln_expected_improvement(gp, u, best.1);
    let mut candidates: Vec<(UnitPoint, f64)> = candidates(best.0, seed, evaluated.len())
        .into_iter()
        .map(|u| (u, score(&u)))
        .collect();
    candidates.sort_by(|a, b| b.1.total_cmp(&a.1));
    let mut refined: Vec<(UnitPoint, f64)> = candidates
        .iter()
        .take(REFINED)
        .map(|&(u, value)| refine(&score, u).unwrap_or((u, value)))
        .collect();
    refined.sort_by(|a, b| b.1.total_cmp(&a.1));
    let apart = |u: &UnitPoint| evaluated.iter().all(|e| distance(u, e) >= MIN_SEPARATION);
    refined
        .iter()
        .chain(&candidates)
        .map(|c| c.0)
        .find(apart)
        .unwrap_or_else(|| farthest(&candidates, evaluated))
}

/// `ln EI(u)` for the best value `best` (`−∞` where the process is certain).
pub(crate) fn ln_expected_improvement(gp: &GaussianProcess, u: &UnitPoint, best: f64) -> f64 {
    let (m, s) = gp.predict(u);
    if s > 0.0 {
        s.ln() + ln_h((best - m) / s)
    } else {
        f64::NEG_INFINITY
    }
}

/// The multistart's candidates: uniform, then around `best`.
fn candidates(best: UnitPoint, seed: u64, evaluations: usize) -> Vec<UnitPoint> {
    let mut rng = SplitMix64::keyed(seed, 0x00E1_0000 + evaluations as u64);
    let mut points: Vec<UnitPoint> = (0..UNIFORM_CANDIDATES)
        .map(|_| std::array::from_fn(|_| rng.next_f64()))
        .collect();
    points.extend((0..LOCAL_CANDIDATES).map(|_| {
        std::array::from_fn(|d| (best[d] + LOCAL_SD * rng.next_gaussian()).clamp(0.0, 1.0))
    }));
    points
}

/// Nelder–Mead on `−ln EI` from `start`: the best point and its `ln EI`.
fn refine(score: &dyn Fn(&UnitPoint) -> f64, start: UnitPoint) -> Option<(UnitPoint, f64)> {
    let mut left = REFINE_EVALUATIONS;
    let mut negative = |u: &UnitPoint| -> Result<Option<f64>, Infallible> {
        if left == 0 {
            return Ok(None);
        }
        left -= 1;
        Ok(Some(-score(u)))
    };
    let simplex = simplex_at(start, REFINE_STEP, (0.0, 1.0));
    let Ok(found) = nelder_mead(&mut negative, &simplex, (0.0, 1.0), 0.0);
    found.map(|(u, value)| (u, -value))
}

/// The candidate whose nearest evaluated point is farthest.
fn farthest(candidates: &[(UnitPoint, f64)], evaluated: &[UnitPoint]) -> UnitPoint {
    let nearest = |u: &UnitPoint| {
        evaluated
            .iter()
            .map(|e| distance(u, e))
            .fold(f64::INFINITY, f64::min)
    };
    candidates
        .iter()
        .map(|c| (c.0, nearest(&c.0)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map_or([0.5; 4], |c| c.0)
}

fn distance(a: &UnitPoint, b: &UnitPoint) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// `ln φ(z)`.
fn ln_phi(z: f64) -> f64 {
    -0.5 * z * z - 0.5 * (2.0 * PI).ln()
}

/// `f₀` and `f₁` of the Mills-ratio continued fraction at `t > 0`.
fn mills_fraction(t: f64) -> (f64, f64) {
    let mut f = t;
    let mut next = t;
    for k in (0..FRACTION_TERMS).rev() {
        next = f;
        f = t + (k + 1) as f64 / f;
    }
    (f, next)
}

/// `Φ(z)`, the standard normal distribution.
pub(crate) fn normal_cdf(z: f64) -> f64 {
    let t = z.abs();
    let lower_tail = if t <= TAIL {
        let t2 = t * t;
        let (mut term, mut sum) = (t, t);
        for k in 1..200 {
            term *= t2 / (2 * k + 1) as f64;
            sum += term;
            if term < 1e-17 * sum {
                break;
            }
        }
        0.5 - ln_phi(t).exp() * sum
    } else {
        ln_phi(t).exp() / mills_fraction(t).0
    };
    if z < 0.0 {
        lower_tail
    } else {
        1.0 - lower_tail
    }
}

/// `ln h(z)`, `h(z) = φ(z) + z Φ(z)`.
fn ln_h(z: f64) -> f64 {
    if z >= -TAIL {
        (ln_phi(z).exp() + z * normal_cdf(z)).ln()
    } else {
        let (f0, f1) = mills_fraction(-z);
        ln_phi(z) - f0.ln() - f1.ln()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, relative: f64) -> bool {
        (a - b).abs() <= relative * b.abs()
    }

    #[test]
    fn the_normal_distribution_and_ln_h_match_reference_values() {
        // Reference values from mpmath at 40 digits.
        for (z, cdf) in [
            (-1.0, 0.158_655_253_931_457_05),
            (-4.0, 3.167_124_183_311_992_1e-5),
            (-5.0, 2.866_515_718_791_939e-7),
            (-20.0, 2.753_624_118_606_233_7e-89),
            (2.5, 0.993_790_334_674_223_8),
        ] {
            assert!(
                close(normal_cdf(z), cdf, 1e-12),
                "Φ({z}) = {}",
                normal_cdf(z)
            );
        }
        for (z, ln) in [
            (-1.0, -2.485_121_025_712_641_3),
            (-4.0, -11.849_061_577_550_663),
            (-5.0, -16.744_301_162_660_99),
            (-8.0, -37.122_364_261_692_63),
            (-40.0, -808.298_568_356_62),
            (0.0, -0.918_938_533_204_672_8),
            (2.5, 0.917_092_065_592_164_5),
        ] {
            assert!(close(ln_h(z), ln, 1e-11), "ln h({z}) = {}", ln_h(z));
        }
        // Continuous where the continued fraction takes over: d ln h / dz = Φ / h = 3.0984 there.
        let (below, above) = (ln_h(-TAIL - 1e-6), ln_h(-TAIL + 1e-6));
        assert!(
            (above - below - 2e-6 * 3.098_42).abs() < 1e-10,
            "{below} {above}"
        );
    }

    #[test]
    fn the_proposal_is_repeatable_in_the_cube_and_never_an_evaluated_point() {
        let points: Vec<UnitPoint> = (0..12)
            .map(|i| {
                let t = i as f64 / 11.0;
                [t, (3.0 * t) % 1.0, (7.0 * t) % 1.0, 0.5]
            })
            .collect();
        let values: Vec<f64> = points
            .iter()
            .map(|p| p.iter().map(|c| (c - 0.3).powi(2)).sum())
            .collect();
        let gp = GaussianProcess::fit(&points, &values, None, true).unwrap();
        let best = (points[3], values[3]);
        let u = next_point(&gp, &points, best, 5);
        assert!(u.iter().all(|c| (0.0..=1.0).contains(c)), "{u:?}");
        assert!(points.iter().all(|p| distance(p, &u) >= MIN_SEPARATION));
        assert_eq!(u, next_point(&gp, &points, best, 5), "deterministic");
        assert!(
            ln_expected_improvement(&gp, &u, best.1)
                > ln_expected_improvement(&gp, &points[0], best.1)
        );
    }
}
