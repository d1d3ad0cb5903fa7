//! Positional Jacobians of link origins with respect to the joint vector.
//!
//! For a link origin `p` (base frame) and each revolute joint `j` between the root and the
//! link, with world axis `a_j` and joint frame origin `o_j`, the column of the joint's degree
//! of freedom gains `multiplier_j · a_j × (p − o_j)` (metres per radian). Couplings are thus
//! folded into the columns of the independent variables.

use nalgebra::{Matrix3xX, Vector3};

use crate::error::Error;
use crate::forward_kinematics::FkState;
use crate::hand_model::{HandModel, JointMotion, LinkId};

impl HandModel {
    /// Write `∂p_link/∂q` (3 × dof, base frame, m/rad) into `out`, for the pose in `state`
    /// (which must come from [`HandModel::forward`] on this model). Allocates nothing.
    pub fn position_jacobian(
        &self,
        state: &FkState,
        link: LinkId,
        out: &mut Matrix3xX<f64>,
    ) -> Result<(), Error> {
        if out.ncols() != self.dof() {
            return Err(Error::JacobianShape {
                expected: self.dof(),
                got: out.ncols(),
            });
        }
        out.fill(0.0);
        let p = state.poses[link.0].translation.vector;
        for &ji in &self.chains[link.0] {
            let joint = &self.joints[ji];
            if let JointMotion::Revolute {
                axis,
                dof,
                multiplier,
                ..
            } = &joint.motion
            {
                let frame = &state.poses[joint.child.0];
                let a: Vector3<f64> = frame.rotation * axis.into_inner();
                let column = a.cross(&(p - frame.translation.vector)) * *multiplier;
                let mut target = out.column_mut(*dof);
                target += column;
            }
        }
        Ok(())
    }

    /// Whether degree of freedom `dof` moves `link` at all (it lies on the link's chain).
    pub fn moves(&self, dof: usize, link: LinkId) -> bool {
        self.chains[link.0].iter().any(|&ji| {
            matches!(self.joints[ji].motion, JointMotion::Revolute { dof: d, .. } if d == dof)
        })
    }
}
