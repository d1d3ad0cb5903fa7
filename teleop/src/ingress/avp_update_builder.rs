//! Apple Vision Pro hand updates built from a hand in ROS axes: the inverse of
//! [`super::avp_frame`], for tests, benchmarks and stand-in headsets.
//!
//! Given the lab's 22 points `q` (ROS axes) and a wrist pose `(t, R)` in ROS axes, the headset
//! would have sent `W = [CᵀRC | Cᵀt]` and each joint relative to it, `t_k = (CᵀRC)ᵀ (Cᵀq − Cᵀt)`;
//! the metacarpals the lab drops sit halfway between the wrist point and the knuckle, and the
//! joints' own rotations (never read) are the identity.

use nalgebra::{Isometry3, Matrix3, Point3, Vector3};

use crate::ingress::avp_frame::{
    JOINTS_WITH_FOREARM, JOINTS_WITHOUT_FOREARM, LAB21_JOINTS, arkit_to_ros,
};
use crate::ingress::avp_proto::{Hand as AvpHand, HandUpdate, Matrix4x4, Skeleton};
use crate::ingress::ingress_config::Hand;

/// A transform from a rotation and a translation, to `f32` rows.
pub fn matrix(rotation: &Matrix3<f64>, translation: &Vector3<f64>) -> Matrix4x4 {
    let mut rows = [[0.0f32; 4]; 4];
    for (i, row) in rows.iter_mut().take(3).enumerate() {
        for (j, v) in row.iter_mut().take(3).enumerate() {
            *v = rotation[(i, j)] as f32;
        }
        row[3] = translation[i] as f32;
    }
    rows[3][3] = 1.0;
    Matrix4x4::from_rows(rows)
}

/// The update a headset would send for `lab22` (the lab's 22 points, ROS axes, metres) with
/// the wrist at `wrist` (ROS axes): 27 joints with `with_forearm` (forearm-arm at point 0,
/// forearm-wrist at the wrist), else 25; `hand` says which of the update's hands it is.
pub fn hand_update(
    lab22: &[Point3<f64>; 22],
    wrist: &Isometry3<f64>,
    with_forearm: bool,
    hand: Hand,
) -> HandUpdate {
    let c = arkit_to_ros();
    let r = c.transpose() * wrist.rotation.to_rotation_matrix().matrix() * c;
    let t = c.transpose() * wrist.translation.vector;
    let local = |q: &Point3<f64>| r.transpose() * (c.transpose() * q.coords - t);
    let count = if with_forearm {
        JOINTS_WITH_FOREARM
    } else {
        JOINTS_WITHOUT_FOREARM
    };
    let mut joints = vec![Vector3::zeros(); count];
    for (point, &joint) in LAB21_JOINTS.iter().enumerate() {
        joints[joint] = local(&lab22[point + 1]);
    }
    for metacarpal in [5, 10, 15, 20] {
        joints[metacarpal] = 0.5 * (joints[0] + joints[metacarpal + 1]);
    }
    if with_forearm {
        joints[25] = joints[0];
        joints[26] = local(&lab22[0]);
    }
    let skeleton = Skeleton {
        joint_matrices: joints
            .iter()
            .map(|p| matrix(&Matrix3::identity(), p))
            .collect(),
    };
    let side = Some(AvpHand {
        wrist_matrix: Some(matrix(&r, &t)),
        skeleton: Some(skeleton),
    });
    let head = Some(matrix(&Matrix3::identity(), &Vector3::new(0.0, 1.6, 0.0)));
    match hand {
        Hand::Right => HandUpdate {
            right_hand: side,
            left_hand: None,
            head,
        },
        Hand::Left => HandUpdate {
            left_hand: side,
            right_hand: None,
            head,
        },
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Translation3, UnitQuaternion};
    use retarget::KeypointLayout;

    use super::*;
    use crate::ingress::avp_frame::convert_update;

    #[test]
    fn building_then_converting_gives_the_hand_back() {
        let lab22: [Point3<f64>; 22] = std::array::from_fn(|k| {
            let k = k as f64;
            Point3::new(
                0.3 + 0.01 * k,
                -0.05 + 0.003 * k * k % 0.07,
                1.1 - 0.004 * k,
            )
        });
        let wrist = Isometry3::from_parts(
            Translation3::new(0.31, -0.04, 1.09),
            UnitQuaternion::from_euler_angles(0.3, -0.5, 1.2),
        );
        for with_forearm in [true, false] {
            let update = hand_update(&lab22, &wrist, with_forearm, Hand::Right);
            let frame = convert_update(&update, Hand::Right, KeypointLayout::Lab22).unwrap();
            let skip = usize::from(!with_forearm);
            for (k, (got, want)) in frame.keypoints.iter().zip(&lab22).enumerate().skip(skip) {
                assert!(
                    (got - want).norm() < 2e-6,
                    "{with_forearm} point {k}: {got} vs {want}"
                );
            }
            assert!(frame.wrist.rotation.angle_to(&wrist.rotation) < 1e-6);
            assert!((frame.wrist.translation.vector - wrist.translation.vector).norm() < 1e-6);
        }
    }
}
