//! Rokoko Studio's coordinate frame to ROS's.
//!
//! Rokoko Studio streams in a Unity-style frame: x right, y up, z forward, **left-handed**
//! (docs/LAB_CONVENTIONS.md §2). ROS (REP 103) is right-handed: x forward, y left, z up. The change of
//! basis is the reflection
//!
//! ```text
//!          ⎡ 0  0  1 ⎤                x_ros =  z_rokoko   (forward)
//!     M =  ⎢−1  0  0 ⎥ ,  det M = −1:  y_ros = −x_rokoko   (left = −right)
//!          ⎣ 0  1  0 ⎦                z_ros =  y_rokoko   (up)
//! ```
//!
//! A point maps as `p' = M p`. A rotation maps as `R' = M R Mᵀ`; because `M` is a
//! reflection its axis maps as a pseudovector, `a' = det(M) · M a = −M a`, and its angle is
//! kept, so a unit quaternion `(x, y, z, w)` maps to `(−z, x, −y, w)`.

use nalgebra::{Point3, Quaternion, UnitQuaternion, Vector3};

/// A point (or displacement) in Rokoko's frame, expressed in ROS's.
pub fn position_to_ros(x: f64, y: f64, z: f64) -> Point3<f64> {
    Point3::new(z, -x, y)
}

/// A Rokoko rotation quaternion `(x, y, z, w)` expressed in ROS's frame, normalised.
/// `None` when it is not finite or too far from unit length to be a rotation (norm outside
/// 0.5–1.5: a broken packet, not rounding).
pub fn rotation_to_ros(x: f64, y: f64, z: f64, w: f64) -> Option<UnitQuaternion<f64>> {
    let q = Quaternion::new(w, -z, x, -y);
    let norm = q.norm();
    if !norm.is_finite() || !(0.5..=1.5).contains(&norm) {
        return None;
    }
    Some(UnitQuaternion::from_quaternion(q))
}

/// The inverse of [`position_to_ros`]: a ROS point in Rokoko's frame, `(x, y, z)`.
pub fn position_from_ros(p: &Point3<f64>) -> Vector3<f64> {
    Vector3::new(-p.y, p.z, p.x)
}

/// The inverse of [`rotation_to_ros`]: a ROS rotation as a Rokoko quaternion
/// `(x, y, z, w)`.
pub fn rotation_from_ros(q: &UnitQuaternion<f64>) -> [f64; 4] {
    let (i, j, k, w) = (q.i, q.j, q.k, q.w);
    // (−z, x, −y, w) = (i, j, k, w)  ⇒  x = j, y = −k, z = −i.
    [j, -k, -i, w]
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix3, Rotation3};

    fn m() -> Matrix3<f64> {
        Matrix3::new(0.0, 0.0, 1.0, -1.0, 0.0, 0.0, 0.0, 1.0, 0.0)
    }

    #[test]
    fn axes_map_as_documented() {
        // Rokoko forward (+z) is ROS forward (+x); Rokoko right (+x) is ROS −y; up is up.
        assert_eq!(position_to_ros(0.0, 0.0, 1.0), Point3::new(1.0, 0.0, 0.0));
        assert_eq!(position_to_ros(1.0, 0.0, 0.0), Point3::new(0.0, -1.0, 0.0));
        assert_eq!(position_to_ros(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, 1.0));
        assert!((m().determinant() + 1.0).abs() < 1e-15);
    }

    #[test]
    fn rotations_map_by_conjugation_with_the_reflection() {
        // In Rokoko's left-handed frame a quaternion's matrix, read with the usual formula,
        // acts on Rokoko coordinates; the ROS quaternion must act on ROS coordinates as
        // M R Mᵀ does.
        for (x, y, z, w) in [
            (0.1, 0.2, 0.3, 0.9),
            (0.7, -0.1, 0.0, 0.7),
            (0.0, 0.0, 1.0, 0.0),
            (-0.3, 0.5, 0.2, -0.6),
        ] {
            let rokoko = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z));
            let expected = m() * rokoko.to_rotation_matrix().matrix() * m().transpose();
            let ros = rotation_to_ros(x, y, z, w).unwrap();
            let got = ros.to_rotation_matrix();
            assert!(
                (got.matrix() - expected).abs().max() < 1e-12,
                "{got} vs {expected}"
            );
            // A proper rotation (det +1) in the right-handed frame.
            assert!(
                (Rotation3::from_matrix_unchecked(expected)
                    .matrix()
                    .determinant()
                    - 1.0)
                    .abs()
                    < 1e-12
            );
        }
    }

    #[test]
    fn a_hand_computed_case() {
        // 90° about Rokoko's up axis (y): in ROS, 90° about up (z) in the other sense,
        // because the handedness flips: Rokoko forward (+z) turns to Rokoko +x (right);
        // in ROS, forward (+x) turns to −y (right).
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let q = rotation_to_ros(0.0, h, 0.0, h).unwrap();
        let turned = q * Vector3::x();
        assert!((turned - Vector3::new(0.0, -1.0, 0.0)).norm() < 1e-12);
    }

    #[test]
    fn inverses_round_trip() {
        let p = Point3::new(0.3, -0.2, 1.1);
        let v = position_from_ros(&p);
        assert!((position_to_ros(v.x, v.y, v.z) - p).norm() < 1e-15);
        let q = UnitQuaternion::from_euler_angles(0.3, -0.4, 1.2);
        let [x, y, z, w] = rotation_from_ros(&q);
        assert!(rotation_to_ros(x, y, z, w).unwrap().angle_to(&q) < 1e-12);
    }

    #[test]
    fn broken_rotations_are_refused() {
        assert!(rotation_to_ros(f64::NAN, 0.0, 0.0, 1.0).is_none());
        assert!(rotation_to_ros(0.0, 0.0, 0.0, 0.0).is_none());
        assert!(rotation_to_ros(0.0, 0.0, 0.0, 3.0).is_none());
        assert!(rotation_to_ros(0.0, 0.0, 0.0, 1.2).is_some());
    }
}
