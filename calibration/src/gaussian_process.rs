//! The Bayesian optimiser's surrogate: a Gaussian process on the unit cube with a constant
//! mean and a Matérn 5/2 kernel with one length scale per axis (ARD), fitted by maximum
//! likelihood.
//!
//! **Model.** The values `y₁ … yₙ` at the points `u₁ … uₙ` (the parameters mapped into the
//! unit cube) are standardised (their mean subtracted, divided by their standard deviation)
//! and modelled as `y(u) = μ + z(u)`, `z` a zero-mean process with covariance `σ² k`:
//!
//! ```text
//! r(u, u′) = √( Σ_d ((u_d − u′_d) / ℓ_d)² )
//! k(r)     = (1 + √5 r + 5r²/3) · exp(−√5 r)                       (Matérn 5/2)
//! R        = [k(r(uᵢ, uⱼ))]ᵢⱼ + δ I                                 (δ: jitter)
//! ```
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
//! **Length scales.** `λ` is maximised over `ln ℓ_d ∈ [ln 0.03, ln 30]` by Nelder–Mead in
//! log-length-scale space (at most 200 evaluations per start, ending when the simplex's
//! values span less than 10⁻⁴): from the previous fit's length scales (first steps of 0.25)
//! when there is one, since the likelihood moves little when one point is added, and from the
//! three isotropic starts `ℓ = 0.15, 0.5, 2` (first steps of 0.5) at the first fit and at
//! every fit the caller asks to be fresh.
//!
//! **Prediction.** At `u`, with `cᵢ = k(r(u, uᵢ))` and `v = L⁻¹ c`, the kriging mean and
//! variance, the second including the uncertainty of the estimated mean, are
//!
//! ```text
//! m(u)  = μ̂ + vᵀρ
//! s²(u) = σ̂² · (1 − vᵀv + (1 − wᵀv)² / wᵀw)
//! ```
//!
//! both mapped back to the values' units.
//!
//! **Jitter.** `δ = 10⁻¹⁰`, raised to `10⁻⁸`, `10⁻⁶`, `10⁻⁴` in turn while the Cholesky
//! factorisation fails (nearly coincident points, very long length scales). A process that
//! cannot be factorised even at `10⁻⁴` cannot be fitted: [`Error::Optimiser`].

use std::convert::Infallible;

use nalgebra::{DMatrix, DVector};

use crate::error::Error;
use crate::nelder_mead::{nelder_mead, simplex_at};

/// A point of the unit cube.
pub(crate) type UnitPoint = [f64; 4];

/// The jitters tried in turn.
const JITTERS: [f64; 4] = [1e-10, 1e-8, 1e-6, 1e-4];
/// The range of every length scale (unit cube).
const LENGTH_SCALES: (f64, f64) = (0.03, 30.0);
/// Isotropic length scales a fresh fit starts from, and the first step (log length scale).
const FRESH_STARTS: [f64; 3] = [0.15, 0.5, 2.0];
const FRESH_STEP: f64 = 0.5;
/// The first step from the previous fit's length scales.
const WARM_STEP: f64 = 0.25;
/// Likelihood evaluations per start, and the spread of the simplex at which a start ends.
const EVALUATIONS_PER_START: usize = 200;
const LIKELIHOOD_TOLERANCE: f64 = 1e-4;
/// Smallest standardised variance (the values all equal).
const VARIANCE_FLOOR: f64 = 1e-12;

/// A fitted Gaussian process (see the module documentation).
#[derive(Debug, Clone)]
pub(crate) struct GaussianProcess {
    points: Vec<UnitPoint>,
    length_scales: [f64; 4],
    /// The values' mean and standard deviation (the standardisation).
    shift: f64,
    scale: f64,
    factor: Factorised,
}

/// The standardised values conditioned on one set of length scales.
#[derive(Debug, Clone)]
struct Factorised {
    /// `L`, lower triangular.
    l: DMatrix<f64>,
    /// `w = L⁻¹ 1` and `wᵀw`.
    w: DVector<f64>,
    ww: f64,
    /// `ρ = L⁻¹ (y − μ̂ 1)`.
    residual: DVector<f64>,
    mean: f64,
    variance: f64,
    log_likelihood: f64,
}

