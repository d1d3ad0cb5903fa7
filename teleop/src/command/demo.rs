//! `pomdar demo`: the whole pipeline on loopback DDS.

use std::path::PathBuf;

use clap::Args;
use retarget::human_hand::MotionKind;

use super::shared_args::{MotionArg, ViewArgs};
use crate::demo::PhysicsTask;
use crate::demo::{DemoOptions, run_demo};
use crate::ros::default_domain_id;
use crate::score::score_inputs::ScoringInputs;
use crate::stand_ins::glove_script_file::load_glove_script;
use crate::stand_ins::sim_glove_node::SimGloveConfig;
use crate::station_driver::setup::load_station_config;

/// The whole pipeline on loopback DDS: simulated glove → station → mock hand and arm.
///
/// Runs in one process on its own ROS domain id (never the lab's 0 by default), prints a
/// status line every second and a summary at the end: input and output rates, end-to-end
/// latency (glove publish → joint target received) p50/p99, solver time, rejected frames,
/// fingertip error.
///
/// Examples:
///   pomdar demo
///   pomdar demo --duration 60 --motion pinches
///   pomdar demo --duration 5 --json
///   pomdar demo --out logs/        # also record the run to logs/demo-<time>.mcap
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct DemoArgs {
    /// How long the simulated glove plays, seconds.
    #[arg(long, default_value_t = 20.0)]
    pub duration: f64,
    /// Print only a JSON summary on stdout (no live status).
    #[arg(long)]
    pub json: bool,
    /// ROS domain id for the demo (default: one of 150–229 that no other run on this machine holds).
    #[arg(long)]
    pub domain_id: Option<u16>,
    /// Station configuration (default: the ETH lab preset built in).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Scripted glove motion (periodic, the wrist in place).
    #[arg(long, value_enum, default_value = "task-like")]
    pub motion: MotionArg,
    /// Instead of --motion, play this task script (TOML keyframes of the wrist's offset from
    /// its start, glove frame, and the hand's pose, e.g. launch_configs/sim/grasp_place.toml)
    /// once from the glove's first frame, then hold its last keyframe. The demo engages on
    /// the first frame, so the arm follows the wrist's path.
    #[arg(long, value_name = "FILE", conflicts_with = "motion")]
    pub glove_script: Option<PathBuf>,
    /// Keypoint noise of the simulated glove, standard deviation per axis, mm (0–50; default
    /// 1, or 0.5 with --glove-script: the noise of a hand at rest, so the script's still
    /// phases are not taken for a stalled glove).
    #[arg(long, value_name = "MM")]
    pub glove_jitter_mm: Option<f64>,
    /// Glove publishing rate, Hz.
    #[arg(long, default_value_t = 100.0)]
    pub glove_rate_hz: f64,
    /// Record the run to an MCAP log in this directory (demo-<time>.mcap).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// The user's calibration profile (TOML written by `pomdar calibrate`); overrides the
    /// configuration's `calibration_profile`. Default: the configuration's, else none
    /// (identity: scale 1, no rotation).
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// The live view.
    #[command(flatten)]
    pub view: ViewArgs,
    /// Drive the simulated robot in a MuJoCo scene of --task instead of the mock robot: the
    /// physics measures the task's progress and the summary gives its correctness (needs the
    /// `physics` build: `bash sim/setup_mujoco.sh`, then `--features physics`).
    #[arg(long)]
    pub physics: bool,
    /// With --physics: the task (catalog id); its scene and its arm constraint.
    #[arg(long, default_value = "G4", requires = "physics")]
    pub task: String,
    /// With --physics: a lab's own task MJCF instead of the project's scaffold (see
    /// `pomdar sim --help`).
    #[arg(long, value_name = "FILE", requires = "physics")]
    pub scene: Option<PathBuf>,
    /// With --physics: the task catalog (default: the built-in POMDAR catalog).
    #[arg(long, value_name = "FILE", requires = "physics")]
    pub catalog: Option<PathBuf>,
}

