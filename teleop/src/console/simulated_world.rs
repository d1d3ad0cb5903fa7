//! `--simulate`: the simulated glove (a periodic motion or a task script) and, for a robot,
//! the mock hand and Franka or with `--physics` the simulated robot in the task's scene, all
//! on the station's loopback domain, in this process.

use retarget::HandModel;
use retarget::human_hand::GloveScript;
use scoring::TaskSpec;
use station::StationConfig;
use tokio::sync::watch;
use tokio::task::JoinHandle;

use super::physics_link::{PhysicsLink, PhysicsParts};
use super::session_error::SessionError;
use super::session_options::{SessionOptions, SimulationOptions};
use crate::clock::StationClock;
use crate::device_thread::spawn_device;
use crate::stand_ins::glove_jitter::glove_jitter_m;
use crate::stand_ins::mock_robot::spawn_mock_robot;
use crate::stand_ins::sim_glove_node::{GloveOrigin, SimGloveConfig, publish_glove};

/// What the simulated robot is for.
pub(super) struct SimulatedRobot<'a> {
    pub(super) config: &'a StationConfig,
    pub(super) model: &'a HandModel,
    #[cfg_attr(not(feature = "physics"), allow(dead_code))] // read by the simulator only
    pub(super) task: &'a TaskSpec,
}

/// The simulated robot's tasks and, with `--physics`, the console's link to it.
pub(super) type SimulatedTasks = (
    Vec<JoinHandle<Result<(), crate::stand_ins::SimError>>>,
    Option<PhysicsLink>,
);

/// `--simulate`: a simulated glove (its motion, or `glove_script`), and for a robot a mock
/// hand and a mock Franka, or with `--physics` the simulated robot in the task's scene, on the
/// station's loopback domain, until `shutdown`.
pub(super) fn spawn_simulation(
    options: &SessionOptions,
    simulation: &SimulationOptions,
    robot: &SimulatedRobot<'_>,
    clock: StationClock,
    shutdown: &watch::Receiver<bool>,
    glove_script: Option<GloveScript>,
) -> Result<SimulatedTasks, SessionError> {
    let config = robot.config;
    let mut tasks = Vec::new();
    let mut physics = None;
    let mut origin = GloveOrigin::FirstSubscriber;
    if simulation.physics {
        let (task, link, origin_rx) = spawn_physics(simulation, robot, clock, shutdown)?;
        tasks.push(task);
        physics = Some(link);
        origin = GloveOrigin::Shared(origin_rx);
    } else if config.drives_robot() {
        let mock = spawn_mock_robot(config, robot.model, clock, shutdown)?;
        tasks.extend([mock.hand, mock.arm]);
    }
    let motion = simulation.motion;
    let glove_config = SimGloveConfig {
        keypoints_topic: config.input.keypoints_topic.clone(),
        wrist_topic: config.input.wrist_topic.clone(),
        layout: config.retarget.layout,
        motion,
        period_s: motion.default_period_s(),
        hand_scale: simulated_hand_scale(options),
        seed: name_seed(&options.user),
        jitter_m: glove_jitter_m(simulation.glove_jitter_mm, glove_script.is_some())?,
        script: glove_script,
        ..SimGloveConfig::default()
    };
    let glove = glove_config.glove()?;
    let network = config.network.clone();
    // On a thread of its own, as a real glove is a machine of its own (`device_thread`).
    let glove = spawn_device("simulated-glove", {
        let shutdown = shutdown.clone();
        async move {
            publish_glove(glove, &glove_config, network, clock, origin, shutdown).await?;
            Ok(())
        }
    })?;
    tasks.push(glove);
    Ok((tasks, physics))
}

/// `--physics`: the simulated robot in the session task's scene.
#[cfg(feature = "physics")]
fn spawn_physics(
    simulation: &SimulationOptions,
    robot: &SimulatedRobot<'_>,
    clock: StationClock,
    shutdown: &watch::Receiver<bool>,
) -> Result<PhysicsParts, SessionError> {
    super::physics_link::spawn_physics_robot(
        robot.config,
        robot.model,
        robot.task,
        simulation.scene.as_deref(),
        clock,
        shutdown,
    )
}

/// `--physics` in a build without the simulator.
#[cfg(not(feature = "physics"))]
fn spawn_physics(
    _simulation: &SimulationOptions,
    _robot: &SimulatedRobot<'_>,
    _clock: StationClock,
    _shutdown: &watch::Receiver<bool>,
) -> Result<PhysicsParts, SessionError> {
    Err(SessionError::NoPhysics)
}

/// The simulated hand's size: the flag, else 1 for a robot session, else one drawn from the
/// participant's name in [0.85, 1.15] (each simulated participant keeps their own hand).
fn simulated_hand_scale(options: &SessionOptions) -> f64 {
    match (options.simulated_hand_scale, options.human()) {
        (Some(scale), _) => scale,
        (None, false) => 1.0,
        (None, true) => 0.85 + 0.3 * (name_seed(&options.user) % 1000) as f64 / 999.0,
    }
}

/// A stable seed from a name, so a simulated participant is the same every run.
fn name_seed(name: &str) -> u64 {
    crate::fnv::fnv1a_64(name.as_bytes())
}
