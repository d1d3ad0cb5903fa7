//! Property tests of the arm mapping (`teleop::arm`): over random configurations (constraint,
//! axes, scale, tracker-to-base rotation, box, caps, orientation policy), latched poses and
//! glove trajectories (small moves, jumps, wrist flips), every command is finite with a unit
//! quaternion, inside the workspace box, within the step caps of the previous command, on the
//! constraint axis; `fixed` stays fixed; `free` follows the glove exactly within the caps;
//! clutching does not move the robot; rejected inputs change nothing.

use std::f64::consts::PI;

use nalgebra::{Isometry3, Quaternion, Translation3, Unit, UnitQuaternion, Vector3};
use proptest::prelude::*;
use station::arm::{
    ArmCommand, ArmConfig, ArmMapper, Constraint, OrientationPolicy, RotationConfig, StartPose,
};

/// Tolerance of "on the axis line" (metres): the constraint's own rounding, no more.
const ON_AXIS_M: f64 = 1e-9;
/// Rounding allowance on the step caps.
const CAP_SLACK_M: f64 = 1e-12;
const CAP_SLACK_RAD: f64 = 1e-9;

fn unit_vector() -> impl Strategy<Value = Vector3<f64>> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
        .prop_map(|(x, y, z)| Vector3::new(x, y, z))
        .prop_filter("direction", |v| v.norm() > 0.1)
        .prop_map(|v| v.normalize())
}

fn rotation(max_angle: f64) -> impl Strategy<Value = UnitQuaternion<f64>> {
    (unit_vector(), 0.0..=max_angle)
        .prop_map(|(axis, angle)| UnitQuaternion::from_scaled_axis(axis * angle))
}

fn xyzw(q: &UnitQuaternion<f64>) -> [f64; 4] {
    [q.i, q.j, q.k, q.w]
}

fn constraint() -> impl Strategy<Value = Constraint> {
    prop_oneof![
        Just(Constraint::Fixed),
        Just(Constraint::VerticalAxis),
        Just(Constraint::HorizontalAxis),
        Just(Constraint::Free),
    ]
}

fn policy() -> impl Strategy<Value = OrientationPolicy> {
    prop_oneof![
        Just(OrientationPolicy::HoldWhenConstrained),
        Just(OrientationPolicy::Hold),
        Just(OrientationPolicy::TwistAboutAxis),
    ]
}

/// A random valid configuration (start pose in the middle of the box).
fn config() -> impl Strategy<Value = ArmConfig> {
    (
        (constraint(), policy(), unit_vector(), unit_vector()),
        (0.2..3.0f64, rotation(PI)),
        (
            [-1.5..0.5f64, -1.5..0.5f64, -1.5..0.5f64],
            [0.05..1.5f64, 0.05..1.5f64, 0.05..1.5f64],
        ),
        (0.001..0.1f64, 0.005..0.5f64),
    )
        .prop_map(
            |((constraint, orientation, vertical, horizontal), (scale, g2b), (lo, size), caps)| {
                let max = [lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]];
                ArmConfig {
                    constraint,
                    orientation,
                    vertical_axis: vertical.into(),
                    horizontal_axis: horizontal.into(),
                    translation_scale: scale,
                    glove_to_base: RotationConfig {
                        rpy_rad: None,
                        quaternion_xyzw: Some(xyzw(&g2b)),
                    },
                    workspace_min_m: lo,
                    workspace_max_m: max,
                    max_translation_step_m: caps.0,
                    max_rotation_step_rad: caps.1,
                    start_pose: StartPose {
                        position_m: [
                            0.5 * (lo[0] + max[0]),
                            0.5 * (lo[1] + max[1]),
                            0.5 * (lo[2] + max[2]),
                        ],
                        rpy_rad: Some([0.0, 0.0, 0.0]),
                        quaternion_xyzw: None,
                    },
                }
            },
        )
}

