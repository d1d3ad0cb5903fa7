//! The node subcommands of `pomdar` (argument parsing is clap's; the work is in the modules).

use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use anyhow::Context as _;
use clap::Args;
use retarget::HandModel;
use retarget::human_hand::MotionKind;
use tokio::sync::{mpsc, watch};

use crate::clock::StationClock;
use crate::demo::{DemoOptions, default_domain_id, run_demo};
use crate::ros::NetworkConfig;
use crate::sim::mock_franka::{MockFrankaConfig, MockFrankaReport, run_mock_franka};
use crate::sim::mock_hand::{MockHandConfig, MockHandReport, run_mock_hand};
use crate::sim::sim_glove_node::{SimGloveConfig, run_sim_glove};
use crate::station_node::ros_node::{OperatorCommand, run_station};
use crate::station_setup::load_station_config;

/// `pomdar demo` options.
#[derive(Debug, Args)]
pub struct DemoArgs {
    /// How long the simulated glove plays, seconds.
    #[arg(long, default_value_t = 20.0)]
    pub duration: f64,
    /// Print only a JSON summary on stdout (no live status).
    #[arg(long)]
    pub json: bool,
    /// ROS domain id for the demo (default: 150–229, from the process id).
    #[arg(long)]
    pub domain_id: Option<u16>,
    /// Station configuration (default: the ETH lab preset built in).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Scripted glove motion.
    #[arg(long, value_enum, default_value = "task-like")]
    pub motion: MotionArg,
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
}

/// The glove's scripted motions.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum MotionArg {
    /// Open hand to fist and back.
    OpenClose,
    /// The four thumb–finger pinches in turn.
    Pinches,
    /// Fingers spread and closed.
    Abduction,
    /// Grasp, release, pinches.
    TaskLike,
}

impl From<MotionArg> for MotionKind {
    fn from(m: MotionArg) -> MotionKind {
        match m {
            MotionArg::OpenClose => MotionKind::OpenClose,
            MotionArg::Pinches => MotionKind::Pinches,
            MotionArg::Abduction => MotionKind::Abduction,
            MotionArg::TaskLike => MotionKind::TaskLike,
        }
    }
}

/// Options shared by the node commands.
#[derive(Debug, Args)]
pub struct NodeArgs {
    /// ROS domain id, 0–232 (default: the config's, else ROS_DOMAIN_ID, else 0).
    #[arg(long)]
    pub domain_id: Option<u16>,
    /// Use this address of this host for DDS (repeatable): discovery multicast is joined and
    /// sent on its interface and only it is announced to other hosts, e.g. 127.0.0.1 or the
    /// lab-network address (docs/DEPLOYMENT.md). An address this host lacks is refused.
    #[arg(long = "interface", value_name = "ADDRESS")]
    pub interfaces: Vec<std::net::IpAddr>,
}

impl NodeArgs {
    pub(crate) fn network(&self, base: &NetworkConfig) -> NetworkConfig {
        NetworkConfig {
            domain_id: self.domain_id.or(base.domain_id),
            interfaces: if self.interfaces.is_empty() {
                base.interfaces.clone()
            } else {
                self.interfaces.clone()
            },
        }
    }
}

/// `pomdar station` options.
#[derive(Debug, Args)]
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
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
}

