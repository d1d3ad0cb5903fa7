//! Unit tests of the clutch and the per-step pipeline (property tests are in
//! `station/tests/suite/arm_properties.rs`).

use std::f64::consts::FRAC_PI_2;

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};

use super::*;
use crate::arm::{OrientationPolicy, RotationConfig};

fn pose(p: [f64; 3], rpy: [f64; 3]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(p[0], p[1], p[2]),
        UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    )
}

fn moved(g: &Isometry3<f64>, dp: [f64; 3]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::from(g.translation.vector + Vector3::from(dp)),
        g.rotation,
    )
}

fn mapper(constraint: Constraint) -> ArmMapper {
    ArmMapper::new(ArmConfig {
        constraint,
        ..ArmConfig::default()
    })
    .unwrap()
}

const GLOVE: [f64; 3] = [0.1, 1.2, 0.3];
const ROBOT: [f64; 3] = [0.5, 0.0, 0.4];

fn engaged(constraint: Constraint) -> (ArmMapper, Isometry3<f64>, Isometry3<f64>) {
    let mut m = mapper(constraint);
    let glove = pose(GLOVE, [0.3, -0.2, 1.0]);
    let robot = pose(ROBOT, [3.0, 0.1, -0.2]);
    m.engage(glove, robot).unwrap();
    (m, glove, robot)
}

fn distance(a: &Isometry3<f64>, b: &Isometry3<f64>) -> (f64, f64) {
    (
        (a.translation.vector - b.translation.vector).norm(),
        a.rotation.angle_to(&b.rotation),
    )
}

#[test]
fn disengaged_steps_produce_nothing() {
    let mut m = mapper(Constraint::Free);
    assert!(!m.is_engaged());
    assert_eq!(m.step(pose(GLOVE, [0.0; 3])).unwrap(), None);
    assert!(m.last_command().is_none());
}

#[test]
fn engaging_never_moves_the_robot() {
    for c in [
        Constraint::Fixed,
        Constraint::VerticalAxis,
        Constraint::HorizontalAxis,
        Constraint::Free,
    ] {
        let (mut m, glove, robot) = engaged(c);
        let command = m.step(glove).unwrap().unwrap();
        let (dp, dr) = distance(&command.target, &robot);
        assert!(dp < 1e-15 && dr < 1e-12, "{c:?}: {dp} {dr}");
        assert!(!command.is_limited() && !command.constrained, "{command:?}");
    }
}

#[test]
fn free_follows_scaled_translation_in_the_base_frame() {
    let mut m = ArmMapper::new(ArmConfig {
        constraint: Constraint::Free,
        translation_scale: 0.5,
        glove_to_base: RotationConfig {
            rpy_rad: Some([FRAC_PI_2, 0.0, 0.0]),
            quaternion_xyzw: None,
        },
        ..ArmConfig::default()
    })
    .unwrap();
    let glove = pose(GLOVE, [0.0; 3]);
    let robot = pose(ROBOT, [0.0; 3]);
    m.engage(glove, robot).unwrap();
    // 1 cm up the tracker's y is 5 mm up the base's z.
    let command = m.step(moved(&glove, [0.0, 0.01, 0.0])).unwrap().unwrap();
    let expected = Vector3::from(ROBOT) + Vector3::new(0.0, 0.0, 0.005);
    assert!((command.target.translation.vector - expected).norm() < 1e-15);
    assert!(!command.constrained && !command.is_limited());
}

#[test]
fn fixed_holds_the_latched_pose() {
    let (mut m, glove, robot) = engaged(Constraint::Fixed);
    let turned = Isometry3::from_parts(
        Translation3::from(glove.translation.vector + Vector3::new(0.05, -0.02, 0.01)),
        UnitQuaternion::from_euler_angles(0.1, 0.2, 0.3) * glove.rotation,
    );
    let command = m.step(turned).unwrap().unwrap();
    let (dp, dr) = distance(&command.target, &robot);
    assert!(dp == 0.0 && dr < 1e-12);
    assert!(command.constrained);
}

#[test]
fn vertical_axis_keeps_only_the_vertical_component() {
    let (mut m, glove, robot) = engaged(Constraint::VerticalAxis);
    let command = m
        .step(moved(&glove, [0.004, 0.003, 0.006]))
        .unwrap()
        .unwrap();
    let expected = robot.translation.vector + Vector3::new(0.0, 0.0, 0.006);
    assert!((command.target.translation.vector - expected).norm() < 1e-15);
    assert!(command.target.rotation.angle_to(&robot.rotation) < 1e-12);
    assert!(command.constrained && !command.is_limited());
}

