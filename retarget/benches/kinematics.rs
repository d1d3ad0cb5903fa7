//! Benchmark: forward kinematics + the five fingertip Jacobians of the built-in ORCA model.
//!
//! `cargo bench -p retarget --bench kinematics` prints one JSON line per measured operation:
//! per-call time p50/p99/mean in nanoseconds over batches of calls at seeded random poses.

#[path = "../tests/suite/common/poses.rs"]
#[allow(dead_code)]
mod poses;

use std::hint::black_box;
use std::time::Instant;

use nalgebra::Matrix3xX;
use rand::{SeedableRng, rngs::StdRng};
use retarget::HandModel;

const POSES: usize = 1024;
const BATCH: usize = 1000;
const BATCHES: usize = 400;

fn main() {
    let model = HandModel::orca_v1_right();
    let mut rng = StdRng::seed_from_u64(7);
    let poses: Vec<Vec<f64>> = (0..POSES)
        .map(|_| poses::random_pose(&model, &mut rng))
        .collect();
    let mut state = model.fk_state();
    let mut jacobians = vec![Matrix3xX::zeros(model.dof()); 5];
    let tips = model.frames().tips;

    let fk = measure(&poses, |q| {
        model.forward(q, &mut state).ok();
        black_box(&state);
    });
    report("fk", &fk);

    let fk_jac = measure(&poses, |q| {
        model.forward(q, &mut state).ok();
        for (link, jacobian) in tips.iter().zip(&mut jacobians) {
            model.position_jacobian(&state, *link, jacobian).ok();
        }
        black_box(&jacobians);
    });
    report("fk_plus_5_fingertip_jacobians", &fk_jac);
}

/// Per-call nanoseconds of each batch, sorted.
fn measure(poses: &[Vec<f64>], mut call: impl FnMut(&[f64])) -> Vec<f64> {
    for q in poses.iter().cycle().take(20 * BATCH) {
        call(q); // warm-up
    }
    let mut per_call = Vec::with_capacity(BATCHES);
    let mut cycle = poses.iter().cycle();
    for _ in 0..BATCHES {
        let start = Instant::now();
        for q in cycle.by_ref().take(BATCH) {
            call(black_box(q));
        }
        per_call.push(start.elapsed().as_nanos() as f64 / BATCH as f64);
    }
    per_call.sort_by(f64::total_cmp);
    per_call
}

fn report(name: &str, sorted_ns: &[f64]) {
    let pick = |p: f64| sorted_ns[((sorted_ns.len() - 1) as f64 * p).round() as usize];
    let mean = sorted_ns.iter().sum::<f64>() / sorted_ns.len() as f64;
    println!(
        "{{\"bench\":\"{name}\",\"model\":\"orca_v1_right\",\"calls\":{},\"p50_ns\":{:.0},\"p99_ns\":{:.0},\"mean_ns\":{:.0}}}",
        sorted_ns.len() * BATCH,
        pick(0.5),
        pick(0.99),
        mean
    );
}
