//! Forward kinematics: the pose of every link in the model's base frame.
//!
//! `T_child = T_parent · origin · Rot(axis, multiplier · q[dof] + offset)` for every joint in
//! topological order. [`FkState`] holds one pose per link and is reused across calls, so the
//! hot path allocates nothing.

use nalgebra::{Isometry3, Point3, UnitQuaternion};

use crate::error::Error;
use crate::hand_model::{HandModel, JointMotion, LinkId};

/// Poses of all links for one joint vector, in the model's base frame (metres).
#[derive(Debug, Clone, PartialEq)]
pub struct FkState {
    pub(crate) poses: Vec<Isometry3<f64>>,
}

impl FkState {
    /// Pose of `link` in the base frame.
    pub fn pose(&self, link: LinkId) -> &Isometry3<f64> {
        &self.poses[link.0]
    }

    /// Origin of `link` in the base frame, metres.
    pub fn position(&self, link: LinkId) -> Point3<f64> {
        Point3::from(self.poses[link.0].translation.vector)
    }
}

impl HandModel {
    /// A state buffer sized for this model, posed at the identity.
    pub fn fk_state(&self) -> FkState {
        FkState {
            poses: vec![Isometry3::identity(); self.link_count()],
        }
    }

    /// Pose every link for joint vector `q` (radians, [`HandModel::dofs`] order) into `state`.
    ///
    /// `q` is not clamped: limits are the caller's contract (the retargeter's QP keeps them).
    pub fn forward(&self, q: &[f64], state: &mut FkState) -> Result<(), Error> {
        if q.len() != self.dof() {
            return Err(Error::DofMismatch {
                expected: self.dof(),
                got: q.len(),
            });
        }
        if state.poses.len() != self.link_count() {
            *state = self.fk_state();
        }
        for joint in &self.joints {
            let parent = state.poses[joint.parent.0];
            let pose = match &joint.motion {
                JointMotion::Fixed => parent * joint.origin,
                JointMotion::Revolute {
                    axis,
                    dof,
                    multiplier,
                    offset_rad,
                    ..
                } => {
                    let angle = multiplier * q[*dof] + offset_rad;
                    let rotation = UnitQuaternion::from_axis_angle(axis, angle);
                    let mut pose = parent * joint.origin;
                    pose.rotation *= rotation;
                    pose
                }
            };
            state.poses[joint.child.0] = pose;
        }
        Ok(())
    }

    /// Convenience: a fresh [`FkState`] for `q`.
    pub fn forward_new(&self, q: &[f64]) -> Result<FkState, Error> {
        let mut state = self.fk_state();
        self.forward(q, &mut state)?;
        Ok(state)
    }
}