/// `pomdar sim-glove` options.
#[derive(Debug, Args)]
pub struct SimGloveArgs {
    /// Scripted motion.
    #[arg(long, value_enum, default_value = "task-like")]
    pub motion: MotionArg,
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

/// `pomdar mock-hand` options.
#[derive(Debug, Args)]
pub struct MockHandArgs {
    /// Joint target topic.
    #[arg(long, default_value = "/pomdar/hand/joint_targets")]
    pub targets_topic: String,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
}

/// `pomdar mock-franka` options.
#[derive(Debug, Args)]
pub struct MockFrankaArgs {
    /// Pose command topic.
    #[arg(long, default_value = "/franka/end_effector_pose_cmd")]
    pub command_topic: String,
    /// Pose feedback topic.
    #[arg(long, default_value = "/franka/end_effector_pose")]
    pub pose_topic: String,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
}

/// Run an async command on a two-worker runtime.
pub fn run_async<T>(future: impl Future<Output = anyhow::Result<T>>) -> anyhow::Result<T> {
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .context("cannot start the async runtime")?
        .block_on(future)
}

/// A shutdown signal that turns true on Ctrl-C.
pub(crate) fn ctrl_c_shutdown() -> watch::Receiver<bool> {
    let (tx, rx) = watch::channel(false);
    tokio::spawn(async move {
        if tokio::signal::ctrl_c().await.is_ok() {
            tx.send(true).ok();
        }
    });
    rx
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
    if !args.json {
        eprintln!(
            "pomdar demo: simulated glove ({:?}, {} Hz) → station → mock ORCA hand + mock Franka, loopback DDS, domain {domain_id}, {} s",
            glove.motion, glove.rate_hz, args.duration
        );
    }
    let outcome = run_demo(DemoOptions {
        duration_s: args.duration,
        domain_id,
        station,
        glove,
        live: !args.json,
        out: args.out.clone(),
    })
    .await?;
    let recorded = outcome.recorded.clone();
    let summary = outcome.summary;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        let ms = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.2} ms"));
        println!("summary over {:.1} s:", summary.duration_s);
        println!("  glove frames       {:.1} /s", summary.input_rate_hz);
        println!(
            "  joint targets      {:.1} /s ({} received)",
            summary.output_rate_hz, summary.hand_targets
        );
        println!("  arm targets        {}", summary.arm_targets);
        println!(
            "  end-to-end latency p50 {}, p99 {} (glove publish → joint target received, {control})",
            ms(summary.latency_ms_p50),
            ms(summary.latency_ms_p99)
        );
        println!(
            "  control step       p50 {}, p99 {}",
            ms(summary.solver_ms_p50),
            ms(summary.solver_ms_p99)
        );
        println!("  rejected frames    {}", summary.rejected_frames);
        if let Some(path) = &recorded {
            println!("  recorded           {}", path.display());
        }
        println!(
            "  fingertip error    {} (palm-to-tip key vectors, uncalibrated)",
            summary
                .fingertip_error_mm
                .map_or("-".into(), |v| format!("{v:.1} mm"))
        );
    }
    Ok(())
}

/// `pomdar station`.
pub async fn station(args: StationArgs) -> anyhow::Result<()> {
    let mut config = load_station_config(Some(&args.config), args.profile.as_deref())?;
    config.network = args.node.network(&config.network);
    config.control.auto_engage |= args.engage;
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
    let summary = run_station(
        config,
        HandModel::orca_v1_right(),
        StationClock::new(),
        shutdown,
        rx,
        recording,
    )
    .await?;
    eprintln!(
        "stopped: {} new frames, {} hand commands, {} arm targets, rejected {:?}",
        summary.counters.frames_new,
        summary.totals.hand_commands,
        summary.totals.arm_targets,
        summary.counters.rejected
    );
    Ok(())
}

/// `pomdar sim-glove`.
pub async fn sim_glove(args: SimGloveArgs) -> anyhow::Result<()> {
    let config = SimGloveConfig {
        motion: args.motion.into(),
        period_s: MotionKind::from(args.motion).default_period_s(),
        rate_hz: args.rate_hz,
        hand_scale: args.hand_scale,
        jitter_m: args.jitter_m,
        ..SimGloveConfig::default()
    };
    let frames = run_sim_glove(
        config,
        args.node.network(&NetworkConfig::default()),
        StationClock::new(),
        ctrl_c_shutdown(),
    )
    .await?;
    eprintln!("published {frames} frames");
    Ok(())
}

/// `pomdar mock-hand`.
pub async fn mock_hand(args: MockHandArgs) -> anyhow::Result<()> {
    let report = Arc::new(Mutex::new(MockHandReport::default()));
    let config = MockHandConfig {
        targets_topic: args.targets_topic,
        ..MockHandConfig::default()
    };
    run_mock_hand(
        HandModel::orca_v1_right(),
        config,
        args.node.network(&NetworkConfig::default()),
        StationClock::new(),
        report.clone(),
        ctrl_c_shutdown(),
    )
    .await?;
    if let Ok(r) = report.lock() {
        eprintln!(
            "received {} targets, latency p50 {:?} ms",
            r.targets,
            r.latency.percentile(0.5)
        );
    }
    Ok(())
}

/// `pomdar mock-franka`.
pub async fn mock_franka(args: MockFrankaArgs) -> anyhow::Result<()> {
    let report = Arc::new(Mutex::new(MockFrankaReport::default()));
    let start = ::station::StationConfig::default()
        .arm
        .start_pose_isometry()
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let config = MockFrankaConfig {
        command_topic: args.command_topic,
        pose_topic: args.pose_topic,
        start,
        max_speed_m_s: 0.5,
        max_rate_rad_s: 1.0,
        rate_hz: 100.0,
    };
    run_mock_franka(
        config,
        args.node.network(&NetworkConfig::default()),
        StationClock::new(),
        report.clone(),
        ctrl_c_shutdown(),
    )
    .await?;
    if let Ok(r) = report.lock() {
        eprintln!("received {} commands ({} rejected)", r.commands, r.rejected);
    }
    Ok(())
}

