//! `pomdar demo`: the whole pipeline on loopback DDS in one process — simulated glove →
//! station → mock ORCA hand and mock Franka — each on its own DDS participant, on the demo's
//! own domain id, with a live status line and a summary.

use std::collections::BTreeMap;
use std::time::Duration;

use retarget::HandModel;
use serde::Serialize;
use tokio::sync::{mpsc, watch};
use tokio::task::JoinHandle;

use crate::clock::StationClock;
pub mod robot;
pub mod summary_text;

use crate::device_thread::spawn_device;
use crate::ros::NetworkConfig;
use crate::stand_ins::SimError;
use crate::stand_ins::mock_franka::MockFrankaReport;
use crate::stand_ins::mock_hand::MockHandReport;
use crate::stand_ins::sim_glove_node::{SimGloveConfig, SimGloveReport, run_sim_glove};
use crate::station_driver::setup::SetupError;
use crate::station_driver::{Engage, constrain_for_task, set_engage};
use crate::station_node::NodeError;
use crate::station_node::operator::StationHooks;
use crate::station_node::recorder::RecordingOptions;
use crate::station_node::ros_node::{OperatorCommand, StationSummary, run_station_observed};
use crate::station_node::tap::Tap;
use robot::{DemoRobot, RobotReports};
pub use robot::{PhysicsOutcome, PhysicsTask};
use station::arm::Constraint;
use station::{InputGap, StationConfig};

