//! Standardisation and principal component analysis of the segment features.
//!
//! `Z` (segments × features) holds z-scores: each feature minus its mean over the segments,
//! divided by its sample standard deviation; a feature whose standard deviation is below
//! [`CONSTANT_TOLERANCE`] becomes 0. With the thin SVD `Z = U Σ Vᵀ` (singular values
//! descending), component *j* has loadings `v_j`, scores `Z v_j` and explains
//! `σ_j² / ‖Z‖²_F` of the total variance. Each `v_j` is signed so that its largest-magnitude
//! loading (the first, among ties) is positive, so the same data always gives the same figure.

#![allow(non_snake_case)] // Z, V: the matrices of the formulas above

use nalgebra::{DMatrix, SVD};

use crate::error::StudyError;

/// A feature whose standard deviation over the segments is below this (hand lengths) is
/// constant: rounding noise is not scaled up to unit variance.
pub const CONSTANT_TOLERANCE: f64 = 1e-9;

/// Relative tolerance for two loadings' magnitudes to count as tied in the sign convention.
const TIE_TOLERANCE: f64 = 1e-9;

/// The fitted components.
#[derive(Debug, Clone, PartialEq)]
pub struct Pca {
    /// Per row of the input: its score on each kept component.
    pub scores: Vec<Vec<f64>>,
    /// Per kept component: its fraction of the standardised features' total variance.
    pub variance_explained: Vec<f64>,
    /// Per kept component: its loading on each feature (unit length).
    pub loadings: Vec<Vec<f64>>,
    /// Features treated as constant.
    pub constant_features: usize,
}

/// `rows` (all of one length) as z-scores, and how many features were constant.
pub fn standardise(rows: &[Vec<f64>]) -> (DMatrix<f64>, usize) {
    let n = rows.len();
    let p = rows.first().map_or(0, Vec::len);
    let mut Z = DMatrix::from_fn(n, p, |i, j| rows[i][j]);
    let mut constant = 0;
    for mut column in Z.column_iter_mut() {
        let mean = column.mean();
        column.add_scalar_mut(-mean);
        let sd = (column.norm_squared() / (n as f64 - 1.0).max(1.0)).sqrt();
        if sd < CONSTANT_TOLERANCE {
            column.fill(0.0);
            constant += 1;
        } else {
            column /= sd;
        }
    }
    (Z, constant)
}

/// Up to `components` principal components of `rows` (at least two rows, all of one length,
/// finite), capped at rows − 1 and at the number of varying features.
pub fn fit(rows: &[Vec<f64>], components: usize) -> Result<Pca, StudyError> {
    let (Z, constant_features) = standardise(rows);
    let (n, p) = Z.shape();
    if n < 2 {
        return Err(StudyError::TooFewSegments { found: n });
    }
    let varying = p - constant_features;
    let total = Z.norm_squared();
    if varying == 0 || total <= 0.0 {
        return Err(StudyError::NoVariance {
            segments: n,
            tolerance: CONSTANT_TOLERANCE,
        });
    }
    let max_iterations = 1000 * (n.min(p) + 10);
    let svd = SVD::try_new(Z.clone(), false, true, 5.0 * f64::EPSILON, max_iterations).ok_or(
        StudyError::PcaNotConverged {
            rows: n,
            columns: p,
        },
    )?;
    let Some(V_t) = svd.v_t else {
        return Err(StudyError::PcaNotConverged {
            rows: n,
            columns: p,
        });
    };
    let kept = components.min(n - 1).min(varying).min(V_t.nrows());
    let mut scores = vec![Vec::with_capacity(kept); n];
    let mut variance_explained = Vec::with_capacity(kept);
    let mut loadings = Vec::with_capacity(kept);
    for j in 0..kept {
        let mut v = V_t.row(j).transpose();
        if sign_of_largest(v.as_slice()) < 0.0 {
            v.neg_mut();
        }
        let s = &Z * &v;
        s.iter().zip(&mut scores).for_each(|(s, row)| row.push(*s));
        variance_explained.push(svd.singular_values[j].powi(2) / total);
        loadings.push(v.iter().copied().collect());
    }
    Ok(Pca {
        scores,
        variance_explained,
        loadings,
        constant_features,
    })
}

