//! One place a simulated task is loaded: the project's own scene for a catalog task (the hand
//! from the station's model, the scaffold and its progress mapping from `simulation`), or a
//! lab's own MJCF by path with the progress joint the catalog maps for that task.

use std::path::Path;

use nalgebra::Isometry3;
use retarget::HandModel;
use scoring::TaskSpec;
use simulation::hand_mjcf::{HandMjcf, HandMjcfOptions, hand_mjcf};
use simulation::lab_hand::lab_hand_mjcf;
use simulation::progress::PhysicsMapping;
use simulation::scene::{MountWeld, SceneOptions, StartPerturbation, task_scene};
use station::{SimulatedPhysicsConfig, StationConfig};

use super::engine::{HandBinding, PhysicsEngine};
use super::error::PhysicsError;

/// The mocap body carrying the hand in every scene (the project's, and a lab's file must name
/// its own the same).
pub const MOUNT_BODY: &str = "pomdar_arm_mount";

/// A task ready to simulate.
pub struct SimulatedTask {
    /// The loaded, bound scene.
    pub engine: PhysicsEngine,
    /// The catalog's entry.
    pub task: TaskSpec,
    /// Where its progress is read.
    pub progress: PhysicsMapping,
    /// The body whose pose is published as the task object's, if any.
    pub object_body: Option<String>,
    /// The scene's MJCF text (the project's scenes only; a lab's file is read by MuJoCo).
    pub scene_xml: Option<String>,
}

/// The project's scene of a task: how its start is moved, which hand it holds and how.
#[derive(Debug, Clone, Copy)]
pub struct ProjectScene<'a> {
    /// How the task's start is moved.
    pub start: StartPerturbation,
    /// The lab's own MJCF of the hand (the manufacturer's model, with its meshes) instead of
    /// the hand the project writes from the URDF.
    pub hand_file: Option<&'a Path>,
    /// The station file's contact, actuator and mount settings (unset: the twin's defaults).
    pub physics: &'a SimulatedPhysicsConfig,
}

impl Default for ProjectScene<'_> {
    fn default() -> Self {
        ProjectScene {
            start: StartPerturbation::NONE,
            hand_file: None,
            physics: &SimulatedPhysicsConfig::DEFAULTS,
        }
    }
}

