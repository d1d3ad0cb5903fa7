//! The Gaussian process's likelihood (`gaussian_process.rs` states the model): the
//! correlation matrix, its Cholesky factor with a jitter, the constant mean and the variance
//! profiled out, and the concentrated log-likelihood of the length scales, maximised by
//! Nelder–Mead.
//!
//! **Mean and variance profiled out.** With the Cholesky factor `R = L Lᵀ`, `w = L⁻¹ 1` and
//! `e = L⁻¹ y`, the generalised least-squares mean, the residual and the variance of maximum
//! likelihood are
//!
//! ```text
//! μ̂ = wᵀe / wᵀw        ρ = e − μ̂ w = L⁻¹ (y − μ̂ 1)        σ̂² = ρᵀρ / n
//! ```
//!
//! and with them put back the log-likelihood is, up to a constant, the concentrated
//! log-likelihood of the length scales alone:
//!
//! ```text
//! λ(ℓ) = −(n/2) ln σ̂² − Σᵢ ln Lᵢᵢ                                   (ln |R| = 2 Σᵢ ln Lᵢᵢ)
//! ```
//!
//! (`σ̂²` is floored at 10⁻¹² of the standardised values' variance, for values all equal.)
//!
//! **Jitter.** `δ = 10⁻¹⁰`, raised to `10⁻⁸`, `10⁻⁶`, `10⁻⁴` in turn while the Cholesky
//! factorisation fails (nearly coincident points, very long length scales). Length scales
//! for which none factorises have `λ = −∞`; a process that cannot be factorised even at
//! `10⁻⁴` cannot be fitted: [`Error::Optimiser`].

use std::convert::Infallible;

use nalgebra::{DMatrix, DVector};

use crate::error::Error;
use crate::nelder_mead::{nelder_mead, simplex_at};

/// A point of the unit cube (the search space with each parameter divided by its range).
pub(crate) type UnitPoint = [f64; 4];

/// The jitters tried in turn.
const JITTERS: [f64; 4] = [1e-10, 1e-8, 1e-6, 1e-4];
/// The range of every length scale (unit cube).
const LENGTH_SCALES: (f64, f64) = (0.03, 30.0);
/// Likelihood evaluations per start, and the spread of the simplex at which a start ends.
const EVALUATIONS_PER_START: usize = 200;
const LIKELIHOOD_TOLERANCE: f64 = 1e-4;
/// Smallest standardised variance (the values all equal).
const VARIANCE_FLOOR: f64 = 1e-12;

/// The standardised values conditioned on one set of length scales.
#[derive(Debug, Clone)]
pub(crate) struct Factorised {
    /// `L`, lower triangular.
    pub(crate) l: DMatrix<f64>,
    /// `w = L⁻¹ 1` and `wᵀw`.
    pub(crate) w: DVector<f64>,
    pub(crate) ww: f64,
    /// `ρ = L⁻¹ (y − μ̂ 1)`.
    pub(crate) residual: DVector<f64>,
    /// `μ̂` and `σ̂²`.
    pub(crate) mean: f64,
    pub(crate) variance: f64,
    /// `λ`.
    pub(crate) log_likelihood: f64,
}

/// Matérn 5/2 correlation at scaled distance `r`.
pub(crate) fn matern52(r: f64) -> f64 {
    let s = 5.0_f64.sqrt() * r;
    (1.0 + s + s * s / 3.0) * (-s).exp()
}

/// `L⁻¹ b` for lower-triangular `L` with a positive diagonal (column by column: nalgebra
/// stores `L` by columns).
pub(crate) fn forward_substitution(l: &DMatrix<f64>, b: &DVector<f64>) -> DVector<f64> {
    let n = b.len();
    let mut x = b.clone();
    let xs = x.as_mut_slice();
    for (j, column) in l.as_slice().chunks_exact(n).enumerate() {
        let xj = xs[j] / column[j];
        xs[j] = xj;
        for (xi, lij) in xs[j + 1..].iter_mut().zip(&column[j + 1..]) {
            *xi -= lij * xj;
        }
    }
    x
}

/// The points and the standardised values, with the squared differences per axis of every
/// pair (computed once per fit, reused by every likelihood evaluation).
pub(crate) struct Observations {
    pub(crate) points: Vec<UnitPoint>,
    y: DVector<f64>,
    /// The values' mean and standard deviation (1 when they are all equal).
    pub(crate) shift: f64,
    pub(crate) scale: f64,
    squared_differences: Vec<[f64; 4]>,
}

impl Observations {
    /// The observations of `values` at `points` (at least one, one value per point).
    pub(crate) fn new(points: &[UnitPoint], values: &[f64]) -> Result<Observations, Error> {
        if points.is_empty() || points.len() != values.len() {
            return Err(Error::Optimiser(format!(
                "a Gaussian process needs one value per point and at least one point, not {} \
                 values at {} points",
                values.len(),
                points.len()
            )));
        }
        let n = values.len() as f64;
        let shift = values.iter().sum::<f64>() / n;
        let sd = (values.iter().map(|v| (v - shift).powi(2)).sum::<f64>() / n).sqrt();
        let scale = if sd > 0.0 { sd } else { 1.0 };
        let mut squared_differences = Vec::with_capacity(points.len() * points.len() / 2);
        for (i, a) in points.iter().enumerate() {
            for b in &points[..i] {
                squared_differences.push(std::array::from_fn(|d| (a[d] - b[d]).powi(2)));
            }
        }
        Ok(Observations {
            points: points.to_vec(),
            y: DVector::from_iterator(values.len(), values.iter().map(|v| (v - shift) / scale)),
            shift,
            scale,
            squared_differences,
        })
    }