/// The sign of the largest-magnitude entry of `v` (the first among ties).
fn sign_of_largest(v: &[f64]) -> f64 {
    let max = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let first = v.iter().find(|x| x.abs() >= max * (1.0 - TIE_TOLERANCE));
    first.map_or(1.0, |x| x.signum())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// x = (0, 1, 2, 3), y = (0, 2, 1, 3): both have mean 1.5 and variance 5/3, correlation
    /// r = 4/5. The correlation matrix [[1, r], [r, 1]] has eigenvalues 1 ± r = 1.8, 0.2
    /// (explaining 0.9 and 0.1) with eigenvectors (1, 1)/√2 and (1, −1)/√2, so a point's
    /// scores are (zx + zy)/√2 and (zx − zy)/√2 with z = (v − 1.5)/√(5/3).
    #[test]
    fn a_two_feature_example_matches_the_hand_computation() {
        let rows = vec![
            vec![0.0, 0.0],
            vec![1.0, 2.0],
            vec![2.0, 1.0],
            vec![3.0, 3.0],
        ];
        let pca = fit(&rows, 3).unwrap();
        assert_eq!(pca.variance_explained.len(), 2, "capped at 2 features");
        assert!((pca.variance_explained[0] - 0.9).abs() < 1e-12);
        assert!((pca.variance_explained[1] - 0.1).abs() < 1e-12);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((pca.loadings[0][0] - h).abs() < 1e-12 && (pca.loadings[0][1] - h).abs() < 1e-12);
        assert!((pca.loadings[1][0] - h).abs() < 1e-12 && (pca.loadings[1][1] + h).abs() < 1e-12);
        let k = 1.0 / (2.0 * 5.0 / 3.0_f64).sqrt(); // 1 / (√2 · √(5/3)) = √0.3
        let expected = [[-3.0 * k, 0.0], [0.0, -k], [0.0, k], [3.0 * k, 0.0]];
        for (got, want) in pca.scores.iter().zip(expected) {
            assert!((got[0] - want[0]).abs() < 1e-12, "{got:?} vs {want:?}");
            assert!((got[1] - want[1]).abs() < 1e-12, "{got:?} vs {want:?}");
        }
        assert!((expected[0][0] + 1.643_167_672_515_498).abs() < 1e-12);
    }

    #[test]
    fn constant_features_are_zero_and_all_constant_is_an_error() {
        let rows = vec![vec![1.0, 5.0], vec![2.0, 5.0], vec![4.0, 5.0]];
        let (Z, constant) = standardise(&rows);
        assert_eq!(constant, 1);
        assert!(Z.column(1).iter().all(|v| *v == 0.0));
        let pca = fit(&rows, 3).unwrap();
        assert_eq!(pca.variance_explained.len(), 1);
        assert!((pca.variance_explained[0] - 1.0).abs() < 1e-12);
        let flat = vec![vec![1.0, 5.0]; 4];
        assert!(matches!(
            fit(&flat, 2),
            Err(StudyError::NoVariance { segments: 4, .. })
        ));
    }

    #[test]
    fn variance_explained_is_descending_and_sums_to_at_most_one() {
        // Deterministic pseudo-random rows: 9 segments × 5 features.
        let rows: Vec<Vec<f64>> = (0..9)
            .map(|i| {
                (0..5)
                    .map(|j| ((i * 7 + j * 13) % 11) as f64 * (1.0 + j as f64))
                    .collect()
            })
            .collect();
        let pca = fit(&rows, 5).unwrap();
        let v = &pca.variance_explained;
        assert_eq!(v.len(), 5);
        assert!(v.windows(2).all(|w| w[0] >= w[1]), "{v:?}");
        assert!(v.iter().sum::<f64>() <= 1.0 + 1e-12, "{v:?}");
        let three = fit(&rows, 3).unwrap();
        assert_eq!(three.scores[0].len(), 3);
        assert!(three.variance_explained.iter().sum::<f64>() < 1.0);
    }
}