/// `pomdar demo`.
pub async fn demo(args: DemoArgs) -> anyhow::Result<()> {
    let station = load_station_config(args.config.as_deref(), args.profile.as_deref())?;
    let glove = SimGloveConfig {
        motion: args.motion.into(),
        period_s: MotionKind::from(args.motion).default_period_s(),
        rate_hz: args.glove_rate_hz,
        keypoints_topic: station.input.keypoints_topic.clone(),
        wrist_topic: station.input.wrist_topic.clone(),
        layout: station.retarget.layout,
        script: args
            .glove_script
            .as_deref()
            .map(load_glove_script)
            .transpose()?,
        jitter_m: crate::stand_ins::glove_jitter::glove_jitter_m(
            args.glove_jitter_mm,
            args.glove_script.is_some(),
        )?,
        ..SimGloveConfig::default()
    };
    if !(args.duration > 0.0 && args.duration <= 86_400.0) {
        anyhow::bail!("--duration {} must be in (0, 86400] seconds", args.duration);
    }
    let domain_id = args.domain_id.unwrap_or_else(default_domain_id);
    let control = match station.control.mode {
        ::station::ControlMode::Rate => {
            format!("{} Hz control ticks", station.control.rate_hz)
        }
        ::station::ControlMode::OnArrival => "commands on frame arrival".to_string(),
    };
    let physics = physics_task(&args)?;
    if !args.json {
        let robot = match &physics {
            Some(p) => format!(
                "simulated ORCA hand + arm in the {} scene (MuJoCo)",
                p.task.id
            ),
            None => "mock ORCA hand + mock Franka".to_string(),
        };
        eprintln!(
            "pomdar demo: simulated glove ({}, {} Hz) → station → {robot}, loopback DDS, domain {domain_id}, {} s",
            glove.describe_performance(),
            glove.rate_hz,
            args.duration
        );
    }
    let view = args.view.start().await?;
    if let Some(view) = &view {
        eprintln!("{}", view.announcement());
    }
    let outcome = run_demo(DemoOptions {
        duration_s: args.duration,
        domain_id,
        station,
        glove,
        live: !args.json,
        out: args.out.clone(),
        tap: view.as_ref().map(|v| v.tap.clone()),
        physics,
    })
    .await;
    if let Some(view) = view {
        view.stop().await;
    }
    let outcome = outcome?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&outcome.summary)?);
    } else {
        crate::demo::summary_text::print_summary(
            &outcome.summary,
            outcome.recorded.as_deref(),
            &control,
        );
    }
    Ok(())
}

/// `--physics`: the task from the catalog, and the scene.
fn physics_task(args: &DemoArgs) -> anyhow::Result<Option<PhysicsTask>> {
    if !args.physics {
        return Ok(None);
    }
    if cfg!(not(feature = "physics")) {
        return Err(crate::demo::DemoError::NoPhysics.into());
    }
    let inputs = ScoringInputs::load(args.catalog.as_deref(), None, None)?;
    let task = inputs.catalog.get(&args.task).cloned().ok_or_else(|| {
        anyhow::anyhow!(
            "--task {}: no such task in the catalog (known: {})",
            args.task,
            inputs.catalog.ids()
        )
    })?;
    Ok(Some(PhysicsTask {
        task,
        scene: args.scene.clone(),
        record_states: false,
    }))
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::*;

    #[derive(Debug, Parser)]
    struct Cli {
        #[command(flatten)]
        args: DemoArgs,
    }

    #[test]
    fn a_glove_script_replaces_the_motion_and_conflicts_with_naming_one() {
        use clap::CommandFactory as _;
        Cli::command().debug_assert();
        let args = Cli::try_parse_from(["pomdar"]).unwrap().args;
        assert_eq!(
            (args.motion, args.glove_script),
            (MotionArg::TaskLike, None)
        );
        let argv = ["pomdar", "--glove-script", "grasp_place.toml"];
        let args = Cli::try_parse_from(argv).unwrap().args;
        assert_eq!(args.glove_script, Some(PathBuf::from("grasp_place.toml")));
        let both = ["pomdar", "--glove-script", "g.toml", "--motion", "pinches"];
        assert!(Cli::try_parse_from(both).is_err());
    }
}