/// Matérn 5/2 correlation at scaled distance `r`.
fn matern52(r: f64) -> f64 {
    let s = 5.0_f64.sqrt() * r;
    (1.0 + s + s * s / 3.0) * (-s).exp()
}

impl GaussianProcess {
    /// Fit to `values` at `points` with the length scales of maximum likelihood, searched
    /// from `previous` (the last fit's length scales) when given, and from the isotropic
    /// starts when there is no previous fit or when `fresh`.
    pub(crate) fn fit(
        points: &[UnitPoint],
        values: &[f64],
        previous: Option<[f64; 4]>,
        fresh: bool,
    ) -> Result<GaussianProcess, Error> {
        let data = Data::new(points, values)?;
        let mut starts: Vec<([f64; 4], f64)> =
            previous.map(|p| (p, WARM_STEP)).into_iter().collect();
        if fresh || previous.is_none() {
            starts.extend(FRESH_STARTS.iter().map(|&l| ([l; 4], FRESH_STEP)));
        }
        let mut best: Option<([f64; 4], f64)> = None;
        for (start, step) in starts {
            if let Some((theta, y)) = data.maximise_likelihood(start, step)
                && best.is_none_or(|b| y < b.1)
            {
                best = Some((theta, y));
            }
        }
        let theta = best.map_or([FRESH_STARTS[1].ln(); 4], |b| b.0);
        data.into_process(theta.map(f64::exp))
    }

    /// Fit to `values` at `points` with the given length scales.
    #[cfg(test)]
    pub(crate) fn with_length_scales(
        points: &[UnitPoint],
        values: &[f64],
        length_scales: [f64; 4],
    ) -> Result<GaussianProcess, Error> {
        Data::new(points, values)?.into_process(length_scales)
    }

    /// The length scales.
    pub(crate) fn length_scales(&self) -> [f64; 4] {
        self.length_scales
    }

    /// The concentrated log-likelihood `λ` of the length scales (standardised values).
    #[cfg(test)]
    pub(crate) fn log_likelihood(&self) -> f64 {
        self.factor.log_likelihood
    }

    /// The predicted mean and standard deviation at `u`, in the values' units.
    pub(crate) fn predict(&self, u: &UnitPoint) -> (f64, f64) {
        let f = &self.factor;
        let c = DVector::from_iterator(
            self.points.len(),
            self.points
                .iter()
                .map(|p| matern52(scaled_distance(u, p, &self.length_scales))),
        );
        let v = forward_substitution(&f.l, &c);
        let mean = f.mean + v.dot(&f.residual);
        let gap = 1.0 - f.w.dot(&v);
        let variance = f.variance * (1.0 - v.dot(&v) + gap * gap / f.ww);
        (
            self.shift + self.scale * mean,
            self.scale * variance.max(0.0).sqrt(),
        )
    }
}

