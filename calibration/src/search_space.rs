//! The four-parameter search space (scale, roll, pitch, yaw), its mapping to a calibration
//! transform, and the space-filling initial design.

use retarget::CalibrationTransform;
use retarget::human_hand::SplitMix64;

use crate::settings::ParameterBounds;

/// A point of the search space: `[scale, roll_rad, pitch_rad, yaw_rad]`.
pub type Parameters = [f64; 4];

/// Lower and upper bounds per parameter.
pub fn box_bounds(bounds: &ParameterBounds) -> [(f64, f64); 4] {
    let a = bounds.angle_max_deg.to_radians();
    [
        (bounds.scale_min, bounds.scale_max),
        (-a, a),
        (-a, a),
        (-a, a),
    ]
}

/// A point mapped into the unit cube of the bounds (each parameter divided by its range).
pub fn to_unit(bounds: &ParameterBounds, x: &Parameters) -> [f64; 4] {
    let b = box_bounds(bounds);
    std::array::from_fn(|i| (x[i] - b[i].0) / (b[i].1 - b[i].0))
}

/// The transform a point stands for.
pub fn transform(x: &Parameters) -> CalibrationTransform {
    CalibrationTransform {
        scale: x[0],
        roll_rad: x[1],
        pitch_rad: x[2],
        yaw_rad: x[3],
        digit_scale: [1.0; 5],
    }
}

/// The point a transform stands for.
pub fn parameters(t: &CalibrationTransform) -> Parameters {
    [t.scale, t.roll_rad, t.pitch_rad, t.yaw_rad]
}

/// The identity transform clamped into the bounds: the uncalibrated default.
pub fn identity_point(bounds: &ParameterBounds) -> Parameters {
    let b = box_bounds(bounds);
    std::array::from_fn(|i| parameters(&CalibrationTransform::IDENTITY)[i].clamp(b[i].0, b[i].1))
}

/// A Latin hypercube design of `n` points in the bounds, the best of 32 random ones by the
/// smallest pairwise distance (in the unit cube), with its first point replaced by the
/// uncalibrated default so the fit can never end worse than no calibration. Deterministic in
/// `seed`.
pub fn initial_design(bounds: &ParameterBounds, n: usize, seed: u64) -> Vec<Parameters> {
    let mut rng = SplitMix64::new(seed);
    let mut best: Vec<[f64; 4]> = Vec::new();
    let mut best_spread = f64::NEG_INFINITY;
    for _ in 0..32 {
        let design = latin_hypercube(n, &mut rng);
        let spread = min_pairwise_distance(&design);
        if spread > best_spread {
            best_spread = spread;
            best = design;
        }
    }
    let b = box_bounds(bounds);
    let mut points: Vec<Parameters> = best
        .iter()
        .map(|u| std::array::from_fn(|i| b[i].0 + u[i] * (b[i].1 - b[i].0)))
        .collect();
    if let Some(first) = points.first_mut() {
        *first = identity_point(bounds);
    }
    points
}

/// `n` points uniformly at random in the bounds (the random-search baseline), deterministic in
/// `seed`.
pub fn uniform_points(bounds: &ParameterBounds, n: usize, seed: u64) -> Vec<Parameters> {
    let mut rng = SplitMix64::new(seed);
    let b = box_bounds(bounds);
    (0..n)
        .map(|_| std::array::from_fn(|i| b[i].0 + rng.next_f64() * (b[i].1 - b[i].0)))
        .collect()
}

fn latin_hypercube(n: usize, rng: &mut SplitMix64) -> Vec<[f64; 4]> {
    let mut points = vec![[0.0; 4]; n];
    for dim in 0..4 {
        let mut strata: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            let j = (rng.next_u64() % (i as u64 + 1)) as usize;
            strata.swap(i, j);
        }
        for (point, stratum) in points.iter_mut().zip(strata) {
            point[dim] = (stratum as f64 + rng.next_f64()) / n as f64;
        }
    }
    points
}

fn min_pairwise_distance(points: &[[f64; 4]]) -> f64 {
    let mut min = f64::INFINITY;
    for (i, a) in points.iter().enumerate() {
        for b in &points[i + 1..] {
            let d: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
            min = min.min(d);
        }
    }
    min.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_design_is_a_latin_hypercube_in_the_bounds_starting_at_the_default() {
        let bounds = ParameterBounds::default();
        let design = initial_design(&bounds, 20, 7);
        assert_eq!(design.len(), 20);
        assert_eq!(design[0], [1.0, 0.0, 0.0, 0.0]);
        let b = box_bounds(&bounds);
        for dim in 0..4 {
            // Every stratum but the replaced first point's holds exactly one point.
            let mut strata: Vec<usize> = design[1..]
                .iter()
                .map(|p| ((p[dim] - b[dim].0) / (b[dim].1 - b[dim].0) * 20.0) as usize)
                .collect();
            strata.sort_unstable();
            strata.dedup();
            assert_eq!(strata.len(), 19, "dimension {dim}");
        }
        assert_eq!(design, initial_design(&bounds, 20, 7), "deterministic");
        assert_ne!(design, initial_design(&bounds, 20, 8));
    }

    #[test]
    fn transform_and_parameters_round_trip() {
        let x = [1.1, 0.1, -0.2, 0.3];
        assert_eq!(parameters(&transform(&x)), x);
    }
}
