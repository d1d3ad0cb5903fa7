//! Silhouette values (Rousseeuw 1987) of labelled points, Euclidean distance.
//!
//! For point *i* in cluster *A*: `a(i)` is its mean distance to the other members of *A*,
//! `b(i)` the smallest mean distance to the members of another cluster, and
//! `s(i) = (b(i) − a(i)) / max(a(i), b(i))`, in [−1, 1]; `s(i) = 0` when *A* has no other
//! member (or when `a = b = 0`). Near 1: the point sits well inside its own cluster; near 0:
//! on the border; negative: closer to another cluster.

/// The silhouette value of every point; `labels[i]` is point *i*'s cluster (any numbering).
/// Needs at least two distinct labels for a meaningful value (else every value is 0).
pub fn silhouette_values(points: &[Vec<f64>], labels: &[usize]) -> Vec<f64> {
    let clusters = labels.iter().max().map_or(0, |m| m + 1);
    let mut sizes = vec![0_usize; clusters];
    labels.iter().for_each(|&l| sizes[l] += 1);
    let mut sums = vec![0.0; clusters];
    (points.iter().zip(labels).enumerate())
        .map(|(i, (p, &own))| {
            sums.fill(0.0);
            for (j, (q, &other)) in points.iter().zip(labels).enumerate() {
                if i != j {
                    sums[other] += distance(p, q);
                }
            }
            if sizes[own] < 2 {
                return 0.0;
            }
            let a = sums[own] / (sizes[own] - 1) as f64;
            let b = (0..clusters)
                .filter(|&c| c != own && sizes[c] > 0)
                .map(|c| sums[c] / sizes[c] as f64)
                .fold(f64::INFINITY, f64::min);
            let denominator = a.max(b);
            if !b.is_finite() || denominator <= 0.0 {
                0.0
            } else {
                (b - a) / denominator
            }
        })
        .collect()
}

fn distance(p: &[f64], q: &[f64]) -> f64 {
    p.iter()
        .zip(q)
        .map(|(a, b)| (a - b).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points on a line: cluster 0 at 0 and 1, cluster 1 at 4 and 6, cluster 2 alone at 10.
    /// Point 0: a = 1, b = min(mean(4, 6), 10) = 5, s = 4/5.
    /// Point 1: a = 1, b = min(mean(3, 5), 9) = 4, s = 3/4.
    /// Point 4 (at 4): a = 2, b = min(mean(4, 3), 6) = 3.5, s = 1.5/3.5 = 3/7.
    /// Point 6: a = 2, b = min(mean(6, 5), 4) = 4, s = 2/4 = 1/2.
    /// Point 10: a singleton, s = 0.
    #[test]
    fn a_hand_computed_example() {
        let points: Vec<Vec<f64>> = [0.0, 1.0, 4.0, 6.0, 10.0].map(|x| vec![x]).to_vec();
        let s = silhouette_values(&points, &[0, 0, 1, 1, 2]);
        let expected = [0.8, 0.75, 3.0 / 7.0, 0.5, 0.0];
        for (got, want) in s.iter().zip(expected) {
            assert!((got - want).abs() < 1e-12, "{s:?}");
        }
    }

    #[test]
    fn two_dimensional_distances_are_euclidean() {
        // Cluster 0 at (0, 0) and (0, 2); cluster 1 at (3, 0) and (3, 2).
        // Point (0, 0): a = 2, b = mean(3, √13) = (3 + √13)/2.
        let points = vec![
            vec![0.0, 0.0],
            vec![0.0, 2.0],
            vec![3.0, 0.0],
            vec![3.0, 2.0],
        ];
        let s = silhouette_values(&points, &[0, 0, 1, 1]);
        let b = (3.0 + 13.0_f64.sqrt()) / 2.0;
        assert!((s[0] - (b - 2.0) / b).abs() < 1e-12, "{s:?}");
        assert!(
            s.iter().all(|v| (v - s[0]).abs() < 1e-12),
            "symmetric: {s:?}"
        );
    }

    #[test]
    fn identical_points_and_one_label_give_zero() {
        let points = vec![vec![1.0]; 3];
        assert_eq!(silhouette_values(&points, &[0, 1, 1]), [0.0, 0.0, 0.0]);
        assert_eq!(
            silhouette_values(&[vec![0.0], vec![1.0]], &[0, 0]),
            [0.0, 0.0]
        );
    }
}