/// A demo that cannot start, or a node of it that failed.
#[derive(Debug, thiserror::Error)]
pub enum DemoError {
    /// The station configuration is not valid.
    #[error(transparent)]
    Config(#[from] station::ConfigError),
    /// The calibration profile cannot be loaded.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// The recording directory cannot be created.
    #[error("cannot create {path}: {source}")]
    CreateDir {
        /// The directory.
        path: std::path::PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The glove, the mock hand or the mock Franka failed.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// The station failed.
    #[error(transparent)]
    Station(#[from] NodeError),
    /// The simulated task cannot be loaded or its robot failed.
    #[cfg(feature = "physics")]
    #[error(transparent)]
    Physics(#[from] crate::physics::error::PhysicsError),
    /// `--physics` asked of a build without the simulator.
    #[error(
        "this pomdar was built without the simulator: run `bash sim/setup_mujoco.sh` once, then build with `--features physics`"
    )]
    NoPhysics,
    /// A node's task panicked or was cancelled.
    #[error("{task}: {source}")]
    Task {
        /// Which node (`glove task`, `station task`, ...).
        task: &'static str,
        /// The runtime's error.
        #[source]
        source: tokio::task::JoinError,
    },
}

/// Options of a demo run.
#[derive(Debug, Clone)]
pub struct DemoOptions {
    /// How long the glove plays, seconds.
    pub duration_s: f64,
    /// DDS domain id of the demo (never the lab's by default).
    pub domain_id: u16,
    /// The station configuration (the demo engages automatically and stays on loopback).
    pub station: StationConfig,
    /// The simulated glove.
    pub glove: SimGloveConfig,
    /// Print a status line every second.
    pub live: bool,
    /// Record the station's run to `DIR/demo-<unix seconds>.mcap`.
    pub out: Option<std::path::PathBuf>,
    /// A copy of what the station sends, for the live view (`--view`).
    pub tap: Option<Tap>,
    /// Drive the simulated robot in this task's MuJoCo scene instead of the mock robot.
    pub physics: Option<PhysicsTask>,
}

/// The machine-readable summary (`--json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DemoSummary {
    /// Seconds the run took, from the nodes' start to their stop.
    pub duration_s: f64,
    /// Seconds between the glove's first and last frame.
    pub glove_sending_s: f64,
    /// DDS domain id used.
    pub domain_id: u16,
    /// Glove frames published per second while the glove sent (from its first frame to its
    /// last: the wait for discovery before and the shutdown after are not counted).
    pub input_rate_hz: f64,
    /// Joint targets received by the mock hand per second over the same span.
    pub output_rate_hz: f64,
    /// Glove publish → joint target received, milliseconds.
    pub latency_ms_p50: Option<f64>,
    /// Glove publish → joint target received, milliseconds.
    pub latency_ms_p99: Option<f64>,
    /// Station control step (retargeting a new frame), milliseconds.
    pub solver_ms_p50: Option<f64>,
    /// Station control step (retargeting a new frame), milliseconds.
    pub solver_ms_p99: Option<f64>,
    /// Frames rejected by the station, all reasons.
    pub rejected_frames: u64,
    /// Mean palm-to-fingertip key-vector error, millimetres (uncalibrated).
    pub fingertip_error_mm: Option<f64>,
    /// Arm targets received by the mock Franka.
    pub arm_targets: u64,
    /// Joint targets received by the mock hand.
    pub hand_targets: u64,
    /// Glove frames published.
    pub frames_published: u64,
    /// Frames the station took as new.
    pub frames_new: u64,
    /// Frames the station recognised as repeats.
    pub frames_repeated: u64,
    /// The longest gap between new glove frames at the station, as received and as sent
    /// (`None` before two frames): a received gap under the watchdog's hold timeout means
    /// nothing was held while the glove played.
    pub longest_input_gap: Option<InputGap>,
    /// Hand commands held (the glove input stale), including those after the glove stopped.
    pub held_commands: u64,
    /// Messages left out of the log because the disk fell behind (`--out`).
    pub log_dropped: u64,
    /// What the physics measured (`--physics`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub physics: Option<PhysicsOutcome>,
}

/// Everything a demo run produced: the summary and the mock robots' full reports.
#[derive(Debug, Clone)]
pub struct DemoOutcome {
    /// The summary.
    pub summary: DemoSummary,
    /// What the mock hand received.
    pub hand: MockHandReport,
    /// What the mock Franka received.
    pub arm: MockFrankaReport,
    /// What the simulated glove published.
    pub glove: SimGloveReport,
    /// The log written, with `out`.
    pub recorded: Option<std::path::PathBuf>,
    /// What the physics measured (`--physics`).
    pub physics: Option<PhysicsOutcome>,
}

/// Run the demo.
pub async fn run_demo(options: DemoOptions) -> Result<DemoOutcome, DemoError> {
    let clock = StationClock::new();
    let network = loopback_network(options.domain_id);
    let station = demo_station_config(&options.station, &network, options.physics.as_ref())?;
    let model = HandModel::orca_v1_right();
    // A bad calibration profile stops the demo before any node starts.
    if let Some(path) = &station.calibration_profile {
        crate::station_driver::setup::load_profile(path, &model, station.retarget.layout)?;
    }
    let nodes = DemoNodes::start(&options, &station, model, network, clock)?;

    let start_ns = clock.now_ns();
    nodes
        .play_glove(options.duration_s, options.live, clock, start_ns)
        .await;
    let stopped = nodes.stop().await?;
    let elapsed = seconds_since(clock, start_ns);
    let RobotReports { hand, arm, physics } = stopped.robot;
    let mut summary = demo_summary(
        &options,
        elapsed,
        &stopped.glove,
        &stopped.station,
        &hand,
        &arm,
    );
    summary.physics = physics.clone();
    Ok(DemoOutcome {
        recorded: stopped.station.recorded.first().cloned(),
        summary,
        hand,
        arm,
        glove: stopped.glove,
        physics,
    })
}

/// The demo's network: its own domain id, loopback only.
fn loopback_network(domain_id: u16) -> NetworkConfig {
    NetworkConfig {
        domain_id: Some(domain_id),
        interfaces: vec![std::net::IpAddr::from([127, 0, 0, 1])],
    }
}

/// The given station configuration on the demo's `network`, engaging by itself, the arm
/// constrained as the simulated task says (else a `Fixed` constraint made `Free`); validated.
fn demo_station_config(
    configured: &StationConfig,
    network: &NetworkConfig,
    physics: Option<&PhysicsTask>,
) -> Result<StationConfig, DemoError> {
    let mut station = configured.clone();
    station.network = network.clone();
    set_engage(&mut station, Engage::OnFirstFrame);
    if let Some(physics) = physics {
        constrain_for_task(&mut station, &physics.task);
    } else if station.arm.constraint == Constraint::Fixed {
        station.arm.constraint = Constraint::Free;
    }
    station.validate()?;
    Ok(station)
}

/// With `out`, where and with which metadata the station records the run: `out` is created
/// and the log named after the current second.
fn demo_recording(
    out: Option<&std::path::Path>,
    clock: StationClock,
) -> Result<Option<RecordingOptions>, DemoError> {
    let Some(dir) = out else {
        return Ok(None);
    };
    std::fs::create_dir_all(dir).map_err(|source| DemoError::CreateDir {
        path: dir.to_path_buf(),
        source,
    })?;
    Ok(Some(RecordingOptions {
        path: dir.join(format!("demo-{}.mcap", clock.now_ns() / 1_000_000_000)),
        metadata: BTreeMap::from([
            ("source".to_string(), "pomdar demo".to_string()),
            ("task".to_string(), "demo".to_string()),
            ("user".to_string(), "simulated glove".to_string()),
            // The log starts with the station, before the glove's first status names it.
            ("keypoint_source".to_string(), "simulated".to_string()),
            (
                "keypoint_device".to_string(),
                "pomdar demo's simulated glove".to_string(),
            ),
            ("operator".to_string(), "pomdar demo".to_string()),
            ("calibration_profile".to_string(), "none".to_string()),
            ("trial_index".to_string(), "0".to_string()),
            ("practice".to_string(), "false".to_string()),
        ]),
    }))
}

/// The demo's running nodes, each with the switch that stops it.
struct DemoNodes {
    robot: DemoRobot,
    robot_stop: watch::Sender<bool>,
    station: JoinHandle<Result<StationSummary, NodeError>>,
    station_shutdown: watch::Sender<bool>,
    /// Held for the whole run, so that the station's operator channel stays open.
    _operator: mpsc::UnboundedSender<OperatorCommand>,
    glove: JoinHandle<Result<SimGloveReport, SimError>>,
    glove_stop: watch::Sender<bool>,
}

/// What the stopped nodes left.
struct StoppedNodes {
    /// What the glove published.
    glove: SimGloveReport,
    /// The station's run.
    station: StationSummary,
    /// What the robot saw.
    robot: RobotReports,
}

impl DemoNodes {
    /// Starts the mock robot, then the station (recording with `options.out`), then the glove.
    fn start(
        options: &DemoOptions,
        station: &StationConfig,
        model: HandModel,
        network: NetworkConfig,
        clock: StationClock,
    ) -> Result<DemoNodes, DemoError> {
        let (station_shutdown, shutdown_rx) = watch::channel(false);
        let (operator, operator_rx) = mpsc::unbounded_channel();

        // The robot stops after the station, so it hears every command the station sent.
        let (robot_stop, robot_stop_rx) = watch::channel(false);
        let robot = DemoRobot::spawn(
            station,
            &model,
            clock,
            &robot_stop_rx,
            options.physics.as_ref(),
        )?;
        let recording = demo_recording(options.out.as_deref(), clock)?;
        let hooks = StationHooks {
            tap: options.tap.clone(),
            ..StationHooks::default()
        };
        let station = tokio::spawn(run_station_observed(
            station.clone(),
            model,
            clock,
            shutdown_rx,
            operator_rx,
            recording,
            hooks,
        ));
        let (glove_stop, glove_stop_rx) = watch::channel(false);
        // On a thread of its own, as a real glove is a machine of its own (`device_thread`).
        let glove = spawn_device(
            "simulated-glove",
            run_sim_glove(options.glove.clone(), network, clock, glove_stop_rx),
        )?;
        Ok(DemoNodes {
            robot,
            robot_stop,
            station,
            station_shutdown,
            _operator: operator,
            glove,
            glove_stop,
        })
    }

