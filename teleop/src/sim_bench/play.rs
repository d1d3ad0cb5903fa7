//! One run of a strategy: the scene loaded with the run's start, the simulated glove playing
//! the strategy's script with the run's noise, the station core and the physics in lock step
//! until the task is done or the script (and two seconds) is over.

use std::path::Path;

use practice::Strategy;
use retarget::HandModel;
use scoring::TaskSpec;
use simulation::scene::StartPerturbation;
use station::StationConfig;

use super::error::BenchError;
use crate::demo::robot::physics_correctness;
use crate::physics::lockstep::{LockstepObserver, LockstepPlay, play_lockstep};
use crate::physics::setup::{ProjectScene, SceneSource, load_task};
use crate::stand_ins::progress_message::ProgressMessage;
use crate::stand_ins::sim_glove_node::SimGloveConfig;

/// Simulated seconds a run goes on after its script's last keyframe.
pub const TAIL_S: f64 = 2.0;

/// What every run of one embodiment on one task shares.
#[derive(Debug, Clone)]
pub struct ItemSetup<'a> {
    /// The hand the station retargets to.
    pub model: &'a HandModel,
    /// The task.
    pub task: &'a TaskSpec,
    /// The station: the embodiment, the task's station settings and its arm constraint.
    pub station: StationConfig,
    /// The lab's MuJoCo model of the hand, if any (else the project's, from `model`).
    pub hand_file: Option<&'a Path>,
    /// The glove's keypoint noise, standard deviation, metres.
    pub jitter_m: f64,
}

/// A run played.
#[derive(Debug, Clone, PartialEq)]
pub struct PlayedRun {
    /// The seed of its glove noise and its start.
    pub seed: u64,
    /// The physics' progress events, up to the completion.
    pub events: Vec<ProgressMessage>,
    /// Correctness from the events.
    pub correctness: f64,
    /// When the task was done (simulated seconds), if it was.
    pub completed_at_s: Option<f64>,
    /// When the run ended (simulated seconds).
    pub end_s: f64,
}

/// Plays `strategy` once with `seed` (its glove noise and the task's moved start).
pub fn play(
    setup: &ItemSetup<'_>,
    strategy: &Strategy,
    seed: u64,
    observer: Option<&mut dyn LockstepObserver>,
) -> Result<PlayedRun, BenchError> {
    let physics = |source| BenchError::Physics {
        embodiment: setup.station.retarget.embodiment.clone(),
        task: setup.task.id.clone(),
        source: Box::new(source),
    };
    let mut station = setup.station.clone();
    for (axis, offset) in station
        .arm
        .start_pose
        .position_m
        .iter_mut()
        .zip(strategy.start_offset_m)
    {
        *axis += offset;
    }
    let arm_start = station
        .arm
        .start_pose_isometry()
        .map_err(|e| BenchError::Setup(format!("arm start pose: {e}")))?;
    let scene = ProjectScene {
        start: StartPerturbation::from_seed(seed),
        hand_file: setup.hand_file,
        physics: &station.simulated_physics,
    };
    let loaded = load_task(
        setup.task,
        setup.model,
        SceneSource::Project(scene),
        arm_start,
    )
    .map_err(physics)?;
    let glove_config = SimGloveConfig {
        script: Some(strategy.script.clone()),
        jitter_m: setup.jitter_m,
        seed,
        layout: station.retarget.layout,
        ..SimGloveConfig::default()
    };
    let glove = glove_config
        .glove()
        .map_err(|e| BenchError::Setup(format!("simulated glove: {e}")))?;
    let done = |events: &[ProgressMessage]| {
        physics_correctness(setup.task, events).is_ok_and(|c| c >= 1.0)
    };
    let play = LockstepPlay {
        config: &station,
        model: setup.model,
        glove: &glove,
        rate_hz: glove_config.rate_hz,
        duration_s: strategy.script.duration_s() + TAIL_S,
        until: Some(&done),
        // Each arm coerces the observer to the run's shorter lifetime (a plain move or
        // `map` keeps the caller's, which the run's locals do not live for).
        observer: match observer {
            Some(o) => Some(o),
            None => None,
        },
    };
    let outcome = play_lockstep(play, loaded).map_err(physics)?;
    let correctness =
        physics_correctness(setup.task, &outcome.events).map_err(|reason| BenchError::Scoring {
            embodiment: setup.station.retarget.embodiment.clone(),
            task: setup.task.id.clone(),
            reason,
        })?;
    let completed_at_s = (correctness >= 1.0)
        .then(|| outcome.events.last().map(|e| e.sim_time_s))
        .flatten();
    Ok(PlayedRun {
        seed,
        events: outcome.events,
        correctness,
        completed_at_s,
        end_s: outcome.sim_time_s,
    })
}
