//! `pomdar demo`: the whole pipeline on loopback DDS in one process — simulated glove →
//! station → mock ORCA hand and mock Franka — each on its own DDS participant, on the demo's
//! own domain id, with a live status line and a summary.

use std::collections::BTreeMap;
use std::time::Duration;

use anyhow::Context as _;
use retarget::HandModel;
use serde::Serialize;
use tokio::sync::{mpsc, watch};

use crate::clock::StationClock;
use crate::ros::NetworkConfig;
use crate::sim::mock_franka::MockFrankaReport;
use crate::sim::mock_hand::MockHandReport;
use crate::sim::mock_robot::spawn_mock_robot;
use crate::sim::sim_glove_node::{SimGloveConfig, run_sim_glove};
use crate::station_node::recorder::RecordingOptions;
use crate::station_node::ros_node::run_station;
use station::StationConfig;
use station::arm::Constraint;

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
}

/// The machine-readable summary (`--json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DemoSummary {
    /// Seconds the glove played.
    pub duration_s: f64,
    /// DDS domain id used.
    pub domain_id: u16,
    /// Glove frames published per second.
    pub input_rate_hz: f64,
    /// Joint targets received by the mock hand per second.
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
    /// The log written, with `out`.
    pub recorded: Option<std::path::PathBuf>,
}

/// Run the demo.
pub async fn run_demo(options: DemoOptions) -> anyhow::Result<DemoOutcome> {
    let clock = StationClock::new();
    let network = NetworkConfig {
        domain_id: Some(options.domain_id),
        interfaces: vec![std::net::IpAddr::from([127, 0, 0, 1])],
    };
    let mut station = options.station.clone();
    station.network = network.clone();
    station.control.auto_engage = true;
    if station.arm.constraint == Constraint::Fixed {
        station.arm.constraint = Constraint::Free;
    }
    station.validate()?;
    let model = HandModel::orca_v1_right();
    // A bad calibration profile stops the demo before any node starts.
    if let Some(path) = &station.calibration_profile {
        crate::station_setup::load_profile(path, &model, station.retarget.layout)?;
    }
    let (shutdown_tx, shutdown_rx) = watch::channel(false);
    let (_operator_tx, operator_rx) = mpsc::unbounded_channel();

    // The robot stops after the station, so it hears every command the station sent.
    let (robot_stop_tx, robot_stop_rx) = watch::channel(false);
    let robot = spawn_mock_robot(&station, &model, clock, &robot_stop_rx)?;
    let recording = match &options.out {
        Some(dir) => {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot create {}", dir.display()))?;
            Some(RecordingOptions {
                path: dir.join(format!("demo-{}.mcap", clock.now_ns() / 1_000_000_000)),
                metadata: BTreeMap::from([
                    ("source".to_string(), "pomdar demo".to_string()),
                    ("task".to_string(), "demo".to_string()),
                    ("user".to_string(), "simulated glove".to_string()),
                    ("operator".to_string(), "pomdar demo".to_string()),
                    ("calibration_profile".to_string(), "none".to_string()),
                    ("trial_index".to_string(), "0".to_string()),
                    ("practice".to_string(), "false".to_string()),
                ]),
            })
        }
        None => None,
    };
    let station_task = tokio::spawn(run_station(
        station.clone(),
        model,
        clock,
        shutdown_rx.clone(),
        operator_rx,
        recording,
    ));
    let (glove_stop_tx, glove_stop_rx) = watch::channel(false);
    let glove = tokio::spawn(run_sim_glove(
        options.glove.clone(),
        network.clone(),
        clock,
        glove_stop_rx,
    ));

    let start_ns = clock.now_ns();
    let mut seconds = 0u64;
    while (clock.now_ns() - start_ns) as f64 * 1e-9 < options.duration_s {
        tokio::time::sleep(Duration::from_millis(200)).await;
        let elapsed = (clock.now_ns() - start_ns) as f64 * 1e-9;
        if options.live && elapsed as u64 > seconds {
            seconds = elapsed as u64;
            if let Ok(report) = robot.hand_report.lock() {
                let recent = report
                    .receive_times_ns
                    .iter()
                    .filter(|&&t| clock.now_ns() - t < 1_000_000_000)
                    .count();
                eprintln!(
                    "[{seconds:>3} s] joint targets {recent:>4}/s  latency p50 {:>6} ms  p99 {:>6} ms  total {}",
                    fmt_ms(report.latency.percentile(0.5)),
                    fmt_ms(report.latency.percentile(0.99)),
                    report.targets
                );
            }
        }
    }
    // Stop the glove first and let its last frames arrive before the rest stops.
    glove_stop_tx.send(true).ok();
    let frames = glove.await.context("glove task")??;
    tokio::time::sleep(Duration::from_millis(200)).await;
    shutdown_tx.send(true).ok();
    let station_summary = station_task.await.context("station task")??;
    tokio::time::sleep(Duration::from_millis(100)).await;
    robot_stop_tx.send(true).ok();
    let summary = &station_summary;
    robot.hand.await.context("mock hand task")??;
    robot.arm.await.context("mock arm task")??;
    let elapsed = (clock.now_ns() - start_ns) as f64 * 1e-9;
    let hand_report = robot
        .hand_report
        .lock()
        .map(|r| r.clone())
        .unwrap_or_default();
    let arm_report = robot
        .arm_report
        .lock()
        .map(|r| r.clone())
        .unwrap_or_default();
    let summary = DemoSummary {
        duration_s: elapsed,
        domain_id: options.domain_id,
        input_rate_hz: frames as f64 / elapsed,
        output_rate_hz: hand_report.targets as f64 / elapsed,
        latency_ms_p50: hand_report.latency.percentile(0.5),
        latency_ms_p99: hand_report.latency.percentile(0.99),
        solver_ms_p50: summary.step_time.percentile(0.5),
        solver_ms_p99: summary.step_time.percentile(0.99),
        rejected_frames: summary.counters.rejected.values().sum(),
        fingertip_error_mm: summary.tip_error_mm.mean(),
        arm_targets: arm_report.commands,
        hand_targets: hand_report.targets,
        frames_published: frames,
        frames_new: summary.counters.frames_new,
        frames_repeated: summary.counters.frames_repeated,
    };
    Ok(DemoOutcome {
        recorded: station_summary.recorded.first().cloned(),
        summary,
        hand: hand_report,
        arm: arm_report,
    })
}

fn fmt_ms(value: Option<f64>) -> String {
    value.map_or("-".into(), |v| format!("{v:.2}"))
}
