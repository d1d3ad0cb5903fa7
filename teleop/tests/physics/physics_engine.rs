//! The physics engine on a scene written here: a one-joint "hand" under a mocap mount and a
//! free box on the floor (real MuJoCo; only with the `physics` feature).

use nalgebra::{Isometry3, Vector3};
use simulation::progress::Reading;
use teleop::physics::engine::{HandBinding, PhysicsEngine};

const SCENE: &str = r#"<mujoco>
  <compiler angle="radian" autolimits="true"/>
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="mount" mocap="true" pos="0 0 0.5">
      <body name="link">
        <joint name="j0" type="hinge" axis="0 1 0" range="-1 1" damping="0.05" armature="0.001"/>
        <geom type="capsule" fromto="0 0 0 0.1 0 0" size="0.01" mass="0.02"/>
      </body>
    </body>
    <body name="box" pos="0.3 0 0.05">
      <freejoint name="box_free"/>
      <geom type="box" size="0.05 0.05 0.05" mass="0.1"/>
    </body>
  </worldbody>
  <actuator><position name="a0" joint="j0" kp="2" ctrlrange="-1 1"/></actuator>
</mujoco>"#;

fn binding() -> HandBinding {
    HandBinding {
        dof_joints: vec!["j0".into()],
        dof_actuators: vec!["a0".into()],
        mount_body: "mount".into(),
        max_speed_rad_s: 4.0,
        zero_offsets_rad: Vec::new(),
    }
}

/// A manufacturer's model whose hinge puts the URDF's zero at `qpos` = 0.3 (`ref`), its ranges
/// in `qpos`.
#[test]
fn urdf_angles_go_in_and_come_out_across_a_joint_zero_offset() {
    let scene = SCENE
        .replace(r#"ctrlrange="-1 1""#, r#"ctrlrange="-0.7 1.3""#)
        .replace(
            r#"axis="0 1 0" range="-1 1""#,
            r#"axis="0 1 0" range="-0.7 1.3" ref="0.3""#,
        );
    assert_eq!(scene.matches("ref=").count(), 1);
    let binding = HandBinding {
        zero_offsets_rad: vec![0.3],
        ..binding()
    };
    let mut engine = PhysicsEngine::from_xml_str(&scene, "offset scene", &binding).unwrap();
    // At MuJoCo's initial state (qpos = ref) the URDF angle is 0.
    assert!(engine.hand_positions()[0].abs() < 1e-12);
    assert!(engine.hand_targets()[0].abs() < 1e-12);
    engine.set_hand_targets(&[0.5]).unwrap();
    engine.advance(1.0);
    let angle = engine.hand_positions()[0];
    assert!((angle - 0.5).abs() < 0.02, "{angle}");
    assert!((engine.joint_position("j0").unwrap() - 0.8).abs() < 0.02);
    // The control range, in URDF angles, is [-1, 1]: 1.2 is clamped to 1.
    engine.set_hand_targets(&[1.2]).unwrap();
    assert!((engine.hand_targets()[0] - 1.0).abs() < 1e-12);
    engine.set_hand_positions(&[-0.4]).unwrap();
    assert!((engine.joint_position("j0").unwrap() + 0.1).abs() < 1e-12);
    assert!((engine.hand_positions()[0] + 0.4).abs() < 1e-12);
}

#[test]
fn the_joint_follows_its_target_at_the_speed_limit() {
    let mut engine = PhysicsEngine::from_xml_str(SCENE, "test scene", &binding()).unwrap();
    engine.set_hand_targets(&[0.8]).unwrap();
    engine.advance(0.1);
    // After 0.1 s at 4 rad/s the control has slewed 0.4 rad: the joint cannot be at 0.8 yet.
    assert!(
        engine.hand_positions()[0] < 0.45,
        "{:?}",
        engine.hand_positions()
    );
    engine.advance(1.0);
    assert!(
        (engine.hand_positions()[0] - 0.8).abs() < 0.03,
        "{:?}",
        engine.hand_positions()
    );
    assert!(engine.set_hand_targets(&[f64::NAN]).is_err());
    assert!(engine.set_hand_targets(&[0.1, 0.2]).is_err());
}

#[test]
fn the_mount_moves_the_hand_and_objects_are_read() {
    let mut engine = PhysicsEngine::from_xml_str(SCENE, "test scene", &binding()).unwrap();
    engine.set_mount_pose(&Isometry3::translation(0.1, 0.2, 0.3));
    engine.advance(0.01);
    let link = engine.body_pose("link").unwrap();
    assert!((link.translation.vector - Vector3::new(0.1, 0.2, 0.3)).norm() < 1e-9);
    engine.advance(0.5);
    let Some(Reading::Body { position_m, .. }) = engine.reading("box_free") else {
        panic!("no body reading")
    };
    assert!((position_m[2] - 0.05).abs() < 0.005, "{position_m:?}");
    engine
        .set_joint("box_free", &[0.3, 0.0, 0.4, 1.0, 0.0, 0.0, 0.0])
        .unwrap();
    assert!(
        matches!(engine.reading("box_free"), Some(Reading::Body { position_m, .. }) if position_m[2] == 0.4)
    );
    assert!(matches!(engine.reading("j0"), Some(Reading::Joint(_))));
    assert!(engine.reading("nope").is_none());
}

#[test]
fn missing_names_are_listed() {
    let mut b = binding();
    b.dof_joints.push("j9".into());
    b.dof_actuators.push("a9".into());
    let error = PhysicsEngine::from_xml_str(SCENE, "test scene", &b)
        .err()
        .unwrap();
    assert!(error.to_string().contains("j9"), "{error}");
    let error = PhysicsEngine::from_xml_str("<mujoco><bad", "broken.xml", &binding())
        .err()
        .unwrap();
    assert!(error.to_string().contains("broken.xml"), "{error}");
}
