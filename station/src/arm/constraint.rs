//! Task constraints and the orientation policy: which part of the requested relative motion
//! the arm may follow.
//!
//! Input: the requested relative motion since engage, already in the robot base frame,
//! `(Δp, ΔR)` (see the module docs of [`arm`](super)). Output: the allowed part
//! `(Δp_c, ΔR_c)`, applied to the latched robot pose as `p = p₀ + Δp_c`, `R = ΔR_c · R₀`.
//!
//! | constraint | translation `Δp_c` | rotation `ΔR_c` (policy `hold_when_constrained`) |
//! |---|---|---|
//! | `fixed` | `0` | `I` |
//! | `vertical_axis`, `horizontal_axis` (unit axis `a`) | `(aᵀΔp) · a` | `I` |
//! | `free` | `Δp` | `ΔR` |
//!
//! Policy `hold` also gives `ΔR_c = I` under `free` (translation-only teleoperation); policy
//! `twist_about_axis` gives an axis constraint the twist of `ΔR` about `a` (swing–twist
//! decomposition: for `ΔR = (w, v)`, twist = `normalise(w, (aᵀv)·a)`), so the hand may turn
//! about the rod but not tilt. `fixed` always holds both.

use nalgebra::{Quaternion, Unit, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

/// Motion removed by a constraint below this (metres or radians) does not set the
/// `constrained` flag: it is rounding, not a restriction.
const CONSTRAINED_FLAG_TOLERANCE: f64 = 1e-12;

/// How the arm may move during a task: the task catalog's own type (`scoring`, the lower
/// crate: it depends on no other crate of the workspace), so a task's constraint is the
/// station's without a mapping.
pub use scoring::ArmConstraint as Constraint;

/// What happens to the glove's relative rotation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OrientationPolicy {
    /// `free` follows the full relative rotation; `fixed` and the axis constraints hold the
    /// latched orientation. The default: on a rod the task is the translation, and a held
    /// orientation cannot twist the fixture.
    HoldWhenConstrained,
    /// Every constraint holds the latched orientation (`free` becomes translation only).
    Hold,
    /// `free` follows the full relative rotation; the axis constraints follow only the
    /// rotation about their own axis (the twist); `fixed` holds.
    TwistAboutAxis,
}

/// A constraint with its axis resolved from the configuration (unit, robot base frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum ResolvedConstraint {
    /// See [`Constraint::Fixed`].
    Fixed,
    /// Along this unit axis.
    Axis(Unit<Vector3<f64>>),
    /// See [`Constraint::Free`].
    Free,
}

/// The translation a constraint allows, before the workspace clamp.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum AllowedTranslation {
    /// Stay at the latched position.
    None,
    /// `p₀ + t · axis`.
    AlongAxis {
        /// Unit axis, robot base frame.
        axis: Unit<Vector3<f64>>,
        /// Signed distance along it, metres.
        t: f64,
    },
    /// `p₀ + Δp`.
    Free(Vector3<f64>),
}

/// The allowed part of a requested relative motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ConstrainedMotion {
    /// Allowed translation.
    pub translation: AllowedTranslation,
    /// Allowed relative rotation `ΔR_c`, robot base frame (left-multiplies `R₀`).
    pub rotation: UnitQuaternion<f64>,
    /// The constraint removed part of the requested motion.
    pub constrained: bool,
}

/// Keep the part of `(delta_p, delta_r)` that `constraint` and `policy` allow.
pub(crate) fn constrain(
    constraint: ResolvedConstraint,
    policy: OrientationPolicy,
    delta_p: &Vector3<f64>,
    delta_r: &UnitQuaternion<f64>,
) -> ConstrainedMotion {
    let identity = UnitQuaternion::identity();
    let (translation, removed_translation, rotation) = match constraint {
        ResolvedConstraint::Fixed => (AllowedTranslation::None, delta_p.norm(), identity),
        ResolvedConstraint::Axis(axis) => {
            let t = axis.dot(delta_p);
            let removed = (delta_p - axis.into_inner() * t).norm();
            let rotation = match policy {
                OrientationPolicy::TwistAboutAxis => twist_about_axis(delta_r, &axis),
                OrientationPolicy::HoldWhenConstrained | OrientationPolicy::Hold => identity,
            };
            (AllowedTranslation::AlongAxis { axis, t }, removed, rotation)
        }
        ResolvedConstraint::Free => {
            let rotation = match policy {
                OrientationPolicy::Hold => identity,
                OrientationPolicy::HoldWhenConstrained | OrientationPolicy::TwistAboutAxis => {
                    *delta_r
                }
            };
            (AllowedTranslation::Free(*delta_p), 0.0, rotation)
        }
    };
    let removed_rotation = rotation.angle_to(delta_r);
    ConstrainedMotion {
        translation,
        rotation,
        constrained: removed_translation > CONSTRAINED_FLAG_TOLERANCE
            || removed_rotation > CONSTRAINED_FLAG_TOLERANCE,
    }
}

