//! One Apple Vision Pro hand update to the lab's keypoints and a wrist pose, in ROS axes.
//!
//! ## Frames
//!
//! ARKit's world is right-handed and **y-up**: x to the user's right, y up, z toward the user
//! (the headset looks along −z when the session starts). ROS (REP 103) is x forward, y left,
//! z up. The change of basis is the proper rotation
//!
//! ```text
//!          ⎡ 0  0 −1 ⎤                x_ros = −z_arkit   (forward)
//!     C =  ⎢−1  0  0 ⎥ ,  det C = +1:  y_ros = −x_arkit   (left = −right)
//!          ⎣ 0  1  0 ⎦                z_ros =  y_arkit   (up)
//! ```
//!
//! (`avp_stream` itself turns the world with `x' = x, y' = −z, z' = y`: z-up too, but with x to
//! the right; the extra quarter turn about z here makes x forward, as every other source of the
//! station is.)
//!
//! A hand update carries the wrist `W = [R_w | t_w]` in ARKit's world and each joint
//! `J_k = [R_k | t_k]` relative to the wrist (row-major; the last row, `0 0 0 1`, is not read).
//! Joint *k* in the world is `W J_k`, so its position is `p_k = R_w t_k + t_w`, and in ROS axes
//!
//! ```text
//! keypoint_k = C (R_w t_k + t_w)                               metres
//! wrist pose = (C t_w,  C R_w Cᵀ)                             position, rotation
//! ```
//!
//! `C R_w Cᵀ` re-expresses both the world and the hand's own axes in ROS's convention, so a
//! turn of the hand about the world's vertical is a turn about ROS's z. Before `R_w` is used it
//! must be a rotation: orthonormal to 1e-3 with determinant +1 (an untracked hand arrives as a
//! zero or scaled matrix and is refused as `wrist_not_rigid`).
//!
//! ## Joints and layouts
//!
//! The skeleton has 25 joints (27 from newer apps): 0 wrist; thumb 1–4 (knuckle, intermediate
//! base, intermediate tip, tip); index 5–9, middle 10–14, ring 15–19, little 20–24 (metacarpal,
//! knuckle, intermediate base, intermediate tip, tip); 25 forearm-wrist and 26 forearm-arm.
//! The lab's 22-point layout (docs/LAB_CONVENTIONS.md §1) takes the wrist, the thumb's four and each finger's
//! four without its metacarpal; its forearm point (0) is the forearm-arm joint when the app
//! sends it, else the wrist again (the ETH lab's convention). `lab21` leaves the forearm out.

use nalgebra::{Isometry3, Matrix3, Point3, Rotation3, Translation3, UnitQuaternion, Vector3};
use retarget::KeypointLayout;

use crate::ingress::avp_proto::{Hand as AvpHand, HandUpdate, Matrix4x4};
use crate::ingress::ingress_config::Hand;

/// Joints in a skeleton without the forearm.
pub const JOINTS_WITHOUT_FOREARM: usize = 25;

/// Joints in a skeleton with the forearm (forearm-wrist 25, forearm-arm 26).
pub const JOINTS_WITH_FOREARM: usize = 27;

/// The forearm-arm joint.
pub const FOREARM_ARM: usize = 26;

/// The skeleton joints of the 21 wrist-and-finger points, in the lab's order.
pub const LAB21_JOINTS: [usize; 21] = [
    0, 1, 2, 3, 4, 6, 7, 8, 9, 11, 12, 13, 14, 16, 17, 18, 19, 21, 22, 23, 24,
];

/// A position farther than this from the headset's world origin is not a hand, metres.
pub const MAX_POSITION_M: f64 = 100.0;

/// How far `R_w Rᵀ_w` may be from the identity (any entry) for `R_w` to count as a rotation.
pub const RIGID_TOLERANCE: f64 = 1e-3;

/// ARKit's axes to ROS's: `x_ros = −z`, `y_ros = −x`, `z_ros = y`.
pub fn arkit_to_ros() -> Matrix3<f64> {
    Matrix3::new(0.0, 0.0, -1.0, -1.0, 0.0, 0.0, 0.0, 1.0, 0.0)
}

/// An update's hand, ready to publish.
#[derive(Debug, Clone, PartialEq)]
pub struct AvpFrame {
    /// The keypoints in the layout's order, ROS axes, metres.
    pub keypoints: Vec<Point3<f64>>,
    /// The wrist pose in ROS axes.
    pub wrist: Isometry3<f64>,
    /// Whether the app sent the forearm joints (27) or not (25; the wrist stands in for the
    /// forearm point).
    pub has_forearm: bool,
}