/// A robot pose inside `config`'s box (fractions of the box, boundary included).
fn robot_pose_in(
    config: &ArmConfig,
    fractions: [f64; 3],
    r: UnitQuaternion<f64>,
) -> Isometry3<f64> {
    let p = Vector3::from_fn(|i, _| {
        let (lo, hi) = (config.workspace_min_m[i], config.workspace_max_m[i]);
        (lo + fractions[i] * (hi - lo)).min(hi)
    });
    Isometry3::from_parts(Translation3::from(p), r)
}

fn fractions() -> impl Strategy<Value = [f64; 3]> {
    // Include the faces: a robot exactly on the boundary is allowed.
    let f = prop_oneof![Just(0.0), Just(1.0), 0.0..=1.0f64];
    [f.clone(), f.clone(), f]
}

fn glove_pose() -> impl Strategy<Value = Isometry3<f64>> {
    ([-2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64], rotation(PI))
        .prop_map(|(p, r)| Isometry3::from_parts(Translation3::new(p[0], p[1], p[2]), r))
}

/// One glove move: mostly hand-sized, sometimes a tracking jump or a wrist flip.
fn glove_move() -> impl Strategy<Value = (Vector3<f64>, UnitQuaternion<f64>)> {
    prop_oneof![
        4 => ([-0.03..0.03f64, -0.03..0.03f64, -0.03..0.03f64], rotation(0.1)),
        1 => ([-2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64], rotation(PI)),
    ]
    .prop_map(|(d, r)| (Vector3::new(d[0], d[1], d[2]), r))
}

fn apply(glove: &Isometry3<f64>, (dp, dr): &(Vector3<f64>, UnitQuaternion<f64>)) -> Isometry3<f64> {
    // Keep the walk within the plausible-position bound so every pose is valid input.
    let p = (glove.translation.vector + dp).map(|v| v.clamp(-50.0, 50.0));
    Isometry3::from_parts(Translation3::from(p), dr * glove.rotation)
}

