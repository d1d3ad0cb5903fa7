//! `pomdar sim`'s runs (built with the `physics` feature only): the simulated robot in a task's
//! MuJoCo scene in real time on the robot's topics, the scene written out (`--write-scene`),
//! or a glove script through the station core into the scene in simulated time
//! (`--lockstep`, once or over several seeds). The command fills a [`SimRequest`].

mod error;
mod lockstep_runs;
mod run_report;

use std::path::PathBuf;
use std::sync::{Arc, Mutex};

pub use error::SimRunError;

use crate::clock::StationClock;
use crate::physics::robot_node::{
    PhysicsRobotConfig, PhysicsRobotReport, PhysicsRobotRun, run_physics_robot,
};
use crate::physics::setup::{ProjectScene, SceneSource, load_task, project_scene_xml};
use crate::ros::NetworkOverride;
use crate::score::score_inputs::ScoringInputs;
use crate::station_driver::setup::load_station_config;
use crate::tui::terminal_shell::ctrl_c_shutdown;
use lockstep_runs::lockstep;
use run_report::{start_move, summary_line, timed_shutdown};

/// What `pomdar sim` is asked to do (see `pomdar sim --help` for each value's flag).
#[derive(Debug, Clone)]
pub struct SimRequest {
    /// `--task`.
    pub task: String,
    /// `--scene`: a lab's own task MJCF.
    pub scene: Option<PathBuf>,
    /// `--catalog`.
    pub catalog: Option<PathBuf>,
    /// `--config`.
    pub config: Option<PathBuf>,
    /// `--write-scene`.
    pub write_scene: Option<PathBuf>,
    /// `--lockstep`: the glove script.
    pub lockstep: Option<PathBuf>,
    /// `--duration`, s.
    pub duration: Option<f64>,
    /// `--glove-jitter-mm`.
    pub glove_jitter_mm: Option<f64>,
    /// `--seed`.
    pub seed: u64,
    /// `--runs`.
    pub runs: u64,
    /// `--hand-mjcf`.
    pub hand_mjcf: Option<PathBuf>,
    /// `--perturb-start`.
    pub perturb_start: bool,
    /// `--domain-id` and `--interface`.
    pub network: NetworkOverride,
}

/// Runs `pomdar sim` as asked.
pub async fn run_sim(args: SimRequest) -> Result<(), SimRunError> {
    let inputs = ScoringInputs::load(args.catalog.as_deref(), None, None)?;
    let task = inputs
        .catalog
        .get(&args.task)
        .cloned()
        .ok_or_else(|| SimRunError::UnknownTask {
            task: args.task.clone(),
            ids: inputs.catalog.ids().to_string(),
        })?;
    let station = load_station_config(args.config.as_deref(), None)?;
    let hand_file = args
        .hand_mjcf
        .as_deref()
        .or(station.simulated_hand_mjcf.as_deref());
    let arm_start = station.arm.start_pose_isometry()?;
    let model = retarget::HandModel::orca_v1_right();
    if let Some(path) = &args.write_scene {
        let scene = ProjectScene {
            hand_file,
            ..ProjectScene::for_station(&station)
        };
        let (xml, _) = project_scene_xml(&task, &model, arm_start, scene)?;
        crate::atomic_file::write_atomically(path, xml.as_bytes()).map_err(|source| {
            SimRunError::WriteScene {
                path: path.clone(),
                source,
            }
        })?;
        println!("wrote the {} scene to {}", task.id, path.display());
        return Ok(());
    }
    if (args.perturb_start || hand_file.is_some()) && args.scene.is_some() {
        return Err(SimRunError::LabSceneAsWritten);
    }
    let source = |seed: u64| match &args.scene {
        Some(path) => SceneSource::LabFile(path),
        None => SceneSource::Project(ProjectScene {
            start: start_move(args.perturb_start, seed),
            hand_file,
            physics: &station.simulated_physics,
        }),
    };
    if let Some(script) = &args.lockstep {
        let load = |seed: u64| load_task(&task, &model, source(seed), arm_start);
        return lockstep(&station, &model, &load, script, &args);
    }
    let loaded = load_task(&task, &model, source(args.seed), arm_start)?;
    let config = PhysicsRobotConfig::for_station(&station, &loaded, arm_start);
    let report = Arc::new(Mutex::new(PhysicsRobotReport::default()));
    let (_control, control_rx) = tokio::sync::mpsc::channel(4);
    let shutdown = match args.duration {
        Some(s) => timed_shutdown(s),
        None => ctrl_c_shutdown(),
    };
    eprintln!(
        "pomdar sim: task {} ({}), {} scene; hand targets on {}, arm targets on {}, progress on {}",
        task.id,
        task.name,
        args.scene
            .as_ref()
            .map_or("the project's".to_string(), |p| p.display().to_string()),
        config.hand_targets_topic,
        config.arm_target_topic,
        config.progress_topic
    );
    let run = PhysicsRobotRun {
        model,
        engine: loaded.engine,
        network: args.network.apply(&station.network),
        clock: StationClock::new(),
        report: report.clone(),
        control: control_rx,
        events: None,
        shutdown,
        options: Default::default(),
    };
    run_physics_robot(config, run).await?;
    if let Ok(r) = report.lock() {
        eprintln!("{}", summary_line(&r));
    }
    Ok(())
}