/// Why an update was not published. Each kind is counted under [`UpdateError::kind`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UpdateError {
    /// The bytes are not a `HandUpdate`.
    #[error("not a HandUpdate: {reason}")]
    Undecodable {
        /// The decoder's message.
        reason: String,
    },
    /// The app's reply to a latency benchmark.
    #[error("a latency-benchmark reply (head m00 = 777), not hand data")]
    BenchmarkReply,
    /// The selected hand, its wrist or its skeleton is missing.
    #[error("no {hand} hand (or no wrist matrix or skeleton) in the update")]
    NoHand {
        /// `right` or `left`.
        hand: &'static str,
    },
    /// A skeleton of another size than 25 or 27 joints.
    #[error("{count} joints in the skeleton (expected 25, or 27 with the forearm)")]
    JointCount {
        /// The count received.
        count: usize,
    },
    /// A NaN or infinite entry, or a position beyond [`MAX_POSITION_M`].
    #[error("{what} is not finite or beyond 100 m")]
    NonFinite {
        /// `wrist matrix` or `joint N`.
        what: String,
    },
    /// The wrist matrix's rotation part is not a rotation.
    #[error("the wrist matrix is not a rigid transform (rotation off by {error:.2e})")]
    WristNotRigid {
        /// The largest entry of `R Rᵀ − I`, or the determinant's distance from 1.
        error: f64,
    },
}

impl UpdateError {
    /// The counter this refusal goes under.
    pub fn kind(&self) -> &'static str {
        match self {
            UpdateError::Undecodable { .. } => "undecodable",
            UpdateError::BenchmarkReply => "benchmark_reply",
            UpdateError::NoHand { .. } => "no_hand",
            UpdateError::JointCount { .. } => "joint_count",
            UpdateError::NonFinite { .. } => "non_finite",
            UpdateError::WristNotRigid { .. } => "wrist_not_rigid",
        }
    }
}

/// The selected hand of `update` as the lab's keypoints and a wrist pose, or why not.
pub fn convert_update(
    update: &HandUpdate,
    hand: Hand,
    layout: KeypointLayout,
) -> Result<AvpFrame, UpdateError> {
    if update.is_benchmark_reply() {
        return Err(UpdateError::BenchmarkReply);
    }
    let (wrist, joints) = select_hand(update, hand)?;
    let has_forearm = match joints.len() {
        JOINTS_WITHOUT_FOREARM => false,
        JOINTS_WITH_FOREARM => true,
        count => return Err(UpdateError::JointCount { count }),
    };
    let (rotation, translation) = rigid(wrist)?;
    let c = arkit_to_ros();
    let to_ros = |k: usize| -> Result<Point3<f64>, UpdateError> {
        let local = translation_of(&joints[k], || format!("joint {k}"))?;
        Ok(Point3::from(c * (rotation * local + translation)))
    };
    let mut keypoints = Vec::with_capacity(22);
    if layout == KeypointLayout::Lab22 {
        keypoints.push(to_ros(if has_forearm { FOREARM_ARM } else { 0 })?);
    }
    for k in LAB21_JOINTS {
        keypoints.push(to_ros(k)?);
    }
    let turned = Rotation3::from_matrix_unchecked(c * rotation * c.transpose());
    // Within the rigidity tolerance, not exactly orthonormal: normalise the quaternion.
    let quaternion =
        UnitQuaternion::new_normalize(*UnitQuaternion::from_rotation_matrix(&turned).quaternion());
    let wrist = Isometry3::from_parts(Translation3::from(c * translation), quaternion);
    Ok(AvpFrame {
        keypoints,
        wrist,
        has_forearm,
    })
}

/// The selected hand's wrist matrix and joints.
fn select_hand(update: &HandUpdate, hand: Hand) -> Result<(&Matrix4x4, &[Matrix4x4]), UpdateError> {
    let chosen: Option<&AvpHand> = match hand {
        Hand::Right => update.right_hand.as_ref(),
        Hand::Left => update.left_hand.as_ref(),
    };
    let missing = || UpdateError::NoHand {
        hand: hand.bone_prefix(),
    };
    let chosen = chosen.ok_or_else(missing)?;
    let wrist = chosen.wrist_matrix.as_ref().ok_or_else(missing)?;
    let joints = chosen.skeleton.as_ref().ok_or_else(missing)?;
    Ok((wrist, &joints.joint_matrices))
}

/// A matrix's translation column, checked finite and within range.
fn translation_of(
    m: &Matrix4x4,
    what: impl FnOnce() -> String,
) -> Result<Vector3<f64>, UpdateError> {
    let t = Vector3::new(f64::from(m.m03), f64::from(m.m13), f64::from(m.m23));
    if t.iter().all(|v| v.is_finite() && v.abs() <= MAX_POSITION_M) {
        Ok(t)
    } else {
        Err(UpdateError::NonFinite { what: what() })
    }
}

/// The wrist matrix's rotation (checked to be one) and translation.
fn rigid(m: &Matrix4x4) -> Result<(Matrix3<f64>, Vector3<f64>), UpdateError> {
    let rows = m.rows();
    let r = Matrix3::from_fn(|i, j| f64::from(rows[i][j]));
    if !r.iter().all(|v| v.is_finite()) {
        return Err(UpdateError::NonFinite {
            what: "wrist matrix".into(),
        });
    }
    let translation = translation_of(m, || "wrist matrix".into())?;
    let off_identity = (r * r.transpose() - Matrix3::identity()).amax();
    let error = off_identity.max((r.determinant() - 1.0).abs());
    if error > RIGID_TOLERANCE {
        return Err(UpdateError::WristNotRigid { error });
    }
    Ok((r, translation))
}

#[cfg(test)]
#[path = "avp_frame_tests.rs"]
mod tests;
