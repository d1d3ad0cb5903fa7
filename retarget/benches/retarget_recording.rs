//! Benchmark: per-frame retargeting time over the reference glove recording.
//!
//! `cargo bench -p retarget --bench retarget_recording` replays every distinct `/ingress/mano`
//! frame of `../shared/reference/rokoko_orca_2024-11-20.mcap` through the default
//! configuration (Orca_full, 22-point layout) five times, with the recording's own time steps,
//! and prints one JSON line per QP method (`active_set`, the default, then `clarabel`):
//! per-frame wall time p50/p99/max in microseconds, and the mean number of Gauss–Newton steps
//! and of Clarabel interior-point iterations per frame.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a benchmark fails loudly

#[path = "../tests/suite/common/recording.rs"]
mod recording;

use std::hint::black_box;
use std::path::PathBuf;
use std::time::Instant;

use retarget::{EmbodimentCatalog, HandModel, QpMethod, RetargetConfig, Retargeter};

const PASSES: usize = 5;

fn main() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/reference")
        .join(recording::RECORDING);
    if !path.is_file() {
        eprintln!("SKIPPED: {} not found", path.display());
        return;
    }
    let (frames, _) = recording::distinct_mano_frames(&path);
    for (name, method) in [
        ("active_set", QpMethod::ActiveSet),
        ("clarabel", QpMethod::Clarabel),
    ] {
        run(&frames, name, method);
    }
}

fn run(frames: &[recording::Frame], name: &str, method: QpMethod) {
    let mut config = RetargetConfig::default();
    config.solver.qp_method = method;
    let mut retargeter = Retargeter::new(
        HandModel::orca_v1_right(),
        config,
        &EmbodimentCatalog::builtin(),
    )
    .unwrap();
    let mut times_us = Vec::with_capacity(PASSES * frames.len());
    let (mut steps, mut qp_iterations) = (0u64, 0u64);
    for _ in 0..PASSES {
        retargeter.reset();
        let mut previous_t = None;
        for frame in frames {
            let dt = previous_t.map_or(0.04, |t| frame.t_s - t);
            previous_t = Some(frame.t_s);
            let start = Instant::now();
            let solution = retargeter.retarget(black_box(&frame.points), dt).unwrap();
            times_us.push(start.elapsed().as_secs_f64() * 1e6);
            steps += u64::from(solution.steps);
            qp_iterations += u64::from(solution.qp_iterations);
        }
    }
    let n = times_us.len();
    times_us.sort_by(f64::total_cmp);
    let pick = |p: f64| times_us[((n - 1) as f64 * p).round() as usize];
    println!(
        "{{\"bench\":\"retarget_recording\",\"qp_method\":\"{name}\",\"frames\":{},\"passes\":{PASSES},\"p50_us\":{:.1},\"p99_us\":{:.1},\"max_us\":{:.1},\"mean_steps\":{:.2},\"mean_qp_iterations\":{:.1}}}",
        frames.len(),
        pick(0.5),
        pick(0.99),
        pick(1.0),
        steps as f64 / n as f64,
        qp_iterations as f64 / n as f64
    );
}
