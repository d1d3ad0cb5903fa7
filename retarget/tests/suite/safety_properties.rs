//! Safety properties over 100,000 random and adversarial (finite) frames: every command is
//! finite, within the joint limits and the rate bound around the previous command, with the
//! embodiment's locked joints exactly at their neutral value; a rejected frame leaves the
//! command unchanged.

use crate::common;

use nalgebra::{Point3, Vector3};
use proptest::prelude::*;
use rand::{Rng, SeedableRng, rngs::StdRng};
use retarget::{EmbodimentCatalog, HandModel, KeypointLayout, RetargetConfig, Retargeter};

const CASES: u32 = 1000;
const FRAMES_PER_CASE: usize = 100;
const TOLERANCE: f64 = 1e-9;

/// One frame, drawn from a mix of plausible and hostile inputs.
fn frame(model: &HandModel, rng: &mut StdRng) -> Vec<Point3<f64>> {
    let layout = KeypointLayout::Lab22;
    let q = common::poses::random_pose(model, rng);
    let mut points = model.synthetic_keypoints(&model.forward_new(&q).unwrap(), layout);
    match rng.random_range(0..8) {
        // A plausible hand with glove noise.
        0 | 1 => {
            for p in &mut points {
                *p += Vector3::from_fn(|_, _| rng.random_range(-0.003..0.003));
            }
        }
        // Some points thrown far away (a bad marker).
        2 => {
            for _ in 0..rng.random_range(1..5) {
                let i = rng.random_range(0..points.len());
                points[i] += Vector3::from_fn(|_, _| rng.random_range(-10.0..10.0));
            }
        }
        // Uniform garbage, at any scale.
        3 => {
            let scale = 10f64.powi(rng.random_range(-9..7));
            for p in &mut points {
                *p = Point3::from(Vector3::from_fn(|_, _| rng.random_range(-1.0..1.0) * scale));
            }
        }
        // Collapsed: every point (nearly) the same.
        4 => {
            let c = points[0];
            for p in &mut points {
                *p = c + Vector3::from_fn(|_, _| rng.random_range(-1e-6..1e-6));
            }
        }
        // A hand scaled by a huge or tiny factor.
        5 => {
            let s = 10f64.powi(rng.random_range(-6..6));
            for p in &mut points {
                *p = Point3::from(p.coords * s);
            }
        }
        // Fingers collapsed onto the palm plane, or the thumb through the palm.
        6 => {
            for p in points.iter_mut().skip(2) {
                p.z = 0.0;
            }
        }
        // An exact repeat of a hand pose far from the last command.
        _ => {}
    }
    points
}

fn time_step(rng: &mut StdRng) -> f64 {
    match rng.random_range(0..6) {
        0 => 1e-6,
        1 => rng.random_range(0.0..2.0),
        _ => rng.random_range(0.005..0.05),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(CASES))]

    #[test]
    fn commands_stay_finite_within_limits_rate_bounds_and_locks(seed in any::<u64>(), embodiment in 0usize..4) {
        let model = HandModel::orca_v1_right();
        let catalog = EmbodimentCatalog::builtin();
        let config = RetargetConfig {
            embodiment: ["orca_full", "orca_5", "orca_3", "orca_2"][embodiment].into(),
            ..RetargetConfig::default()
        };
        let mut retargeter = Retargeter::new(model.clone(), config.clone(), &catalog).unwrap();
        let free = retargeter.free_dofs().to_vec();
        let neutral = retargeter.neutral().to_vec();
        let limits: Vec<_> = model.limits().collect();
        let mut rng = StdRng::seed_from_u64(seed);
        for _ in 0..FRAMES_PER_CASE {
            let points = frame(&model, &mut rng);
            let dt = time_step(&mut rng);
            let before = retargeter.command().to_vec();
            match retargeter.retarget(&points, dt) {
                Err(_) => prop_assert_eq!(retargeter.command(), &before[..]),
                Ok(solution) => {
                    let reach = config.solver.max_joint_speed_rad_s * dt.min(config.solver.max_rate_dt_s);
                    prop_assert_eq!(&solution.q[..], retargeter.command());
                    for (i, (&q, l)) in solution.q.iter().zip(&limits).enumerate() {
                        prop_assert!(q.is_finite(), "joint {} not finite", i);
                        prop_assert!(q >= l.lower_rad - TOLERANCE && q <= l.upper_rad + TOLERANCE,
                            "joint {} = {} outside [{}, {}]", i, q, l.lower_rad, l.upper_rad);
                        prop_assert!((q - before[i]).abs() <= reach + TOLERANCE,
                            "joint {} moved {} > {} in dt {}", i, (q - before[i]).abs(), reach, dt);
                        if !free.contains(&i) {
                            prop_assert_eq!(q, neutral[i], "locked joint {} moved", i);
                        }
                    }
                    prop_assert!(solution.cost_after.is_finite() && solution.cost_after <= solution.cost_before + 1e-12);
                }
            }
        }
    }
}

#[test]
fn malformed_frames_are_errors_and_hold_the_command() {
    let (model, mut retargeter) = common::poses::orca_retargeter(RetargetConfig::default());
    let good = model.synthetic_keypoints(
        &model.forward_new(&model.zero_pose()).unwrap(),
        KeypointLayout::Lab22,
    );
    retargeter.retarget(&good, 0.04).unwrap();
    let held = retargeter.command().to_vec();
    let mut nan = good.clone();
    nan[9].x = f64::NAN;
    let mut infinite = good.clone();
    infinite[0].z = f64::INFINITY;
    let collapsed = vec![Point3::new(0.1, 0.2, 0.3); 22];
    let cases: [(&[Point3<f64>], f64, &str); 6] = [
        (&nan, 0.04, "point 9 (index_tip) is not finite"),
        (&infinite, 0.04, "point 0 (forearm) is not finite"),
        (&good[..21], 0.04, "layout lab22 has 22 points, got 21"),
        (&collapsed, 0.04, "collapsed palm frame"),
        (&good, 0.0, "time step must be positive"),
        (&good, f64::NAN, "time step must be positive"),
    ];
    for (points, dt, message) in cases {
        let err = retargeter.retarget(points, dt).unwrap_err().to_string();
        assert!(err.contains(message), "{err}");
        assert_eq!(retargeter.command(), &held[..]);
    }
}
