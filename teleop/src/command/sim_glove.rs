//! `pomdar sim-glove`: the simulated glove node.

use clap::Args;
use retarget::human_hand::MotionKind;

use super::shared_args::{MotionArg, NodeArgs, ctrl_c_shutdown};
use crate::clock::StationClock;
use crate::ros::NetworkConfig;
use crate::stand_ins::glove_script_file::load_glove_script;
use crate::stand_ins::sim_glove_node::{SimGloveConfig, run_sim_glove};

/// Publish simulated glove keypoints and wrist pose (the lab's topics) until Ctrl-C.
#[derive(Debug, Args)]
pub struct SimGloveArgs {
    /// Scripted motion (periodic, the wrist in place).
    #[arg(long, value_enum, default_value = "task-like")]
    pub motion: MotionArg,
    /// Instead of --motion, play this task script (TOML keyframes of the wrist's offset from
    /// its start, glove frame, and the hand's pose, e.g. launch_configs/sim/grasp_place.toml)
    /// once from the first subscriber, then keep publishing its last keyframe.
    #[arg(long, value_name = "FILE", conflicts_with = "motion")]
    pub glove_script: Option<std::path::PathBuf>,
    /// Publishing rate, Hz.
    #[arg(long, default_value_t = 100.0)]
    pub rate_hz: f64,
    /// Hand size relative to an average adult hand (0.8–1.25 realistic).
    #[arg(long, default_value_t = 1.0)]
    pub hand_scale: f64,
    /// Keypoint noise, standard deviation per axis, metres.
    #[arg(long, default_value_t = 0.001)]
    pub jitter_m: f64,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
}

/// `pomdar sim-glove`.
pub async fn sim_glove(args: SimGloveArgs) -> anyhow::Result<()> {
    let config = SimGloveConfig {
        motion: args.motion.into(),
        period_s: MotionKind::from(args.motion).default_period_s(),
        rate_hz: args.rate_hz,
        hand_scale: args.hand_scale,
        jitter_m: args.jitter_m,
        script: args
            .glove_script
            .as_deref()
            .map(load_glove_script)
            .transpose()?,
        ..SimGloveConfig::default()
    };
    let report = run_sim_glove(
        config,
        args.node.network(&NetworkConfig::default()),
        StationClock::new(),
        ctrl_c_shutdown(),
    )
    .await?;
    eprintln!("published {} frames", report.frames);
    if report.not_published() > 0 {
        eprintln!(
            "warning: {} messages not published (by topic: {:?})",
            report.not_published(),
            report.publish_failed
        );
    }
    Ok(())
}
