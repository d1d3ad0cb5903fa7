//! The workspace box: an axis-aligned box in the robot base frame that every target position
//! stays inside.
//!
//! Free motion is clamped per coordinate (the Euclidean projection onto the box). Motion along
//! a constraint axis is clamped along the axis line instead, to the segment
//! `{p₀ + t·a : lo ≤ p₀ + t·a ≤ hi}`, so the target stays on its axis; a per-coordinate clamp
//! would push a tilted axis's target off the line.

use nalgebra::{Unit, Vector3};

const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

/// Axis-aligned box, robot base frame, metres; `min_m[i] < max_m[i]` (checked by the config).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkspaceBox {
    /// Lower corner, metres.
    pub min_m: Vector3<f64>,
    /// Upper corner, metres.
    pub max_m: Vector3<f64>,
}

/// A coordinate outside the box: which axis, the value and the bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxViolation {
    /// `x`, `y` or `z`.
    pub axis: &'static str,
    /// The coordinate, metres.
    pub value: f64,
    /// Lower bound, metres.
    pub min_m: f64,
    /// Upper bound, metres.
    pub max_m: f64,
}

impl WorkspaceBox {
    /// Whether `p` is inside the box (boundary included).
    pub fn contains(&self, p: &Vector3<f64>) -> bool {
        self.first_violation(p).is_none()
    }

    /// The first coordinate of `p` outside the box, if any.
    pub fn first_violation(&self, p: &Vector3<f64>) -> Option<BoxViolation> {
        (0..3)
            .find(|&i| !(p[i] >= self.min_m[i] && p[i] <= self.max_m[i]))
            .map(|i| BoxViolation {
                axis: AXIS_NAMES[i],
                value: p[i],
                min_m: self.min_m[i],
                max_m: self.max_m[i],
            })
    }

    /// Per-coordinate clamp: the closest point of the box to `p`.
    pub fn clamp(&self, p: &Vector3<f64>) -> Vector3<f64> {
        Vector3::from_fn(|i, _| p[i].clamp(self.min_m[i], self.max_m[i]))
    }

    /// The range `[t_lo, t_hi]` of `t` with `origin + t·axis` inside the box.
    ///
    /// `origin` must be inside the box, so the range contains 0 and is never empty. Axis
    /// components that are exactly zero leave their coordinate at `origin`'s, which is inside.
    pub fn line_interval(&self, origin: &Vector3<f64>, axis: &Unit<Vector3<f64>>) -> (f64, f64) {
        let mut t_lo = f64::NEG_INFINITY;
        let mut t_hi = f64::INFINITY;
        for i in 0..3 {
            let a = axis[i];
            if a == 0.0 {
                continue;
            }
            let t_min = (self.min_m[i] - origin[i]) / a;
            let t_max = (self.max_m[i] - origin[i]) / a;
            t_lo = t_lo.max(t_min.min(t_max));
            t_hi = t_hi.min(t_min.max(t_max));
        }
        // Rounding can make a bound cross 0 by an ulp when the origin sits on a face.
        (t_lo.min(0.0), t_hi.max(0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box() -> WorkspaceBox {
        WorkspaceBox {
            min_m: Vector3::new(0.0, -1.0, 0.0),
            max_m: Vector3::new(1.0, 1.0, 2.0),
        }
    }

    #[test]
    fn clamp_is_the_nearest_point_of_the_box() {
        let b = unit_box();
        assert_eq!(
            b.clamp(&Vector3::new(2.0, 0.5, -3.0)),
            Vector3::new(1.0, 0.5, 0.0)
        );
        let inside = Vector3::new(0.5, 0.0, 1.0);
        assert_eq!(b.clamp(&inside), inside);
    }

    #[test]
    fn first_violation_names_the_axis() {
        let v = unit_box()
            .first_violation(&Vector3::new(0.5, 0.0, 2.5))
            .unwrap();
        assert_eq!(v.axis, "z");
        assert_eq!((v.value, v.min_m, v.max_m), (2.5, 0.0, 2.0));
        assert!(
            unit_box()
                .first_violation(&Vector3::new(0.5, f64::NAN, 1.0))
                .is_some()
        );
    }

    #[test]
    fn line_interval_of_a_vertical_axis() {
        let (lo, hi) = unit_box().line_interval(&Vector3::new(0.5, 0.0, 0.5), &Vector3::z_axis());
        assert_eq!((lo, hi), (-0.5, 1.5));
    }

    #[test]
    fn line_interval_of_a_tilted_axis_keeps_both_ends_in_the_box() {
        let b = unit_box();
        let origin = Vector3::new(0.2, 0.0, 1.0);
        let axis = Unit::new_normalize(Vector3::new(1.0, -2.0, 0.5));
        let (lo, hi) = b.line_interval(&origin, &axis);
        assert!(lo < 0.0 && hi > 0.0);
        for t in [lo, hi] {
            let p = origin + axis.into_inner() * t;
            assert!(b.clamp(&p).metric_distance(&p) < 1e-12, "{p}");
        }
        // Just beyond either end is outside.
        assert!(!b.contains(&(origin + axis.into_inner() * (hi + 1e-6))));
        assert!(!b.contains(&(origin + axis.into_inner() * (lo - 1e-6))));
    }
}
