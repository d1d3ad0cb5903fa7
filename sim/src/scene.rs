//! The 18 POMDAR task scenes as MuJoCo MJCF, written by this project, each with its progress
//! mapping; and the world around them (table, light, the hand on a free body welded to the
//! arm's mocap body).
//!
//! The paper's CAD is not shipped and the lab's own task files carry no licence, so every
//! scaffold here is a simplified stand-in drawn from the task descriptions: the mechanism
//! that makes progress (a keyed slot, a bump, a slide, a hinge, a free object and a target)
//! is modelled, the printed parts are not. All sizes and masses are this project's guesses;
//! each file says which facts come from the paper (the task list, notch and curve counts,
//! the 0–200 mm slide, rotation out of 360°, the grasp levels).
//!
//! World frame: the Franka base frame, x forward, z up, the table top the plane z = 0. The
//! scaffolds stand around x = 0.5 m, y = 0 in front of the arm's start pose (0.45, 0, 0.40).
//!
//! | file | tasks | progress joint |
//! |---|---|---|
//! | `vertical.rs` | V1–V3: a handle keyed through 6 slotted plates on a tower | `handle_slide` (slide, marks) |
//! | `horizontal.rs` | H1–H3: a carriage on a rail lifted over bumps; H4/H5: a rod slid through its supports | `carriage_slide`, `rod_slide` (slides) |
//! | `continuous.rs` | C1–C3: a rotor (bolt, T-bar, wheel) on a post; C4: a spinner | `rotor_hinge`, `spinner_hinge` (hinges) |
//! | `grasp.rs` | G1–G6: a free object and a target region | `object_free` (free joint) |
//! | `world.rs` | the world: options, defaults, table, light, mount, hand, sections | |
//!
//! Contact classes: fixtures `pomdar_fixture` (condim 3), moving task parts `pomdar_object`
//! (condim 4: torsional friction for grasping), free objects `pomdar_free_object` (condim 6:
//! rolling friction stops a sphere or cylinder rolling away), and non-colliding markers
//! `pomdar_marker`. Their contacts and the task joints' limits use `solref` 0.004 s (twice
//! the default time step) instead of MuJoCo's 0.02 s: with the default, a 50 g handle pushed
//! up with 3 N sank 10 mm into a plate and slipped through a notch 30° off its key, and a
//! rod pushed with 1 N ran 10 mm past its end stop (measured with MuJoCo 3.17.0); MuJoCo's
//! `refsafe` keeps the time constant at least twice the time step for larger steps. `solimp`
//! stays at the default. Elliptic friction cones with `impratio` 10 by default (MuJoCo's advice
//! for grasping; [`SceneOptions::impratio`]) and the `implicitfast` integrator are this project's choice.
//!
//! Reading progress (for the simulator): a slide's or hinge's `qpos`, or for a free joint its
//! body's world position (`xpos`, the body origin) and the norm of the joint's linear
//! velocity (`qvel[0..3]`, world frame).

mod continuous;
mod grasp;
mod horizontal;
mod mjcf;
mod start;
mod vertical;
mod world;

#[cfg(test)]
mod tests;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use scoring::{InvalidMapping, PhysicsMapping, TaskSpec};

use crate::hand_mjcf::HandMjcf;

pub use start::{MECHANISM_CENTRE_XY, START_OFFSET_MAX_M, START_YAW_MAX_RAD, StartPerturbation};

/// The 18 task IDs this module writes scenes for, in catalog order.
pub const TASK_IDS: [&str; 18] = [
    "V1", "V2", "V3", "H1", "H2", "H3", "H4", "H5", "C1", "C2", "C3", "C4", "G1", "G2", "G3", "G4",
    "G5", "G6",
];

/// The mocap body the simulator moves to the arm's target pose.
pub const MOUNT_BODY: &str = "pomdar_arm_mount";

/// The free body carrying the hand, welded to the mocap body at the hand's mount pose.
pub const HAND_MOUNT_BODY: &str = "pomdar_hand_mount";

/// The weld between [`MOUNT_BODY`] and [`HAND_MOUNT_BODY`].
pub const MOUNT_WELD: &str = "pomdar_hand_mount_weld";

/// The allowed physics time steps, s.
pub const TIMESTEP_RANGE_S: std::ops::RangeInclusive<f64> = 0.0001..=0.01;