/// `‖(u − p) / ℓ‖`.
fn scaled_distance(u: &UnitPoint, p: &UnitPoint, ls: &[f64; 4]) -> f64 {
    (0..4)
        .map(|d| ((u[d] - p[d]) / ls[d]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// `L⁻¹ b` for lower-triangular `L` with a positive diagonal (column by column: nalgebra
/// stores `L` by columns).
fn forward_substitution(l: &DMatrix<f64>, b: &DVector<f64>) -> DVector<f64> {
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
struct Data {
    points: Vec<UnitPoint>,
    y: DVector<f64>,
    shift: f64,
    scale: f64,
    squared_differences: Vec<[f64; 4]>,
}

impl Data {
    fn new(points: &[UnitPoint], values: &[f64]) -> Result<Data, Error> {
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
        Ok(Data {
            points: points.to_vec(),
            y: DVector::from_iterator(values.len(), values.iter().map(|v| (v - shift) / scale)),
            shift,
            scale,
            squared_differences,
        })
    }

    /// Nelder–Mead on `−λ` over the log length scales from `start` (length scales) with
    /// first steps `step`: the best log length scales and their `−λ`.
    fn maximise_likelihood(&self, start: [f64; 4], step: f64) -> Option<([f64; 4], f64)> {
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

    fn into_process(self, length_scales: [f64; 4]) -> Result<GaussianProcess, Error> {
        let factor = self.factorise(&length_scales).ok_or_else(|| {
            Error::Optimiser(format!(
                "the Gaussian process cannot be fitted to the {} evaluations: its correlation \
                 matrix is not positive definite even with a jitter of {:e}",
                self.points.len(),
                JITTERS[JITTERS.len() - 1]
            ))
        })?;
        Ok(GaussianProcess {
            points: self.points,
            length_scales,
            shift: self.shift,
            scale: self.scale,
            factor,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use retarget::human_hand::SplitMix64;

    /// 30 seeded points and a function that varies along the first two axes only.
    fn sample() -> (Vec<UnitPoint>, Vec<f64>) {
        let mut rng = SplitMix64::new(11);
        let points: Vec<UnitPoint> = (0..30)
            .map(|_| std::array::from_fn(|_| rng.next_f64()))
            .collect();
        let values = points
            .iter()
            .map(|u| (3.0 * u[0]).sin() + (u[1] - 0.4).powi(2))
            .collect();
        (points, values)
    }

    #[test]
    fn the_process_interpolates_its_data_and_is_uncertain_away_from_it() {
        let (points, values) = sample();
        let gp = GaussianProcess::fit(&points, &values, None, true).unwrap();
        for (u, y) in points.iter().zip(&values) {
            let (m, s) = gp.predict(u);
            assert!((m - y).abs() < 1e-4 && s < 1e-3, "{m} vs {y}, sd {s}");
        }
        let (m, s) = gp.predict(&[0.5, 0.5, 0.5, 0.5]);
        let truth = 1.5_f64.sin() + 0.01;
        assert!((m - truth).abs() < 0.05, "{m} vs {truth}");
        assert!(s > 1e-4, "{s}");
    }

    #[test]
    fn maximum_likelihood_finds_the_axes_that_matter_and_beats_fixed_length_scales() {
        let (points, values) = sample();
        let gp = GaussianProcess::fit(&points, &values, None, true).unwrap();
        let ls = gp.length_scales();
        assert!(ls[2] > 3.0 * ls[0] && ls[3] > 3.0 * ls[0], "{ls:?}");
        assert!(ls[2] > 3.0 * ls[1] && ls[3] > 3.0 * ls[1], "{ls:?}");
        for l in [0.1, 0.5, 2.0] {
            let fixed = GaussianProcess::with_length_scales(&points, &values, [l; 4]).unwrap();
            assert!(gp.log_likelihood() > fixed.log_likelihood(), "ℓ = {l}");
        }
        let warm = GaussianProcess::fit(&points, &values, Some(ls), false).unwrap();
        assert!(warm.log_likelihood() >= gp.log_likelihood() - 1e-6);
    }

    #[test]
    fn equal_values_and_coincident_points_still_fit() {
        let points = vec![[0.2; 4], [0.2; 4], [0.7, 0.1, 0.3, 0.9]];
        let gp = GaussianProcess::fit(&points, &[1.0, 1.0, 1.0], None, true).unwrap();
        let (m, s) = gp.predict(&[0.5; 4]);
        assert!((m - 1.0).abs() < 1e-9 && s.is_finite(), "{m} {s}");
    }

    #[test]
    fn a_process_that_cannot_be_fitted_is_an_optimiser_error() {
        let points = vec![[0.2; 4], [f64::NAN, 0.5, 0.5, 0.5]];
        let e = GaussianProcess::fit(&points, &[1.0, 2.0], None, true).unwrap_err();
        assert!(
            matches!(&e, Error::Optimiser(m) if m.contains("not positive definite")),
            "{e}"
        );
        let e = GaussianProcess::fit(&[], &[], None, true).unwrap_err();
        assert!(matches!(e, Error::Optimiser(_)), "{e}");
    }
}