    /// Waits until the glove has played `duration_s` from `start_ns`; with `live`, prints a
    /// status line every second.
    async fn play_glove(&self, duration_s: f64, live: bool, clock: StationClock, start_ns: i64) {
        let mut seconds = 0u64;
        while seconds_since(clock, start_ns) < duration_s {
            tokio::time::sleep(Duration::from_millis(200)).await;
            let elapsed = seconds_since(clock, start_ns);
            if live && elapsed as u64 > seconds {
                seconds = elapsed as u64;
                self.print_status_line(seconds, clock);
            }
        }
    }

    /// The live status line: the robot's view of the last second.
    fn print_status_line(&self, seconds: u64, clock: StationClock) {
        eprintln!("[{seconds:>3} s] {}", self.robot.status(clock));
    }

    /// Stops the glove first and lets its last frames arrive, then the station, then the
    /// robot once it has heard every target the station sent (at most [`ROBOT_HEAR_WAIT`]), so
    /// that each hears everything the one before it sent.
    async fn stop(self) -> Result<StoppedNodes, DemoError> {
        self.glove_stop.send(true).ok();
        let glove = join("glove task", self.glove).await?;
        tokio::time::sleep(Duration::from_millis(200)).await;
        self.station_shutdown.send(true).ok();
        let station = join("station task", self.station).await?;
        let sent = (station.totals.hand_commands, station.totals.arm_targets);
        self.robot.wait_to_hear(sent, ROBOT_HEAR_WAIT).await;
        self.robot_stop.send(true).ok();
        let robot = self.robot.finish().await?;
        Ok(StoppedNodes {
            glove,
            station,
            robot,
        })
    }
}

/// Longest wait, once the station has stopped, for the robot to hear what it sent last.
const ROBOT_HEAR_WAIT: Duration = Duration::from_secs(2);

/// The result of the node task `task`, its panic or cancellation a [`DemoError::Task`].
pub(crate) async fn join<T, E>(
    task: &'static str,
    handle: JoinHandle<Result<T, E>>,
) -> Result<T, DemoError>
where
    DemoError: From<E>,
{
    let result = handle
        .await
        .map_err(|source| DemoError::Task { task, source })?;
    Ok(result?)
}

/// Seconds on `clock` since `start_ns`.
fn seconds_since(clock: StationClock, start_ns: i64) -> f64 {
    (clock.now_ns() - start_ns) as f64 * 1e-9
}

/// Joint targets the mock hand received between the glove's first and last frame, per second
/// of that span.
fn targets_per_second_while_sending(glove: &SimGloveReport, hand: &MockHandReport) -> f64 {
    let Some((first, last)) = glove.sending_ns.filter(|(first, last)| last > first) else {
        return 0.0;
    };
    let received = hand
        .receive_times_ns
        .iter()
        .filter(|&&t| (first..=last).contains(&t))
        .count();
    received as f64 / ((last - first) as f64 * 1e-9)
}

/// The summary of a run that lasted `elapsed` seconds.
fn demo_summary(
    options: &DemoOptions,
    elapsed: f64,
    glove: &SimGloveReport,
    station: &StationSummary,
    hand_report: &MockHandReport,
    arm_report: &MockFrankaReport,
) -> DemoSummary {
    DemoSummary {
        duration_s: elapsed,
        glove_sending_s: glove.sending_span_s(),
        domain_id: options.domain_id,
        input_rate_hz: glove.sending_rate_hz().unwrap_or(0.0),
        output_rate_hz: targets_per_second_while_sending(glove, hand_report),
        latency_ms_p50: hand_report.latency.percentile(0.5),
        latency_ms_p99: hand_report.latency.percentile(0.99),
        solver_ms_p50: station.step_time.percentile(0.5),
        solver_ms_p99: station.step_time.percentile(0.99),
        rejected_frames: station.counters.rejected.values().sum(),
        fingertip_error_mm: station.tip_error_mm.mean(),
        arm_targets: arm_report.commands,
        hand_targets: hand_report.targets,
        frames_published: glove.frames,
        frames_new: station.counters.frames_new,
        frames_repeated: station.counters.frames_repeated,
        longest_input_gap: station.longest_input_gap,
        held_commands: station.totals.held_commands,
        log_dropped: station.faults.log_dropped,
        physics: None,
    }
}
