//! `pomdar station`: the station node.

use std::path::PathBuf;

use clap::Args;
use tokio::sync::mpsc;

use super::shared_args::{HandSourceArgs, NodeArgs, ViewArgs, ctrl_c_shutdown};
use crate::clock::StationClock;
use crate::station_driver::setup::load_station_config;
use crate::station_driver::{Engage, set_engage};
use crate::station_node::ros_node::{OperatorCommand, StationHooks, run_station_observed};

/// Run the station node (no simulated parts) until Ctrl-C.
///
/// Subscribes to the glove keypoints and wrist pose, publishes hand joint targets, the
/// lab's /hand/policy_output, the arm target and a JSON status, as the config file says
/// (launch_configs/station/*.toml). --engage engages once glove input is fresh
/// (`pomdar trial`, the operator console, runs its own station and engages on the
/// operator's key); --record logs the run (inputs, outputs, status, events) to an MCAP
/// file; --profile applies a user's calibration (from `pomdar calibrate`).
///
/// Example:
///   pomdar station --config launch_configs/station/eth_lab.toml --engage --record run.mcap --profile profiles/alice.toml
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct StationArgs {
    /// Station configuration file (launch_configs/station/*.toml).
    #[arg(long, value_name = "FILE")]
    pub config: PathBuf,
    /// Engage as soon as glove input is fresh.
    #[arg(long)]
    pub engage: bool,
    /// Record the run (inputs, outputs, status, events) to this MCAP file.
    #[arg(long, value_name = "FILE.mcap")]
    pub record: Option<PathBuf>,
    /// The user's calibration profile (TOML written by `pomdar calibrate`); overrides the
    /// configuration's `calibration_profile`. Default: the configuration's, else none
    /// (identity: scale 1, no rotation).
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// The hand (default: the built-in ORCA v1 right hand).
    #[command(flatten)]
    pub hand: HandSourceArgs,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
    /// The RTPS datagram guard.
    #[command(flatten)]
    pub guard: super::shared_args::GuardArgs,
    /// The live view.
    #[command(flatten)]
    pub view: ViewArgs,
}

/// `pomdar station`.
pub async fn station(args: StationArgs) -> anyhow::Result<()> {
    let mut config = load_station_config(Some(&args.config), args.profile.as_deref())?;
    config.network = args.node.network(&config.network);
    if args.engage {
        set_engage(&mut config, Engage::OnFirstFrame);
    }
    // Crafted DATA_FRAG datagrams must not exhaust the station's memory (docs/SECURITY.md).
    args.guard.apply();
    let shutdown = ctrl_c_shutdown();
    let (_tx, rx) = mpsc::unbounded_channel::<OperatorCommand>();
    eprintln!(
        "pomdar station: domain {}, keypoints {}, joint targets {}, arm {}; Ctrl-C stops",
        crate::ros::domain_id(config.network.domain_id)?,
        config.input.keypoints_topic,
        config.output.joint_targets_topic,
        config.output.arm_target_topic
    );
    let recording = args
        .record
        .map(|path| crate::station_node::recorder::RecordingOptions {
            path,
            metadata: std::collections::BTreeMap::from([
                ("source".to_string(), "pomdar station".to_string()),
                (
                    "calibration_profile".to_string(),
                    config
                        .calibration_profile
                        .as_ref()
                        .map_or("none".to_string(), |p| p.display().to_string()),
                ),
            ]),
        });
    let source = args.hand.source();
    let model = source.load()?;
    let view = args.view.start().await?;
    if let Some(view) = &view {
        eprintln!("{}", view.announcement());
    }
    let (status_tx, status_rx) = tokio::sync::watch::channel(None);
    let hooks = StationHooks {
        robot_description: source.robot_description()?,
        status: Some(status_tx),
        tap: view.as_ref().map(|v| v.tap.clone()),
        ..StationHooks::default()
    };
    tokio::spawn(say_what_it_waits_for(
        status_rx,
        config.input.keypoints_topic.clone(),
    ));
    let summary = run_station_observed(
        config,
        model,
        StationClock::new(),
        shutdown,
        rx,
        recording,
        hooks,
    )
    .await;
    if let Some(view) = view {
        view.stop().await;
    }
    let summary = summary?;
    eprintln!(
        "stopped: {} new frames, {} hand commands, {} arm targets, rejected {:?}",
        summary.counters.frames_new,
        summary.totals.hand_commands,
        summary.totals.arm_targets,
        summary.counters.rejected
    );
    Ok(())
}

/// Until the first glove frame arrives, say every two seconds what the station waits for (an
/// operator cannot tell a station waiting for its glove from a hung one); then say once that
/// frames arrive.
async fn say_what_it_waits_for(
    mut status: tokio::sync::watch::Receiver<Option<serde_json::Value>>,
    topic: String,
) {
    let started = std::time::Instant::now();
    let mut last_said = None::<std::time::Instant>;
    while status.changed().await.is_ok() {
        let Some(document) = status.borrow_and_update().clone() else {
            continue;
        };
        if document["input_age_ms"].is_number() {
            let rate = document["input_rate_hz"].as_f64().unwrap_or(0.0);
            eprintln!("glove frames arriving on {topic} ({rate:.1} /s)");
            return;
        }
        if last_said.is_none_or(|t| t.elapsed().as_secs_f64() >= 2.0) {
            eprintln!(
                "waiting for glove keypoints on {topic}: none for {:.0} s (is the ingress running, on this ROS_DOMAIN_ID and network?)",
                started.elapsed().as_secs_f64()
            );
            last_said = Some(std::time::Instant::now());
        }
    }
}