impl<'a> ProjectScene<'a> {
    /// The scene a station configuration asks for: its hand file and physics settings, the
    /// start as drawn.
    pub fn for_station(station: &'a StationConfig) -> ProjectScene<'a> {
        ProjectScene {
            start: StartPerturbation::NONE,
            hand_file: station.simulated_hand_mjcf.as_deref(),
            physics: &station.simulated_physics,
        }
    }
}

/// Where the scene comes from.
#[derive(Debug, Clone, Copy)]
pub enum SceneSource<'a> {
    /// The project's scaffold for the task.
    Project(ProjectScene<'a>),
    /// A lab's own MJCF file (its hand's joints and actuators named as the URDF's degrees of
    /// freedom, its hand under a mocap body named [`MOUNT_BODY`]).
    LabFile(&'a Path),
}

/// The hand the twin simulates: the lab's MJCF `hand_file`, or the project's from `model`,
/// with `physics`' contact (and, for the project's hand, actuator) settings.
pub fn twin_hand(
    model: &HandModel,
    hand_file: Option<&Path>,
    physics: &SimulatedPhysicsConfig,
) -> Result<HandMjcf, PhysicsError> {
    let options = hand_options(physics);
    let Some(path) = hand_file else {
        return Ok(hand_mjcf(model, &options));
    };
    let origin = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| PhysicsError::Load {
        origin: origin.clone(),
        message: format!("cannot read the hand's MJCF: {e}"),
    })?;
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let dir = absolute
        .parent()
        .map_or(String::new(), |d| d.display().to_string());
    lab_hand_mjcf(&text, &origin, &dir, model, &options).map_err(|e| PhysicsError::Load {
        origin,
        message: e.to_string(),
    })
}

/// The project's scene of `task` written as MJCF (for `pomdar sim --write-scene`).
pub fn project_scene_xml(
    task: &TaskSpec,
    model: &HandModel,
    arm_start: Isometry3<f64>,
    scene: ProjectScene<'_>,
) -> Result<(String, PhysicsMapping), PhysicsError> {
    let hand = twin_hand(model, scene.hand_file, scene.physics)?;
    scene_with_hand(task, &hand, arm_start, &scene)
}

/// The twin's hand settings: the defaults, with what `physics` sets.
fn hand_options(physics: &SimulatedPhysicsConfig) -> HandMjcfOptions {
    let default = HandMjcfOptions::default();
    HandMjcfOptions {
        position_gain: physics.actuator_kp.unwrap_or(default.position_gain),
        joint_damping: physics.joint_damping.unwrap_or(default.joint_damping),
        armature: physics.joint_armature.unwrap_or(default.armature),
        max_torque_nm: physics
            .actuator_max_torque_nm
            .unwrap_or(default.max_torque_nm),
        friction: physics.contact_friction.unwrap_or(default.friction),
        contact_solref: physics.contact_solref.unwrap_or(default.contact_solref),
        contact_solimp: physics.contact_solimp.unwrap_or(default.contact_solimp),
        contact_margin_m: physics.contact_margin_m.unwrap_or(default.contact_margin_m),
        ..default
    }
}

/// The project's scene of `task` holding `hand`, its start and world as `scene` says.
fn scene_with_hand(
    task: &TaskSpec,
    hand: &HandMjcf,
    arm_start: Isometry3<f64>,
    scene: &ProjectScene<'_>,
) -> Result<(String, PhysicsMapping), PhysicsError> {
    let default = SceneOptions::default();
    let weld = MountWeld::default();
    let options = SceneOptions {
        arm_start,
        start: scene.start,
        impratio: scene.physics.impratio.unwrap_or(default.impratio),
        mount: MountWeld {
            solref: scene.physics.mount_solref.unwrap_or(weld.solref),
            solimp: scene.physics.mount_solimp.unwrap_or(weld.solimp),
        },
        ..default
    };
    let scene = task_scene(task, hand, &options).map_err(|e| PhysicsError::Load {
        origin: format!("the project's scene for {}", task.id),
        message: e.to_string(),
    })?;
    Ok((scene.xml, scene.progress))
}

/// Load `task` from `source` with the hand `model`, the arm's mount at `arm_start`.
pub fn load_task(
    task: &TaskSpec,
    model: &HandModel,
    source: SceneSource<'_>,
    arm_start: Isometry3<f64>,
) -> Result<SimulatedTask, PhysicsError> {
    let hand = match source {
        SceneSource::Project(scene) => twin_hand(model, scene.hand_file, scene.physics)?,
        SceneSource::LabFile(_) => twin_hand(model, None, &SimulatedPhysicsConfig::DEFAULTS)?,
    };
    let binding = hand_binding(&hand);
    let (engine, progress, scene_xml) = match source {
        SceneSource::Project(scene) => {
            // The hand read once: it is the scene's and the binding's.
            let (xml, progress) = scene_with_hand(task, &hand, arm_start, &scene)?;
            let origin = format!("the project's scene for {}", task.id);
            let engine = PhysicsEngine::from_xml_str(&xml, &origin, &binding)?;
            (engine, progress, Some(xml))
        }
        SceneSource::LabFile(path) => {
            let progress = task.physics.clone().ok_or_else(|| PhysicsError::Progress {
                message: format!(
                    "task {} has no physics mapping in the catalog: add `physics = {{ joint = \"…\" }}` to its entry to read its progress from {}",
                    task.id,
                    path.display()
                ),
            })?;
            let engine = PhysicsEngine::from_file(path, &binding)?;
            (engine, progress, None)
        }
    };
    if engine.reading(&progress.joint).is_none() {
        return Err(PhysicsError::Missing {
            origin: task.id.clone(),
            kind: "progress joint",
            names: vec![progress.joint.clone()],
        });
    }
    let object_body = engine.body_of_joint(&progress.joint);
    Ok(SimulatedTask {
        engine,
        task: task.clone(),
        progress,
        object_body,
        scene_xml,
    })
}

/// How the engine finds the hand of a scene written with `hand`'s names.
pub fn hand_binding(hand: &HandMjcf) -> HandBinding {
    HandBinding {
        dof_joints: hand.dof_joints.clone(),
        dof_actuators: hand.dof_actuators.clone(),
        mount_body: MOUNT_BODY.to_string(),
        max_speed_rad_s: hand.max_speed_rad_s,
        zero_offsets_rad: hand.zero_offsets_rad.clone(),
    }
}
