//! Per-tick step caps, scaled by norm.
//!
//! Relative to the previous command `(p_prev, R_prev)` (robot base frame):
//!
//! ```text
//! d = p_target − p_prev                 if ‖d‖ > δp:  p = p_prev + d · δp / ‖d‖
//! ρ = log(R_target · R_prevᵀ) ∈ ℝ³      if ‖ρ‖ > δR:  R = exp(ρ · δR / ‖ρ‖) · R_prev
//! ```
//!
//! The whole step vector is scaled, never clipped per axis, so the command moves straight
//! toward the target (per-axis clipping would bend the path and could leave a constraint axis).
//! `ρ` is the rotation vector of the shortest rotation (angle in [0, π]), so the orientation
//! moves along the geodesic toward the target.

use nalgebra::{UnitQuaternion, Vector3};

/// A value after a step cap, and whether the cap changed it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Capped<T> {
    /// The value, within the cap of the previous one.
    pub value: T,
    /// The requested step exceeded the cap and was scaled down.
    pub capped: bool,
}

/// Move from `previous` toward `target` by at most `max_step_m` (Euclidean norm).
pub fn cap_translation(
    previous: &Vector3<f64>,
    target: &Vector3<f64>,
    max_step_m: f64,
) -> Capped<Vector3<f64>> {
    let step = target - previous;
    let length = step.norm();
    if length > max_step_m {
        Capped {
            value: previous + step * (max_step_m / length),
            capped: true,
        }
    } else {
        Capped {
            value: *target,
            capped: false,
        }
    }
}

/// Rotate from `previous` toward `target` by at most `max_step_rad` (rotation angle, applied
/// in the robot base frame).
pub fn cap_rotation(
    previous: &UnitQuaternion<f64>,
    target: &UnitQuaternion<f64>,
    max_step_rad: f64,
) -> Capped<UnitQuaternion<f64>> {
    let rotation_vector = (target * previous.inverse()).scaled_axis();
    let angle = rotation_vector.norm();
    if angle > max_step_rad {
        let step = UnitQuaternion::from_scaled_axis(rotation_vector * (max_step_rad / angle));
        Capped {
            value: UnitQuaternion::new_normalize((step * previous).into_inner()),
            capped: true,
        }
    } else {
        Capped {
            value: *target,
            capped: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;

    #[test]
    fn a_small_step_passes_unchanged() {
        let prev = Vector3::new(0.1, 0.2, 0.3);
        let target = prev + Vector3::new(0.003, -0.004, 0.0);
        let c = cap_translation(&prev, &target, 0.01);
        assert!(!c.capped);
        assert_eq!(c.value, target);
    }

    #[test]
    fn a_large_step_is_scaled_by_norm_keeping_its_direction() {
        let prev = Vector3::zeros();
        // Per-axis clipping to 0.01 would give (0.01, 0.01, 0): direction 45°, wrong.
        let target = Vector3::new(0.3, 0.04, 0.0);
        let c = cap_translation(&prev, &target, 0.01);
        assert!(c.capped);
        assert!((c.value.norm() - 0.01).abs() < 1e-15);
        let expected_direction = target.normalize();
        assert!((c.value.normalize() - expected_direction).norm() < 1e-12);
        // Per-axis clipping would have produced this instead.
        assert!((c.value - Vector3::new(0.01, 0.01, 0.0)).norm() > 1e-3);
    }

    #[test]
    fn rotation_is_capped_along_the_geodesic() {
        let prev = UnitQuaternion::from_euler_angles(0.1, -0.2, 0.3);
        let delta = UnitQuaternion::from_scaled_axis(Vector3::new(0.0, 0.6, 0.8) * 1.0);
        let target = delta * prev;
        let c = cap_rotation(&prev, &target, 0.15);
        assert!(c.capped);
        assert!((prev.angle_to(&c.value) - 0.15).abs() < 1e-12);
        // Same axis as the requested step.
        let axis = (c.value * prev.inverse()).axis().unwrap();
        assert!((axis.into_inner() - Vector3::new(0.0, 0.6, 0.8)).norm() < 1e-9);
        // The rest of the way is 0.85 rad.
        assert!((c.value.angle_to(&target) - 0.85).abs() < 1e-12);
    }

    #[test]
    fn rotation_cap_takes_the_short_way_round() {
        let prev = UnitQuaternion::identity();
        // 3π/2 about z is −π/2 the short way.
        let target = UnitQuaternion::from_scaled_axis(Vector3::z() * (1.5 * PI));
        let c = cap_rotation(&prev, &target, 0.1);
        assert!(c.capped);
        assert!((c.value.scaled_axis() - Vector3::z() * -0.1).norm() < 1e-12);
    }

    #[test]
    fn a_small_rotation_passes_unchanged() {
        let prev = UnitQuaternion::from_euler_angles(0.4, 0.0, -1.0);
        let target = UnitQuaternion::from_scaled_axis(Vector3::x() * 0.01) * prev;
        let c = cap_rotation(&prev, &target, 0.02);
        assert!(!c.capped);
        assert_eq!(c.value, target);
    }
}