#[test]
fn twist_policy_turns_about_the_vertical_only() {
    let mut m = ArmMapper::new(ArmConfig {
        constraint: Constraint::VerticalAxis,
        orientation: OrientationPolicy::TwistAboutAxis,
        ..ArmConfig::default()
    })
    .unwrap();
    let glove = pose(GLOVE, [0.0; 3]);
    let robot = pose(ROBOT, [3.0, 0.0, 0.0]);
    m.engage(glove, robot).unwrap();
    // 0.015 rad yaw plus 0.015 rad roll: only the yaw passes.
    let turn = UnitQuaternion::from_euler_angles(0.015, 0.0, 0.015);
    let command = m
        .step(Isometry3::from_parts(
            glove.translation,
            turn * glove.rotation,
        ))
        .unwrap()
        .unwrap();
    let delta = command.target.rotation * robot.rotation.inverse();
    assert!((delta * Vector3::z() - Vector3::z()).norm() < 1e-12);
    assert!((delta.angle() - 0.015).abs() < 1e-4, "{}", delta.angle());
    assert!(command.constrained);
}

#[test]
fn a_glove_jump_becomes_a_bounded_ramp() {
    let (mut m, glove, robot) = engaged(Constraint::Free);
    let jumped = moved(&glove, [0.0, 0.06, 0.08]); // 0.1 m away
    let mut previous = robot.translation.vector;
    let mut capped_steps = 0;
    for _ in 0..12 {
        let command = m.step(jumped).unwrap().unwrap();
        let p = command.target.translation.vector;
        assert!((p - previous).norm() <= 0.01 + 1e-15);
        // Straight toward the goal: the step is parallel to (0, 0.6, 0.8).
        assert!((p - previous).cross(&Vector3::new(0.0, 0.6, 0.8)).norm() < 1e-12);
        capped_steps += usize::from(command.translation_capped);
        previous = p;
    }
    assert!((9..=10).contains(&capped_steps), "{capped_steps}");
    let goal = robot.translation.vector + Vector3::new(0.0, 0.06, 0.08);
    assert!((previous - goal).norm() < 1e-12);
}

#[test]
fn a_wrist_flip_is_a_bounded_rotation_ramp() {
    let (mut m, glove, robot) = engaged(Constraint::Free);
    let flip = UnitQuaternion::from_scaled_axis(Vector3::new(0.0, 1.0, 0.0) * 1.0);
    let flipped = Isometry3::from_parts(glove.translation, flip * glove.rotation);
    let mut previous = robot.rotation;
    for i in 0..60 {
        let command = m.step(flipped).unwrap().unwrap();
        let r = command.target.rotation;
        assert!(previous.angle_to(&r) <= 0.02 + 1e-12);
        assert_eq!(command.rotation_capped, i < 49, "step {i}");
        previous = r;
    }
    assert!(previous.angle_to(&(flip * robot.rotation)) < 1e-9);
}

#[test]
fn workspace_clamps_free_motion_per_coordinate() {
    let (mut m, glove, _) = engaged(Constraint::Free);
    let far = moved(&glove, [0.0, 0.0, 5.0]);
    let mut last = None;
    for _ in 0..200 {
        last = m.step(far).unwrap();
    }
    let command = last.unwrap();
    assert!(command.clamped_to_workspace);
    assert_eq!(command.target.translation.vector.z, 0.75);
    assert_eq!(command.target.translation.vector.x, ROBOT[0]);
}

#[test]
fn workspace_clamps_along_a_tilted_axis() {
    let mut m = ArmMapper::new(ArmConfig {
        constraint: Constraint::HorizontalAxis,
        horizontal_axis: [0.6, 0.8, 0.0],
        max_translation_step_m: 0.1,
        ..ArmConfig::default()
    })
    .unwrap();
    let glove = pose(GLOVE, [0.0; 3]);
    let robot = pose(ROBOT, [3.0, 0.0, 0.0]);
    m.engage(glove, robot).unwrap();
    let mut command = None;
    for _ in 0..20 {
        command = m.step(moved(&glove, [3.0, 4.0, 0.0])).unwrap();
    }
    let command = command.unwrap();
    let p = command.target.translation.vector;
    assert!(command.clamped_to_workspace);
    // On the line through ROBOT along (0.6, 0.8, 0), where it leaves the box: the x = 0.75
    // face (t = 0.25 / 0.6), reached before the y = 0.45 face (t = 0.45 / 0.8).
    let offset = p - Vector3::from(ROBOT);
    assert!(offset.cross(&Vector3::new(0.6, 0.8, 0.0)).norm() < 1e-12);
    assert!(
        (p - Vector3::new(0.75, 1.0 / 3.0, 0.4)).norm() < 1e-12,
        "{p}"
    );
}

