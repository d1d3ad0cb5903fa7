//! Benchmark: the station over loopback DDS.
//!
//! `cargo bench -p teleop --bench station_latency` runs the demo pipeline (simulated glove →
//! station → mock hand, separate DDS participants, loopback only) twice, in every-frame mode:
//!
//! 1. glove at 100 Hz for 10 s: end-to-end latency, glove publish → joint target received,
//!    p50/p99, and the process's CPU use;
//! 2. glove at 1 kHz for 5 s: frames published vs frames the station received (drops);
//! 3. glove at 100 Hz for 10 s, recording to a trial log and not, side by side (not, with,
//!    three times): the latency the log costs, as the ratio of the p99s (budget ≤ 1.2).
//!
//! Prints one JSON line per run, and the recording ratio.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a benchmark fails loudly

use station::{ControlMode, StationConfig};
use teleop::demo::{DemoOptions, DemoSummary, run_demo};
use teleop::ros::default_domain_id;
use teleop::stand_ins::sim_glove_node::SimGloveConfig;

/// User + system CPU seconds of this process so far (Linux `/proc/self/stat`).
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let after = stat.rsplit_once(')')?.1;
    let fields: Vec<&str> = after.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0) // USER_HZ is 100 on Linux
}

/// One demo run; its summary.
fn demo(
    rate_hz: f64,
    duration_s: f64,
    domain: u16,
    out: Option<std::path::PathBuf>,
) -> DemoSummary {
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
    runtime
        .block_on(run_demo(DemoOptions {
            duration_s,
            domain_id: domain,
            station,
            glove,
            live: false,
            out,
            tap: None,
            physics: None,
        }))
        .unwrap()
        .summary
}

fn run(rate_hz: f64, duration_s: f64, domain: u16) {
    let cpu_before = cpu_seconds();
    let summary = demo(rate_hz, duration_s, domain, None);
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

/// Runs without and with a trial log, alternately.
const PAIRS: usize = 3;

/// 100 Hz for 10 s, alternately without and with a trial log, [`PAIRS`] times each: the p99
/// of each run, the ratio of the worst recording p99 to the worst plain one, and of the
/// medians (a p99 of 1,000 samples is the tenth-worst sample: one scheduling hiccup on a busy
/// machine moves it).
fn recording_cost(domain: u16) {
    let dir = std::env::temp_dir().join(format!("pomdar-bench-recording-{}", std::process::id()));
    let p99 = |out: Option<std::path::PathBuf>| {
        let recording = out.is_some();
        let summary = demo(100.0, 10.0, domain, out);
        let p99 = summary.latency_ms_p99.unwrap_or(f64::NAN);
        println!(
            "{{\"bench\":\"station_latency_recording\",\"recording\":{recording},\"latency_ms_p50\":{:.3},\"latency_ms_p99\":{p99:.3},\"log_dropped\":{}}}",
            summary.latency_ms_p50.unwrap_or(f64::NAN),
            summary.log_dropped
        );
        p99
    };
    let mut plain = Vec::new();
    let mut recorded = Vec::new();
    for _ in 0..PAIRS {
        plain.push(p99(None));
        recorded.push(p99(Some(dir.clone())));
    }
    let worst = |v: &[f64]| v.iter().copied().fold(f64::NAN, f64::max);
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    println!(
        "{{\"bench\":\"station_latency_recording_ratio\",\"p99_plain_ms\":{:.3},\"p99_recording_ms\":{:.3},\"ratio\":{:.2},\"median_p99_plain_ms\":{:.3},\"median_p99_recording_ms\":{:.3},\"median_ratio\":{:.2},\"budget\":1.2}}",
        worst(&plain),
        worst(&recorded),
        worst(&recorded) / worst(&plain),
        median(&mut plain),
        median(&mut recorded),
        median(&mut recorded) / median(&mut plain),
    );
    std::fs::remove_dir_all(&dir).ok();
}

fn main() {
    let domain = default_domain_id();
    run(100.0, 10.0, domain);
    run(1000.0, 5.0, domain);
    recording_cost(domain);
}
