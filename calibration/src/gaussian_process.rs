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
//! The mean `μ̂` (generalised least squares), the variance `σ̂²` and the concentrated
//! log-likelihood `λ(ℓ)` of the length scales come from the Cholesky factor `R = L Lᵀ`, with
//! `w = L⁻¹ 1` and the residual `ρ = L⁻¹ (y − μ̂ 1)` (`gp_likelihood.rs` writes them out).
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

use nalgebra::DVector;

use crate::error::Error;
pub(crate) use crate::gp_likelihood::UnitPoint;
use crate::gp_likelihood::{Factorised, Observations, forward_substitution, matern52};

/// Isotropic length scales a fresh fit starts from, and the first step (log length scale).
const FRESH_STARTS: [f64; 3] = [0.15, 0.5, 2.0];
const FRESH_STEP: f64 = 0.5;
/// The first step from the previous fit's length scales.
const WARM_STEP: f64 = 0.25;

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
        let observations = Observations::new(points, values)?;
        let mut starts: Vec<([f64; 4], f64)> =
            previous.map(|p| (p, WARM_STEP)).into_iter().collect();
        if fresh || previous.is_none() {
            starts.extend(FRESH_STARTS.iter().map(|&l| ([l; 4], FRESH_STEP)));
        }
        let mut best: Option<([f64; 4], f64)> = None;
        for (start, step) in starts {
            if let Some((theta, y)) = observations.maximise_likelihood(start, step)
                && best.is_none_or(|b| y < b.1)
            {
                best = Some((theta, y));
            }
        }
        let theta = best.map_or([FRESH_STARTS[1].ln(); 4], |b| b.0);
        GaussianProcess::conditioned(observations, theta.map(f64::exp))
    }

    /// Fit to `values` at `points` with the given length scales.
    #[cfg(test)]
    pub(crate) fn with_length_scales(
        points: &[UnitPoint],
        values: &[f64],
        length_scales: [f64; 4],
    ) -> Result<GaussianProcess, Error> {
        GaussianProcess::conditioned(Observations::new(points, values)?, length_scales)
    }

    /// The process of `observations` conditioned on `length_scales`.
    fn conditioned(
        observations: Observations,
        length_scales: [f64; 4],
    ) -> Result<GaussianProcess, Error> {
        let factor = observations.factorise_or_fail(&length_scales)?;
        Ok(GaussianProcess {
            length_scales,
            shift: observations.shift,
            scale: observations.scale,
            points: observations.points,
            factor,
        })
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