#[test]
fn engage_outside_the_box_is_refused_and_changes_nothing() {
    let (mut m, glove, robot) = engaged(Constraint::Free);
    let e = m
        .engage(glove, pose([0.5, 0.0, 0.9], [0.0; 3]))
        .unwrap_err();
    assert!(
        matches!(e, ArmRefusal::OutsideWorkspace { axis: "z", .. }),
        "{e}"
    );
    assert_eq!(m.latched().unwrap().1, robot);
}

#[test]
fn an_invalid_glove_pose_is_rejected_and_changes_nothing() {
    let (mut m, glove, _) = engaged(Constraint::Free);
    let first = m.step(moved(&glove, [0.0, 0.0, 0.03])).unwrap().unwrap();
    let nan = moved(&glove, [f64::NAN, 0.0, 0.0]);
    assert!(matches!(
        m.step(nan),
        Err(ArmRefusal::NonFinitePose {
            pose: PoseRole::GloveWrist,
            ..
        })
    ));
    let garbled = Isometry3::from_parts(
        glove.translation,
        UnitQuaternion::new_unchecked(Quaternion::new(0.0, 0.0, 0.0, 0.0)),
    );
    assert!(matches!(
        m.step(garbled),
        Err(ArmRefusal::NonUnitQuaternion { .. })
    ));
    assert_eq!(m.last_command(), Some(&first));
    // The ramp continues from the last good command, not from the rejected input.
    let next = m.step(moved(&glove, [0.0, 0.0, 0.03])).unwrap().unwrap();
    let dz = next.target.translation.vector.z - first.target.translation.vector.z;
    assert!((dz - 0.01).abs() < 1e-15, "{dz}");
}

#[test]
fn clutching_repositions_the_hand_without_moving_the_robot() {
    let (mut m, glove, _) = engaged(Constraint::Free);
    let held = m.step(moved(&glove, [0.0, 0.005, 0.0])).unwrap().unwrap();
    m.disengage();
    let elsewhere = moved(&glove, [0.3, -0.2, 0.1]);
    assert_eq!(m.step(elsewhere).unwrap(), None);
    assert_eq!(m.last_command(), Some(&held));
    m.engage(elsewhere, held.target).unwrap();
    let after = m.step(elsewhere).unwrap().unwrap();
    let (dp, dr) = distance(&after.target, &held.target);
    assert!(dp < 1e-15 && dr < 1e-12);
    // Motion after re-engage is relative to the new latch.
    let up = m
        .step(moved(&elsewhere, [0.0, 0.0, 0.004]))
        .unwrap()
        .unwrap();
    let dz = up.target.translation.vector - held.target.translation.vector;
    assert!((dz - Vector3::new(0.0, 0.0, 0.004)).norm() < 1e-15);
}

#[test]
fn constraint_changes_only_while_disengaged() {
    let (mut m, _, _) = engaged(Constraint::Free);
    assert_eq!(m.set_constraint(Constraint::Free), Ok(()));
    assert_eq!(
        m.set_constraint(Constraint::Fixed),
        Err(ArmRefusal::ConstraintChangeWhileEngaged)
    );
    m.disengage();
    m.set_constraint(Constraint::HorizontalAxis).unwrap();
    assert_eq!(m.constraint(), Constraint::HorizontalAxis);
    assert_eq!(m.config().constraint, Constraint::HorizontalAxis);
}

#[test]
fn engage_at_start_pose_uses_the_configured_pose() {
    let mut m = mapper(Constraint::Free);
    let glove = pose(GLOVE, [0.0; 3]);
    m.engage_at_start_pose(glove).unwrap();
    let command = m.step(glove).unwrap().unwrap();
    assert_eq!(command.position_m(), [0.45, 0.0, 0.40]);
    let q = command.quaternion_xyzw();
    assert!((q[0].abs() - 1.0).abs() < 1e-12, "{q:?}");
}

#[test]
fn an_invalid_config_is_refused() {
    let e = ArmMapper::new(ArmConfig {
        max_translation_step_m: 0.0,
        ..ArmConfig::default()
    })
    .unwrap_err();
    assert!(e.to_string().contains("max_translation_step_m"), "{e}");
}