    /// Nelder–Mead on `−λ` over the log length scales (within the range of `LENGTH_SCALES`)
    /// from `start` (length scales) with first steps `step`: the best log length scales and
    /// their `−λ`.
    pub(crate) fn maximise_likelihood(
        &self,
        start: [f64; 4],
        step: f64,
    ) -> Option<([f64; 4], f64)> {
        let (lo, hi) = (LENGTH_SCALES.0.ln(), LENGTH_SCALES.1.ln());
        let mut left = EVALUATIONS_PER_START;
        let mut negative_likelihood = |theta: &[f64; 4]| -> Result<Option<f64>, Infallible> {
            if left == 0 {
                return Ok(None);
            }
            left -= 1;
            let ls = theta.map(f64::exp);
            Ok(Some(
                self.factorise(&ls)
                    .map_or(f64::INFINITY, |f| -f.log_likelihood),
            ))
        };
        let theta0 = start.map(|l| l.clamp(LENGTH_SCALES.0, LENGTH_SCALES.1).ln());
        let simplex = simplex_at(theta0, step, (lo, hi));
        let Ok(found) = nelder_mead(
            &mut negative_likelihood,
            &simplex,
            (lo, hi),
            LIKELIHOOD_TOLERANCE,
        );
        found
    }

    /// The correlation matrix for `ls` with `jitter` on its diagonal.
    fn correlation(&self, ls: &[f64; 4], jitter: f64) -> DMatrix<f64> {
        let n = self.points.len();
        let inverse_squares = ls.map(|l| 1.0 / (l * l));
        let mut r = DMatrix::identity(n, n) * (1.0 + jitter);
        let mut pairs = self.squared_differences.iter();
        for i in 0..n {
            for j in 0..i {
                let d2 = pairs.next().map_or(f64::NAN, |s| {
                    (0..4).map(|d| s[d] * inverse_squares[d]).sum::<f64>()
                });
                let k = matern52(d2.sqrt());
                r[(i, j)] = k;
                r[(j, i)] = k;
            }
        }
        r
    }

    /// The values conditioned on `ls` with the smallest jitter that factorises (`None`: none
    /// does).
    fn factorise(&self, ls: &[f64; 4]) -> Option<Factorised> {
        JITTERS.iter().find_map(|&jitter| {
            let l = self.correlation(ls, jitter).cholesky()?.unpack();
            let diagonal_ok = l.diagonal().iter().all(|d| d.is_finite() && *d > 0.0);
            diagonal_ok.then(|| self.profile(l))
        })
    }

    /// Mean and variance profiled out for the factor `l` (module documentation).
    fn profile(&self, l: DMatrix<f64>) -> Factorised {
        let n = self.y.len();
        let w = forward_substitution(&l, &DVector::from_element(n, 1.0));
        let e = forward_substitution(&l, &self.y);
        let ww = w.dot(&w);
        let mean = w.dot(&e) / ww;
        let residual = e - &w * mean;
        let variance = (residual.dot(&residual) / n as f64).max(VARIANCE_FLOOR);
        let log_det_half: f64 = l.diagonal().iter().map(|d| d.ln()).sum();
        let log_likelihood = -0.5 * n as f64 * variance.ln() - log_det_half;
        Factorised {
            l,
            w,
            ww,
            residual,
            mean,
            variance,
            log_likelihood,
        }
    }

    /// The values conditioned on `ls`, or the error of a process that cannot be fitted.
    pub(crate) fn factorise_or_fail(&self, ls: &[f64; 4]) -> Result<Factorised, Error> {
        self.factorise(ls).ok_or_else(|| {
            Error::Optimiser(format!(
                "the Gaussian process cannot be fitted to the {} evaluations: its correlation \
                 matrix is not positive definite even with a jitter of {:e}",
                self.points.len(),
                JITTERS[JITTERS.len() - 1]
            ))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_profiled_mean_variance_and_likelihood_match_the_direct_formulas() {
        let points: Vec<UnitPoint> = (0..7)
            .map(|i| {
                let t = f64::from(i) / 6.0;
                [t, (5.0 * t) % 1.0, t * t, 0.3]
            })
            .collect();
        let values = [0.3, 1.2, -0.4, 0.9, 2.0, 0.1, 0.7];
        let observations = Observations::new(&points, &values).unwrap();
        let ls = [0.4, 0.7, 1.3, 2.0];
        let f = observations.factorise_or_fail(&ls).unwrap();
        // Directly: R⁻¹ and |R| of the same matrix.
        let r = observations.correlation(&ls, JITTERS[0]);
        let inverse = r.clone().try_inverse().unwrap();
        let (ones, y) = (DVector::from_element(7, 1.0), &observations.y);
        let mean = (ones.transpose() * &inverse * y)[0] / (ones.transpose() * &inverse * &ones)[0];
        let centred = y - &ones * mean;
        let variance = (centred.transpose() * &inverse * &centred)[0] / 7.0;
        let log_likelihood = -3.5 * variance.ln() - 0.5 * r.determinant().ln();
        assert!((f.mean - mean).abs() < 1e-9, "{} vs {mean}", f.mean);
        assert!(
            (f.variance - variance).abs() < 1e-9 * variance,
            "{}",
            f.variance
        );
        assert!(
            (f.log_likelihood - log_likelihood).abs() < 1e-8,
            "{}",
            f.log_likelihood
        );
        assert!((f.l.clone() * f.l.transpose() - r).norm() < 1e-12);
    }
}