/// Every invariant of one command, given the previous one and the latch.
fn check_command(
    config: &ArmConfig,
    latched_robot: &Isometry3<f64>,
    previous: &Isometry3<f64>,
    command: &ArmCommand,
) -> Result<(), TestCaseError> {
    let target = &command.target;
    let p = target.translation.vector;
    let q = target.rotation;
    prop_assert!(
        p.iter().chain(q.coords.iter()).all(|v| v.is_finite()),
        "{target}"
    );
    prop_assert!((q.quaternion().norm() - 1.0).abs() <= 1e-12);

    let workspace = config.workspace();
    prop_assert!(workspace.contains(&p), "outside the box: {p}");

    let step_m = (p - previous.translation.vector).norm();
    prop_assert!(
        step_m <= config.max_translation_step_m + CAP_SLACK_M,
        "step {step_m} m"
    );
    let step_rad = previous.rotation.angle_to(&q);
    prop_assert!(
        step_rad <= config.max_rotation_step_rad + CAP_SLACK_RAD,
        "step {step_rad} rad"
    );

    let p0 = latched_robot.translation.vector;
    let r0 = latched_robot.rotation;
    match config.axis_of(config.constraint).unwrap() {
        Some(axis) => {
            let off_axis = (p - p0).cross(&axis).norm();
            prop_assert!(off_axis <= ON_AXIS_M, "{off_axis} m off the axis");
            let turn = q * r0.inverse();
            match config.orientation {
                OrientationPolicy::TwistAboutAxis => {
                    prop_assert!((turn * axis.into_inner() - axis.into_inner()).norm() <= 1e-9);
                }
                OrientationPolicy::HoldWhenConstrained | OrientationPolicy::Hold => {
                    prop_assert!(turn.angle() <= 1e-9, "orientation moved {}", turn.angle());
                }
            }
        }
        None if config.constraint == Constraint::Fixed => {
            prop_assert!((p - p0).norm() <= 1e-12, "fixed moved {}", (p - p0).norm());
            prop_assert!(q.angle_to(&r0) <= 1e-9);
        }
        None => {
            if config.orientation == OrientationPolicy::Hold {
                prop_assert!(q.angle_to(&r0) <= 1e-9);
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Box, caps, axis, fixed, unit quaternion: for every configuration and trajectory.
    #[test]
    fn every_command_respects_the_limits(
        config in config(),
        robot_fractions in fractions(),
        robot_rotation in rotation(PI),
        glove0 in glove_pose(),
        moves in prop::collection::vec(glove_move(), 1..60),
    ) {
        let robot = robot_pose_in(&config, robot_fractions, robot_rotation);
        let mut mapper = ArmMapper::new(config.clone()).unwrap();
        mapper.engage(glove0, robot).unwrap();
        let (_, latched_robot) = mapper.latched().unwrap();
        let mut previous = latched_robot;
        let mut glove = glove0;
        for m in &moves {
            glove = apply(&glove, m);
            let command = mapper.step(glove).unwrap().unwrap();
            check_command(&config, &latched_robot, &previous, &command)?;
            previous = command.target;
        }
    }

    /// Within the caps and the box, `free` reproduces the relative glove pose exactly.
    #[test]
    fn free_follows_the_glove_exactly_within_the_caps(
        mut config in config(),
        robot_rotation in rotation(PI),
        robot_offset in [-0.3..0.3f64, -0.3..0.3f64, -0.3..0.3f64],
        glove0 in glove_pose(),
        caps in (0.002..0.02f64, 0.005..0.2f64),
        moves in prop::collection::vec((unit_vector(), 0.0..0.9f64, unit_vector(), 0.0..0.9f64), 1..40),
    ) {
        config.constraint = Constraint::Free;
        config.orientation = OrientationPolicy::HoldWhenConstrained;
        config.workspace_min_m = [-1.5; 3];
        config.workspace_max_m = [1.5; 3];
        config.max_translation_step_m = caps.0;
        config.max_rotation_step_rad = caps.1;
        let s = config.translation_scale;
        let g2b = config.glove_to_base_rotation().unwrap();
        let robot = Isometry3::from_parts(Translation3::new(robot_offset[0], robot_offset[1], robot_offset[2]), robot_rotation);
        let mut mapper = ArmMapper::new(config.clone()).unwrap();
        mapper.engage(glove0, robot).unwrap();
        let mut glove = glove0;
        for (dir, frac, axis, rot_frac) in &moves {
            // Each move stays under 90 % of both caps once mapped to the robot.
            let dp = dir * (frac * caps.0 / s);
            let dr = UnitQuaternion::from_scaled_axis(axis * (rot_frac * caps.1));
            glove = apply(&glove, &(dp, dr));
            let command = mapper.step(glove).unwrap().unwrap();
            let expected_p = robot.translation.vector
                + g2b * (glove.translation.vector - glove0.translation.vector) * s;
            let expected_r = g2b * (glove.rotation * glove0.rotation.inverse()) * g2b.inverse() * robot.rotation;
            let error_m = (command.target.translation.vector - expected_p).norm();
            let error_rad = command.target.rotation.angle_to(&expected_r);
            prop_assert!(error_m <= 1e-9, "position off by {error_m} m");
            prop_assert!(error_rad <= 1e-9, "orientation off by {error_rad} rad");
            prop_assert!(!command.constrained && !command.is_limited(), "{command:?}");
        }
    }

    /// Disengage, move the glove anywhere, re-engage at the held pose: the robot does not move,
    /// and the limits hold relative to the new latch.
    #[test]
    fn clutching_does_not_move_the_robot(
        config in config(),
        robot_fractions in fractions(),
        robot_rotation in rotation(PI),
        glove0 in glove_pose(),
        before in prop::collection::vec(glove_move(), 1..20),
        while_released in prop::collection::vec(glove_move(), 1..20),
        after in prop::collection::vec(glove_move(), 1..20),
    ) {
        let robot = robot_pose_in(&config, robot_fractions, robot_rotation);
        let mut mapper = ArmMapper::new(config.clone()).unwrap();
        mapper.engage(glove0, robot).unwrap();
        let mut glove = glove0;
        for m in &before {
            glove = apply(&glove, m);
            mapper.step(glove).unwrap().unwrap();
        }
        let held = *mapper.last_command().unwrap();
        mapper.disengage();
        for m in &while_released {
            glove = apply(&glove, m);
            prop_assert_eq!(mapper.step(glove).unwrap(), None);
        }
        prop_assert_eq!(mapper.last_command(), Some(&held));
        mapper.engage(glove, held.target).unwrap();
        let first = mapper.step(glove).unwrap().unwrap();
        let moved_m = (first.target.translation.vector - held.target.translation.vector).norm();
        let moved_rad = first.target.rotation.angle_to(&held.target.rotation);
        prop_assert!(moved_m <= 1e-12, "re-engage moved the robot {moved_m} m");
        prop_assert!(moved_rad <= 1e-9, "re-engage turned the robot {moved_rad} rad");
        prop_assert!(!first.constrained && !first.is_limited(), "{first:?}");

        let (_, latched) = mapper.latched().unwrap();
        let mut previous = first.target;
        for m in &after {
            glove = apply(&glove, m);
            let command = mapper.step(glove).unwrap().unwrap();
            check_command(&config, &latched, &previous, &command)?;
            previous = command.target;
        }
    }

    /// A rejected glove pose (NaN, infinite, garbled quaternion) changes nothing: the mapper's
    /// commands equal those of a twin that never saw it.
    #[test]
    fn rejected_inputs_change_nothing(
        config in config(),
        robot_fractions in fractions(),
        robot_rotation in rotation(PI),
        glove0 in glove_pose(),
        moves in prop::collection::vec((glove_move(), prop::option::weighted(0.3, 0..4usize)), 1..40),
    ) {
        let robot = robot_pose_in(&config, robot_fractions, robot_rotation);
        let mut mapper = ArmMapper::new(config.clone()).unwrap();
        let mut twin = ArmMapper::new(config).unwrap();
        mapper.engage(glove0, robot).unwrap();
        twin.engage(glove0, robot).unwrap();
        let mut glove = glove0;
        for (m, corruption) in &moves {
            glove = apply(&glove, m);
            if let Some(kind) = corruption {
                let bad = corrupt(&glove, *kind);
                prop_assert!(mapper.step(bad).is_err());
            }
            prop_assert_eq!(mapper.step(glove).unwrap(), twin.step(glove).unwrap());
        }
    }
}

fn corrupt(glove: &Isometry3<f64>, kind: usize) -> Isometry3<f64> {
    let mut bad = *glove;
    match kind {
        0 => bad.translation.vector.x = f64::NAN,
        1 => bad.translation.vector.z = f64::INFINITY,
        2 => {
            bad.rotation = UnitQuaternion::new_unchecked(Quaternion::new(0.0, 0.0, 0.0, 0.0));
        }
        _ => {
            bad.rotation = UnitQuaternion::new_unchecked(glove.rotation.into_inner() * 1.5);
        }
    }
    bad
}

#[test]
fn engage_refuses_a_robot_outside_the_box() {
    let mut mapper = ArmMapper::new(ArmConfig::default()).unwrap();
    let glove = Isometry3::identity();
    let outside =
        Isometry3::from_parts(Translation3::new(0.5, 0.0, 1.0), UnitQuaternion::identity());
    assert!(mapper.engage(glove, outside).is_err());
    assert!(!mapper.is_engaged());
    // The axis used by the default vertical constraint is +z of the base.
    let axis: Option<Unit<Vector3<f64>>> = ArmConfig::default()
        .axis_of(Constraint::VerticalAxis)
        .unwrap();
    assert_eq!(axis, Some(Vector3::z_axis()));
}
