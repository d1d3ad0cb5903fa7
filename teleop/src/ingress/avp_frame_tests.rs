//! The frame maths against values worked out by hand (see the module docs).

use super::*;
use crate::ingress::avp_proto::Skeleton;

const EPS: f64 = 1e-6;

fn translation(x: f32, y: f32, z: f32) -> Matrix4x4 {
    Matrix4x4::from_rows([
        [1.0, 0.0, 0.0, x],
        [0.0, 1.0, 0.0, y],
        [0.0, 0.0, 1.0, z],
        [0.0, 0.0, 0.0, 1.0],
    ])
}

/// Joint k sits at (k mm, 0, 0) from the wrist.
fn skeleton(count: usize) -> Vec<Matrix4x4> {
    (0..count)
        .map(|k| translation(k as f32 * 0.001, 0.0, 0.0))
        .collect()
}

fn update(wrist: Matrix4x4, joints: Vec<Matrix4x4>) -> HandUpdate {
    HandUpdate {
        right_hand: Some(AvpHand {
            wrist_matrix: Some(wrist),
            skeleton: Some(Skeleton {
                joint_matrices: joints,
            }),
        }),
        ..HandUpdate::default()
    }
}

fn close(a: &Point3<f64>, b: [f64; 3]) -> bool {
    (a.coords - Vector3::from(b)).amax() < EPS
}

#[test]
fn arkit_axes_map_to_ros_axes() {
    let c = arkit_to_ros();
    // Forward (−z) is ROS +x, right (+x) is ROS −y, up (+y) is ROS +z.
    assert_eq!(c * Vector3::new(0.0, 0.0, -1.0), Vector3::x());
    assert_eq!(c * Vector3::new(1.0, 0.0, 0.0), -Vector3::y());
    assert_eq!(c * Vector3::new(0.0, 1.0, 0.0), Vector3::z());
    assert!((c.determinant() - 1.0).abs() < 1e-15);
}

#[test]
fn a_translated_wrist_and_joint_worked_by_hand() {
    // Wrist at (0.1, 1.2, −0.4) in ARKit, not turned; joint 4 (thumb tip) at (4 mm, 0, 0)
    // from it, so at (0.104, 1.2, −0.4) in the world: ROS (0.4, −0.104, 1.2).
    let frame = convert_update(
        &update(translation(0.1, 1.2, -0.4), skeleton(25)),
        Hand::Right,
        KeypointLayout::Lab21,
    )
    .unwrap();
    assert_eq!(frame.keypoints.len(), 21);
    assert!(
        close(&frame.keypoints[4], [0.4, -0.104, 1.2]),
        "{:?}",
        frame.keypoints[4]
    );
    assert!(close(
        &frame.wrist.translation.vector.into(),
        [0.4, -0.1, 1.2]
    ));
    assert!(frame.wrist.rotation.angle() < EPS);
}

#[test]
fn a_wrist_turned_about_up_turns_about_ros_z() {
    // 90° about ARKit's y (up): x → −z (right becomes forward). R = [[0,0,1],[0,1,0],[−1,0,0]].
    let wrist = Matrix4x4::from_rows([
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]);
    let frame = convert_update(
        &update(wrist, skeleton(25)),
        Hand::Right,
        KeypointLayout::Lab21,
    )
    .unwrap();
    // Joint 9 (index tip) at (9 mm, 0, 0) local: world (0, 0, −0.009), forward: ROS (0.009, 0, 0).
    assert!(
        close(&frame.keypoints[8], [0.009, 0.0, 0.0]),
        "{:?}",
        frame.keypoints[8]
    );
    // In ROS the turn takes right (−y) to forward (+x): +90° about z.
    let q = frame.wrist.rotation;
    let half = std::f64::consts::FRAC_PI_4;
    assert!(
        (q.w - half.cos()).abs() < EPS && (q.k - half.sin()).abs() < EPS,
        "{q:?}"
    );
    assert!(q.i.abs() < EPS && q.j.abs() < EPS);
}

#[test]
fn the_lab_layouts_take_the_documented_joints() {
    let c = |k: usize| [0.0, -(k as f64) * 0.001, 0.0];
    for (count, forearm) in [(25, 0), (27, FOREARM_ARM)] {
        let frame = convert_update(
            &update(translation(0.0, 0.0, 0.0), skeleton(count)),
            Hand::Right,
            KeypointLayout::Lab22,
        )
        .unwrap();
        assert_eq!(frame.keypoints.len(), 22);
        assert_eq!(frame.has_forearm, count == 27);
        assert!(close(&frame.keypoints[0], c(forearm)), "{count}: forearm");
        // Wrist, thumb knuckle..tip, then index knuckle (6, not the metacarpal 5) ... little tip.
        for (point, joint) in [
            (1, 0),
            (2, 1),
            (5, 4),
            (6, 6),
            (9, 9),
            (10, 11),
            (14, 16),
            (18, 21),
            (21, 24),
        ] {
            assert!(
                close(&frame.keypoints[point], c(joint)),
                "{count}: point {point}"
            );
        }
    }
}

#[test]
fn the_left_hand_is_read_when_asked() {
    let mut u = update(translation(0.0, 0.0, 0.0), skeleton(25));
    u.left_hand = u.right_hand.take();
    assert_eq!(
        convert_update(&u, Hand::Right, KeypointLayout::Lab21)
            .unwrap_err()
            .kind(),
        "no_hand"
    );
    assert!(convert_update(&u, Hand::Left, KeypointLayout::Lab21).is_ok());
}

#[test]
fn broken_updates_are_refused_by_kind() {
    let ok = || update(translation(0.0, 1.0, 0.0), skeleton(27));
    let mut zero = ok();
    zero.right_hand.as_mut().unwrap().wrist_matrix = Some(Matrix4x4::default());
    let mut mirrored = ok();
    mirrored
        .right_hand
        .as_mut()
        .unwrap()
        .wrist_matrix
        .as_mut()
        .unwrap()
        .m00 = -1.0;
    let mut nan = ok();
    nan.right_hand
        .as_mut()
        .unwrap()
        .skeleton
        .as_mut()
        .unwrap()
        .joint_matrices[7]
        .m13 = f32::NAN;
    let mut far = ok();
    far.right_hand
        .as_mut()
        .unwrap()
        .wrist_matrix
        .as_mut()
        .unwrap()
        .m03 = 1e6;
    let mut short = ok();
    short
        .right_hand
        .as_mut()
        .unwrap()
        .skeleton
        .as_mut()
        .unwrap()
        .joint_matrices
        .truncate(24);
    let mut benchmark = ok();
    benchmark.head = Some(Matrix4x4 {
        m00: 777.0,
        ..Matrix4x4::default()
    });
    let no_skeleton = HandUpdate {
        right_hand: Some(AvpHand {
            wrist_matrix: Some(translation(0.0, 0.0, 0.0)),
            skeleton: None,
        }),
        ..HandUpdate::default()
    };
    for (u, kind) in [
        (zero, "wrist_not_rigid"),
        (mirrored, "wrist_not_rigid"),
        (nan, "non_finite"),
        (far, "non_finite"),
        (short, "joint_count"),
        (benchmark, "benchmark_reply"),
        (no_skeleton, "no_hand"),
        (HandUpdate::default(), "no_hand"),
    ] {
        let e = convert_update(&u, Hand::Right, KeypointLayout::Lab22).unwrap_err();
        assert_eq!(e.kind(), kind, "{e}");
    }
}
