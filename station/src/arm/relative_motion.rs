//! The glove's motion since engage, expressed in the robot base frame.
//!
//! With `G` the glove tracker frame, `B` the robot base frame, `R_BG` = `glove_to_base`
//! (`ᴮv = R_BG · ᴳv`), the wrist pose latched at engage `(ᴳp_w0, ᴳR_w0)` and the current wrist
//! pose `(ᴳp_w, ᴳR_w)`:
//!
//! ```text
//! Δp = s · R_BG · (ᴳp_w − ᴳp_w0)                       metres, base frame
//! ΔR = R_BG · (ᴳR_w · ᴳR_w0ᵀ) · R_BGᵀ                   rotation about base-frame axes
//! ```
//!
//! `ᴳR_w · ᴳR_w0ᵀ` is the wrist's rotation since engage about axes fixed in the tracker frame
//! (the spatial, left-multiplied difference); conjugating by `R_BG` re-expresses the same
//! rotation about the corresponding base-frame axes. Turning the wrist about the tracker's
//! vertical turns the end effector about the base's vertical (if `R_BG` maps one to the other),
//! whatever the wrist's and the end effector's own orientations: the mapping needs no
//! wrist-to-flange calibration, only `R_BG`. Only rotations enter, so a translation between
//! the frames' origins is irrelevant to relative motion and is not configured.

use nalgebra::{Isometry3, UnitQuaternion, Vector3};

/// Relative motion `(Δp, ΔR)` of the glove wrist since engage, robot base frame.
pub(crate) fn relative_motion(
    glove_to_base: &UnitQuaternion<f64>,
    translation_scale: f64,
    glove_at_engage: &Isometry3<f64>,
    glove_now: &Isometry3<f64>,
) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let delta_p_glove = glove_now.translation.vector - glove_at_engage.translation.vector;
    let delta_p = glove_to_base * delta_p_glove * translation_scale;
    let delta_r_glove = glove_now.rotation * glove_at_engage.rotation.inverse();
    let delta_r = glove_to_base * delta_r_glove * glove_to_base.inverse();
    (delta_p, delta_r)
}

#[cfg(test)]
mod tests {
    use std::f64::consts::FRAC_PI_2;

    use nalgebra::Translation3;

    use super::*;

    fn pose(p: [f64; 3], rpy: [f64; 3]) -> Isometry3<f64> {
        Isometry3::from_parts(
            Translation3::new(p[0], p[1], p[2]),
            UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
        )
    }

    #[test]
    fn no_motion_gives_zero() {
        let g = pose([0.3, 1.2, -0.4], [0.5, -0.3, 2.0]);
        let (dp, dr) = relative_motion(
            &UnitQuaternion::from_euler_angles(0.1, 0.2, 0.3),
            2.0,
            &g,
            &g,
        );
        assert!(dp.norm() < 1e-15);
        assert!(dr.angle() < 1e-15);
    }

    #[test]
    fn translation_is_scaled_and_rotated_into_the_base_frame() {
        // Tracker Y-up to base Z-up: +90° about x takes tracker y to base z.
        let glove_to_base = UnitQuaternion::from_scaled_axis(Vector3::x() * FRAC_PI_2);
        let g0 = pose([0.0, 1.0, 0.0], [0.3, 0.0, 0.0]);
        let g1 = pose([0.0, 1.1, 0.0], [0.3, 0.0, 0.0]);
        let (dp, _) = relative_motion(&glove_to_base, 0.5, &g0, &g1);
        assert!((dp - Vector3::new(0.0, 0.0, 0.05)).norm() < 1e-12, "{dp}");
    }

    #[test]
    fn rotation_about_the_tracker_vertical_is_rotation_about_the_base_vertical() {
        let glove_to_base = UnitQuaternion::from_scaled_axis(Vector3::x() * FRAC_PI_2);
        // The wrist starts in an arbitrary orientation, then turns 0.4 rad about tracker y.
        let g0 = pose([0.0; 3], [0.7, -0.2, 1.9]);
        let turn = UnitQuaternion::from_scaled_axis(Vector3::y() * 0.4);
        let g1 = Isometry3::from_parts(g0.translation, turn * g0.rotation);
        let (_, dr) = relative_motion(&glove_to_base, 1.0, &g0, &g1);
        assert!(
            (dr.scaled_axis() - Vector3::z() * 0.4).norm() < 1e-12,
            "{dr}"
        );
    }
}
