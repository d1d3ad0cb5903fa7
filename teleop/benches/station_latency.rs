//! Benchmark: the station over loopback DDS.
//!
//! `cargo bench -p teleop --bench station_latency` runs the demo pipeline (simulated glove →
//! station → mock hand, separate DDS participants, loopback only) twice, in every-frame mode:
//!
//! 1. glove at 100 Hz for 10 s: end-to-end latency, glove publish → joint target received,
//!    p50/p99, and the process's CPU use;
//! 2. glove at 1 kHz for 5 s: frames published vs frames the station received (drops).
//!
//! Prints one JSON line per run.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a benchmark fails loudly

use station::{ControlMode, StationConfig};
use teleop::demo::{DemoOptions, run_demo};
use teleop::ros::default_domain_id;
use teleop::sim::sim_glove_node::SimGloveConfig;

/// User + system CPU seconds of this process so far (Linux `/proc/self/stat`).
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let after = stat.rsplit_once(')')?.1;
    let fields: Vec<&str> = after.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0) // USER_HZ is 100 on Linux
}

fn run(rate_hz: f64, duration_s: f64, domain: u16) {
    let mut station = StationConfig::default();
    station.control.mode = ControlMode::OnArrival;
    station.input.qos = teleop::ros::QosConfig::best_effort(1000);
    let glove = SimGloveConfig {
        rate_hz,
        ..SimGloveConfig::default()
    };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    let cpu_before = cpu_seconds();
    let summary = runtime
        .block_on(run_demo(DemoOptions {
            duration_s,
            domain_id: domain,
            station,
            glove,
            live: false,
            out: None,
            tap: None,
            physics: None,
        }))
        .unwrap()
        .summary;
    let cpu = cpu_seconds()
        .zip(cpu_before)
        .map(|(a, b)| (a - b) / summary.duration_s * 100.0);
    let received = summary.frames_new + summary.frames_repeated;
    println!(
        "{{\"bench\":\"station_latency\",\"glove_rate_hz\":{rate_hz},\"duration_s\":{:.1},\"frames_published\":{},\"frames_received\":{received},\"dropped\":{},\"joint_targets\":{},\"latency_ms_p50\":{:.3},\"latency_ms_p99\":{:.3},\"control_step_ms_p50\":{:.3},\"control_step_ms_p99\":{:.3},\"process_cpu_percent_of_one_core\":{:.0}}}",
        summary.duration_s,
        summary.frames_published,
        summary.frames_published.saturating_sub(received),
        summary.hand_targets,
        summary.latency_ms_p50.unwrap_or(f64::NAN),
        summary.latency_ms_p99.unwrap_or(f64::NAN),
        summary.solver_ms_p50.unwrap_or(f64::NAN),
        summary.solver_ms_p99.unwrap_or(f64::NAN),
        cpu.unwrap_or(f64::NAN),
    );
}

fn main() {
    let domain = default_domain_id();
    run(100.0, 10.0, domain);
    run(1000.0, 5.0, domain);
}