/// `pomdar resim` options.
#[derive(Debug, Args)]
pub struct ResimArgs {
    /// The recorded log (MCAP) whose glove input is re-simulated.
    pub input: PathBuf,
    /// Station configuration (default: the built-in ETH lab preset).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Output log (MCAP) for the station's outputs.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Write the statistics as JSON to this file.
    #[arg(long, value_name = "FILE")]
    pub stats_json: Option<PathBuf>,
    /// Replace an existing output file.
    #[arg(long)]
    pub overwrite: bool,
    /// The user's calibration profile (TOML written by `pomdar calibrate`); overrides the
    /// configuration's `calibration_profile`. Default: the configuration's, else none
    /// (identity: scale 1, no rotation).
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
}

/// `pomdar resim`.
pub fn resim(args: ResimArgs) -> anyhow::Result<()> {
    use crate::mcap_log::{TrialReader, TrialWriter, TrialWriterOptions};
    let config = load_station_config(args.config.as_deref(), args.profile.as_deref())?;
    let reader = TrialReader::open(&args.input)?;
    let options = TrialWriterOptions {
        overwrite: args.overwrite,
        ..TrialWriterOptions::default()
    };
    let mut writer = TrialWriter::create(&args.out, options)?;
    let stats = crate::resim::resim(&reader, &config, HandModel::orca_v1_right(), &mut writer)?;
    writer.finish()?;
    let json = serde_json::to_string_pretty(&stats)?;
    if let Some(path) = &args.stats_json {
        std::fs::write(path, &json).with_context(|| format!("cannot write {}", path.display()))?;
    }
    let ms = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.3}"));
    if let Some(profile) = &stats.profile {
        eprintln!("{profile}");
    }
    eprintln!(
        "re-simulated {}: {} frames ({} new, {} repeated, rejected {:?}), {} joint targets, layout {}, control step p50 {} ms, p99 {} ms → {}",
        args.input.display(),
        stats.frames_read,
        stats.frames_new,
        stats.frames_repeated,
        stats.rejected,
        stats.joint_targets,
        stats.layout,
        ms(stats.step_ms_p50),
        ms(stats.step_ms_p99),
        args.out.display()
    );
    Ok(())
}

/// `pomdar recover` options.
#[derive(Debug, Args)]
pub struct RecoverArgs {
    /// The interrupted log (`NAME.mcap.part`).
    pub part: PathBuf,
    /// Where to write the repaired log (default: the name without `.part`).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

/// `pomdar recover`.
pub fn recover(args: RecoverArgs) -> anyhow::Result<()> {
    let out = match args.out {
        Some(out) => out,
        None => {
            let name = args.part.to_string_lossy();
            let Some(stem) = name.strip_suffix(".part") else {
                anyhow::bail!("{} does not end in .part: give --out", args.part.display());
            };
            PathBuf::from(stem)
        }
    };
    let report = crate::mcap_log::recover(&args.part, &out)?;
    println!("{report}");
    Ok(())
}

/// `pomdar replay` options.
#[derive(Debug, Args)]
pub struct ReplayArgs {
    /// The log (MCAP) to republish.
    pub input: PathBuf,
    /// Speed factor (1 = original timing).
    #[arg(long, default_value_t = 1.0)]
    pub rate: f64,
    /// Topics to republish (default: every topic of a supported type).
    #[arg(long, value_delimiter = ',')]
    pub topics: Vec<String>,
    /// Start again at the end.
    #[arg(long = "loop")]
    pub looped: bool,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
}

/// `pomdar replay`.
pub async fn replay(args: ReplayArgs) -> anyhow::Result<()> {
    let reader = crate::mcap_log::TrialReader::open(&args.input)?;
    let options = crate::replay::ReplayOptions {
        rate: args.rate,
        topics: args.topics,
        looped: args.looped,
        ..crate::replay::ReplayOptions::default()
    };
    let report = crate::replay::replay(
        &reader,
        &args.node.network(&NetworkConfig::default()),
        &options,
        ctrl_c_shutdown(),
    )
    .await?;
    eprintln!(
        "replayed {:?} ({} passes); skipped {:?}",
        report.published, report.passes, report.skipped
    );
    Ok(())
}
