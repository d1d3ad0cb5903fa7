//! Round trip: keypoints generated from the robot's own FK (its key vectors as human input,
//! scale 1) are retargeted back to fingertip positions the robot actually had.

use crate::common;

use nalgebra::Vector3;
use rand::{SeedableRng, rngs::StdRng};
use retarget::{EmbodimentCatalog, HandModel, KeypointLayout, RetargetConfig, Retargeter};

/// The key-vector energy alone: the pinch and separation terms deliberately depart from the
/// key vectors when fingertips are within `pinch.release_m` of each other, which random robot
/// poses often are; they have their own tests (`pinch.rs`).
fn key_vectors_only() -> RetargetConfig {
    let mut config = RetargetConfig::default();
    config.pinch.weight = 0.0;
    config.pinch.separation_weight = 0.0;
    config
}

/// Frames a pose is held for in the neutral-start test (1 s at 25 Hz).
const HOLD_FRAMES: usize = 25;

fn percentile(values: &mut [f64], p: f64) -> f64 {
    values.sort_by(f64::total_cmp);
    values[((values.len() - 1) as f64 * p).round() as usize]
}

fn random_pose(model: &HandModel, rng: &mut StdRng) -> Vec<f64> {
    let mut q = common::poses::random_pose(model, rng);
    q[model.dof_index("wrist").unwrap()] = 0.0; // not an Orca_full finger joint
    q
}

/// Worst fingertip error (metres, robot palm frame) of `q_out` against `q_true`.
fn tip_error(retargeter: &mut Retargeter, q_true: &[f64], q_out: &[f64]) -> f64 {
    let truth = retargeter.robot_tips(q_true).unwrap();
    let out = retargeter.robot_tips(q_out).unwrap();
    truth
        .iter()
        .zip(&out)
        .map(|(a, b): (&Vector3<f64>, &Vector3<f64>)| (a - b).norm())
        .fold(0.0, f64::max)
}

#[test]
fn random_reachable_poses_from_a_neutral_start_reproduce_fingertips() {
    let (model, mut retargeter) = common::poses::orca_retargeter(key_vectors_only());
    let mut rng = StdRng::seed_from_u64(3);
    let mut errors = Vec::new();
    for _ in 0..1000 {
        let q_true = random_pose(&model, &mut rng);
        let keypoints =
            model.synthetic_keypoints(&model.forward_new(&q_true).unwrap(), KeypointLayout::Lab22);
        // The operator holds the pose for one second of 25 Hz frames, with the default
        // per-frame step budget, rate limit and smoothness prior.
        retargeter.reset();
        let mut q = Vec::new();
        for _ in 0..HOLD_FRAMES {
            q = retargeter.retarget(&keypoints, 0.04).unwrap().q;
        }
        errors.push(tip_error(&mut retargeter, &q_true, &q));
    }
    let p50 = percentile(&mut errors, 0.5);
    let p95 = percentile(&mut errors, 0.95);
    let max = percentile(&mut errors, 1.0);
    println!(
        "round trip, neutral start, 1000 poses held {HOLD_FRAMES} frames: worst-tip error p50 {:.3} mm, p95 {:.3} mm, max {:.1} mm",
        p50 * 1e3,
        p95 * 1e3,
        max * 1e3
    );
    assert!(p95 <= 2e-3, "p95 {p95} m");
}

#[test]
fn one_solve_from_neutral_reproduces_fingertips() {
    // A single frame from the neutral pose, as the calibration runs the retargeter: enough
    // Gauss–Newton steps, no rate limit and no pull toward the previous (neutral) command.
    let model = HandModel::orca_v1_right();
    let mut config = key_vectors_only();
    config.regularisation.previous_command = 0.0;
    config.solver.steps_per_frame = 30;
    config.solver.max_joint_speed_rad_s = 100.0;
    config.solver.max_rate_dt_s = 1.0;
    let mut retargeter =
        Retargeter::new(model.clone(), config, &EmbodimentCatalog::builtin()).unwrap();
    let mut rng = StdRng::seed_from_u64(5);
    let (mut errors, mut steps) = (Vec::new(), 0);
    for _ in 0..1000 {
        let q_true = random_pose(&model, &mut rng);
        let keypoints =
            model.synthetic_keypoints(&model.forward_new(&q_true).unwrap(), KeypointLayout::Lab22);
        retargeter.reset();
        let solution = retargeter.retarget(&keypoints, 1.0).unwrap();
        steps += solution.steps;
        errors.push(tip_error(&mut retargeter, &q_true, &solution.q));
    }
    let p50 = percentile(&mut errors, 0.5);
    let p95 = percentile(&mut errors, 0.95);
    println!(
        "round trip, one solve from neutral, 1000 poses: worst-tip error p50 {:.3} mm, p95 {:.3} mm, {:.1} GN steps on average",
        p50 * 1e3,
        p95 * 1e3,
        f64::from(steps) / 1000.0
    );
    assert!(p95 <= 2e-3, "p95 {p95} m");
}

#[test]
fn smooth_trajectories_with_warm_start_track_fingertips() {
    let (model, mut retargeter) = common::poses::orca_retargeter(key_vectors_only());
    let mut rng = StdRng::seed_from_u64(11);
    let dt = 0.04; // 25 Hz
    let mut errors = Vec::new();
    for _ in 0..10 {
        // Start exactly at a pose the solver knows, then move smoothly through random
        // waypoints with a raised-cosine profile (peak joint speed ≈ 2 rad/s).
        let mut from = random_pose(&model, &mut rng);
        let start =
            model.synthetic_keypoints(&model.forward_new(&from).unwrap(), KeypointLayout::Lab22);
        retargeter.reset();
        for _ in 0..60 {
            retargeter.retarget(&start, dt).unwrap();
        }
        for _ in 0..4 {
            let to = random_pose(&model, &mut rng);
            let distance = from
                .iter()
                .zip(&to)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            let frames = ((distance / (2.0 * dt)) * std::f64::consts::FRAC_PI_2)
                .ceil()
                .max(1.0) as usize;
            for i in 1..=frames {
                let s = 0.5 - 0.5 * (std::f64::consts::PI * i as f64 / frames as f64).cos();
                let q: Vec<f64> = from.iter().zip(&to).map(|(a, b)| a + s * (b - a)).collect();
                let keypoints = model
                    .synthetic_keypoints(&model.forward_new(&q).unwrap(), KeypointLayout::Lab22);
                let solution = retargeter.retarget(&keypoints, dt).unwrap();
                errors.push(tip_error(&mut retargeter, &q, &solution.q));
            }
            from = to;
        }
    }
    let n = errors.len();
    let p50 = percentile(&mut errors, 0.5);
    let p95 = percentile(&mut errors, 0.95);
    println!(
        "round trip, smooth trajectories, {n} frames at 25 Hz: worst-tip error p50 {:.3} mm, p95 {:.3} mm",
        p50 * 1e3,
        p95 * 1e3
    );
    assert!(p95 <= 1e-3, "p95 {p95} m");
}