/// The twist of `q` about the unit `axis`: the rotation about `axis` closest to `q` (swing–twist
/// decomposition `q = swing · twist`, with the swing's axis perpendicular to `axis`).
///
/// A half-turn about an axis perpendicular to `axis` has no defined twist; the identity is
/// returned.
pub fn twist_about_axis(q: &UnitQuaternion<f64>, axis: &Unit<Vector3<f64>>) -> UnitQuaternion<f64> {
    let projected = axis.into_inner() * axis.dot(&q.imag());
    let twist = Quaternion::from_parts(q.scalar(), projected);
    if twist.norm() <= CONSTRAINED_FLAG_TOLERANCE {
        UnitQuaternion::identity()
    } else {
        UnitQuaternion::new_normalize(twist)
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;

    fn requested() -> (Vector3<f64>, UnitQuaternion<f64>) {
        (
            Vector3::new(0.03, -0.02, 0.05),
            UnitQuaternion::from_euler_angles(0.2, -0.1, 0.4),
        )
    }

    #[test]
    fn fixed_allows_nothing() {
        let (dp, dr) = requested();
        for policy in [
            OrientationPolicy::HoldWhenConstrained,
            OrientationPolicy::Hold,
            OrientationPolicy::TwistAboutAxis,
        ] {
            let m = constrain(ResolvedConstraint::Fixed, policy, &dp, &dr);
            assert_eq!(m.translation, AllowedTranslation::None);
            assert_eq!(m.rotation, UnitQuaternion::identity());
            assert!(m.constrained);
        }
    }

    #[test]
    fn axis_keeps_the_projection_and_holds_orientation() {
        let (dp, dr) = requested();
        let m = constrain(
            ResolvedConstraint::Axis(Vector3::z_axis()),
            OrientationPolicy::HoldWhenConstrained,
            &dp,
            &dr,
        );
        match m.translation {
            AllowedTranslation::AlongAxis { t, .. } => assert_eq!(t, 0.05),
            other => panic!("{other:?}"),
        }
        assert_eq!(m.rotation, UnitQuaternion::identity());
        assert!(m.constrained);
    }

    #[test]
    fn motion_along_the_axis_is_not_flagged() {
        let dp = Vector3::new(0.0, 0.0, -0.04);
        let m = constrain(
            ResolvedConstraint::Axis(Vector3::z_axis()),
            OrientationPolicy::HoldWhenConstrained,
            &dp,
            &UnitQuaternion::identity(),
        );
        assert!(!m.constrained);
    }

    #[test]
    fn free_follows_unless_the_policy_holds() {
        let (dp, dr) = requested();
        let m = constrain(
            ResolvedConstraint::Free,
            OrientationPolicy::HoldWhenConstrained,
            &dp,
            &dr,
        );
        assert_eq!(m.translation, AllowedTranslation::Free(dp));
        assert_eq!(m.rotation, dr);
        assert!(!m.constrained);
        let held = constrain(ResolvedConstraint::Free, OrientationPolicy::Hold, &dp, &dr);
        assert_eq!(held.rotation, UnitQuaternion::identity());
        assert!(held.constrained);
    }

    #[test]
    fn twist_policy_turns_about_the_axis_only() {
        let axis = Unit::new_normalize(Vector3::new(1.0, 1.0, 0.0));
        let (dp, dr) = requested();
        let m = constrain(
            ResolvedConstraint::Axis(axis),
            OrientationPolicy::TwistAboutAxis,
            &dp,
            &dr,
        );
        // The allowed rotation leaves the axis where it is ...
        assert!((m.rotation * axis.into_inner() - axis.into_inner()).norm() < 1e-12);
        // ... and is not the identity: part of the request was about the axis.
        assert!(m.rotation.angle() > 1e-3);
    }

    #[test]
    fn twist_of_a_rotation_about_the_axis_is_itself() {
        let q = UnitQuaternion::from_scaled_axis(Vector3::z() * 0.7);
        let t = twist_about_axis(&q, &Vector3::z_axis());
        assert!(t.angle_to(&q) < 1e-12);
        // A swing-only rotation has no twist; a half-turn swing is the degenerate case.
        let swing = UnitQuaternion::from_scaled_axis(Vector3::x() * 0.7);
        assert!(twist_about_axis(&swing, &Vector3::z_axis()).angle() < 1e-12);
        let half_turn = UnitQuaternion::from_scaled_axis(Vector3::x() * PI);
        assert_eq!(
            twist_about_axis(&half_turn, &Vector3::z_axis()),
            UnitQuaternion::identity()
        );
    }

    #[test]
    fn twist_and_swing_recompose_the_rotation() {
        let q = UnitQuaternion::from_euler_angles(0.3, 0.5, -1.1);
        let axis = Vector3::z_axis();
        let twist = twist_about_axis(&q, &axis);
        let swing = q * twist.inverse();
        // The swing's axis is perpendicular to the twist axis.
        let swing_axis = swing.axis().unwrap();
        assert!(swing_axis.dot(&axis).abs() < 1e-12);
    }
}