/// How the world is set up.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneOptions {
    /// The physics time step, s, in [`TIMESTEP_RANGE_S`]. Default 0.002.
    pub timestep_s: f64,
    /// The mocap body's initial pose (the arm flange) in the world frame, m. Default the
    /// station's start pose: (0.45, 0, 0.40), flange pointing down (a half turn about x).
    pub arm_start: Isometry3<f64>,
    /// How the task's start is moved (default: not at all).
    pub start: StartPerturbation,
    /// MuJoCo's `impratio` in the elliptic friction cones: how much stiffer friction is than
    /// the normal force. Default 10.
    pub impratio: f64,
    /// How the hand is held to the arm's mocap body.
    pub mount: MountWeld,
}

/// The weld holding the hand's free body to the arm's mocap body: stiff, but a constraint the
/// contacts see, so a finger carried by the arm drags what it presses on (a hand parented to
/// the mocap body moves by having its pose set, and its fingers slide over what they push).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MountWeld {
    /// MuJoCo `solref`: time constant (s) and damping ratio. Default `0.005 1`.
    pub solref: [f64; 2],
    /// MuJoCo `solimp`: impedance at zero and full violation and the width (m). Default
    /// `0.97 0.99 0.0005`.
    pub solimp: [f64; 3],
}

impl Default for MountWeld {
    fn default() -> Self {
        // The benchmark authors' own ORCA scene holds its hand by a weld with these numbers.
        MountWeld {
            solref: [0.005, 1.0],
            solimp: [0.97, 0.99, 0.0005],
        }
    }
}

impl Default for SceneOptions {
    fn default() -> Self {
        SceneOptions {
            timestep_s: 0.002,
            arm_start: Isometry3::from_parts(
                Translation3::new(0.45, 0.0, 0.40),
                UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI),
            ),
            start: StartPerturbation::NONE,
            impratio: 10.0,
            mount: MountWeld::default(),
        }
    }
}

/// The names the simulator needs from the hand placed in a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneHand {
    /// The actuated joints, in degree-of-freedom order.
    pub dof_joints: Vec<String>,
    /// The position actuators, in the same order.
    pub dof_actuators: Vec<String>,
    /// The fingertip bodies: thumb, index, middle, ring, little.
    pub tip_bodies: [String; 5],
    /// The palm body.
    pub palm_body: String,
    /// The fastest joint speed the hand can follow, rad/s.
    pub max_speed_rad_s: f64,
}

/// A task's whole world as MJCF, with where its progress is read.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The task's ID (`V1`).
    pub task_id: String,
    /// The MJCF document.
    pub xml: String,
    /// Where the task's progress is read (this scene's own joints).
    pub progress: PhysicsMapping,
    /// The mocap body's name ([`MOUNT_BODY`]).
    pub mount_body: String,
    /// The hand's names in the scene.
    pub hand: SceneHand,
}

/// A scene cannot be written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    /// No scene for this task ID.
    #[error("task id {id:?}: no scene; the known tasks are {known}")]
    UnknownTask {
        /// The ID asked for.
        id: String,
        /// The known IDs, joined.
        known: String,
    },
    /// The time step is out of range.
    #[error("timestep_s = {value}: s, in [0.0001, 0.01]")]
    Timestep {
        /// The value given.
        value: f64,
    },
    /// The arm's start pose is not finite.
    #[error("arm_start = {value}: a finite pose")]
    ArmStart {
        /// The pose given, as text.
        value: String,
    },
    /// The start perturbation is out of range.
    #[error("start = {value}: a shift of at most 5 mm along x and y and a turn of at most 3°")]
    Start {
        /// The perturbation given, as text.
        value: String,
    },
    /// The scene's progress mapping does not fit the task's correctness kind in the catalog.
    #[error("task {id}: the scene's progress mapping does not fit its catalog entry: {source}")]
    Mapping {
        /// The task's ID.
        id: String,
        /// What does not fit.
        source: InvalidMapping,
    },
}

/// A task's own part of the world.
struct Scaffold {
    /// Bodies and geoms inside `<worldbody>`.
    bodies: String,
    /// Where progress is read.
    mapping: PhysicsMapping,
}

/// The whole world for `task` (one of [`TASK_IDS`]) with `hand` under the arm's mocap body.
///
/// The scene's own progress mapping is returned; the catalog's `physics` entry (for a lab's
/// own task files) is not used. `Err` for an unknown ID, options out of range, or a catalog
/// entry whose correctness kind does not fit the scene (another number of notches).
pub fn task_scene(
    task: &TaskSpec,
    hand: &HandMjcf,
    options: &SceneOptions,
) -> Result<Scene, SceneError> {
    check_options(options)?;
    let scaffold =
        scaffold_for(&task.id, &options.start).ok_or_else(|| SceneError::UnknownTask {
            id: task.id.clone(),
            known: TASK_IDS.join(", "),
        })?;
    scaffold
        .mapping
        .validate(&task.correctness)
        .map_err(|source| SceneError::Mapping {
            id: task.id.clone(),
            source,
        })?;
    Ok(Scene {
        task_id: task.id.clone(),
        xml: world::world_xml(&task.id, &scaffold.bodies, hand, options),
        progress: scaffold.mapping,
        mount_body: MOUNT_BODY.to_string(),
        hand: SceneHand {
            dof_joints: hand.dof_joints.clone(),
            dof_actuators: hand.dof_actuators.clone(),
            tip_bodies: hand.tip_bodies.clone(),
            palm_body: hand.palm_body.clone(),
            max_speed_rad_s: hand.max_speed_rad_s,
        },
    })
}

fn check_options(options: &SceneOptions) -> Result<(), SceneError> {
    if !TIMESTEP_RANGE_S.contains(&options.timestep_s) {
        return Err(SceneError::Timestep {
            value: options.timestep_s,
        });
    }
    let pose = &options.arm_start;
    let finite = pose.translation.vector.iter().all(|v| v.is_finite())
        && pose.rotation.coords.iter().all(|v| v.is_finite());
    if !finite {
        return Err(SceneError::ArmStart {
            value: format!("{pose:?}"),
        });
    }
    let start = &options.start;
    let within = start.offset_m.iter().all(|v| v.abs() <= START_OFFSET_MAX_M)
        && start.yaw_rad.abs() <= START_YAW_MAX_RAD;
    if !within {
        return Err(SceneError::Start {
            value: format!("{start:?}"),
        });
    }
    Ok(())
}

fn scaffold_for(id: &str, start: &StartPerturbation) -> Option<Scaffold> {
    use continuous::Rotor;
    use grasp::Object;
    use horizontal::{RailGrip, RodStroke};
    use vertical::Handle;
    Some(match id {
        "V1" => placed(vertical::scaffold(Handle::Wheel), start),
        "V2" => placed(vertical::scaffold(Handle::Stick), start),
        "V3" => placed(vertical::scaffold(Handle::Sphere), start),
        "H1" => placed(horizontal::rail_scaffold(RailGrip::Scissors), start),
        "H2" => placed(horizontal::rail_scaffold(RailGrip::Chopsticks), start),
        "H3" => placed(horizontal::rail_scaffold(RailGrip::Syringe), start),
        "H4" => placed(horizontal::rod_scaffold(RodStroke::Palmar), start),
        "H5" => placed(horizontal::rod_scaffold(RodStroke::Pinch), start),
        "C1" => placed(continuous::rotor_scaffold(Rotor::Bolt), start),
        "C2" => placed(continuous::rotor_scaffold(Rotor::Stick), start),
        "C3" => placed(continuous::rotor_scaffold(Rotor::Wheel), start),
        "C4" => placed(continuous::spinner_scaffold(), start),
        "G1" => grasp::scaffold(Object::Wheel, start),
        "G2" => grasp::scaffold(Object::Sphere, start),
        "G3" => grasp::scaffold(Object::Disk, start),
        "G4" => grasp::scaffold(Object::CylinderSmall, start),
        "G5" => grasp::scaffold(Object::CylinderMedium, start),
        "G6" => grasp::scaffold(Object::CylinderLarge, start),
        _ => return None,
    })
}

/// A mechanism's scaffold moved as `start` says.
fn placed(scaffold: Scaffold, start: &StartPerturbation) -> Scaffold {
    Scaffold {
        bodies: start.place_mechanism(&scaffold.bodies),
        ..scaffold
    }
}
