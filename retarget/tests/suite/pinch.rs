//! Pinch: when the human thumb tip touches a fingertip (< 1 cm), the Orca_full robot's thumb
//! and that fingertip close to within 1.5 cm, for each of the four fingers, for hands smaller
//! and larger than the robot's (where the key vectors alone would leave a gap).
//!
//! The "human" is the robot itself at a pinch pose (thumb tip 7 mm from the fingertip, as
//! glove tip points sit when the pads touch) found by a small Gauss–Newton search, its
//! keypoints scaled about the wrist by 0.8, 1.0 and 1.25 (the hand sizes calibration must
//! cover). The human still pinches (gap < 1 cm), but the retargeter runs uncalibrated at
//! scale 1, so for the scaled hands the palm-to-tip key vectors point past or short of the
//! robot's reach; a control run shows the gap that the key vectors alone leave.

use crate::common;

use nalgebra::{DMatrix, DVector, Matrix3xX, Point3};
use retarget::{EmbodimentCatalog, Finger, HandModel, KeypointLayout, RetargetConfig, Retargeter};

/// Human thumb-tip to fingertip gap of the pinch poses, metres.
const PINCH_GAP_M: f64 = 0.007;

/// Robot pose (within limits) whose thumb tip is `PINCH_GAP_M` from `finger`'s tip.
fn pinch_pose(model: &HandModel, finger: Finger) -> Vec<f64> {
    let prefix = match finger {
        Finger::Little => "pinky",
        other => other.name(),
    };
    let free: Vec<usize> = model
        .dof_names()
        .enumerate()
        .filter(|(_, n)| n.starts_with("thumb") || n.starts_with(prefix))
        .map(|(i, _)| i)
        .collect();
    let limits: Vec<_> = model.limits().collect();
    let (thumb, tip) = (
        model.frames().tip(Finger::Thumb),
        model.frames().tip(finger),
    );
    let mut best = (f64::INFINITY, model.zero_pose());
    for seed in [0.3, 0.5, 0.7] {
        let mut q: Vec<f64> = limits
            .iter()
            .map(|l| l.clamp(0.0) * (1.0 - seed) + (l.lower_rad + l.upper_rad) * 0.5 * seed)
            .collect();
        let (mut ja, mut jb) = (Matrix3xX::zeros(model.dof()), Matrix3xX::zeros(model.dof()));
        for _ in 0..200 {
            let state = model.forward_new(&q).unwrap();
            let d = state.position(thumb) - state.position(tip);
            let r = d - d.normalize() * PINCH_GAP_M;
            model.position_jacobian(&state, thumb, &mut ja).unwrap();
            model.position_jacobian(&state, tip, &mut jb).unwrap();
            let j = DMatrix::from_fn(3, free.len(), |row, k| {
                ja[(row, free[k])] - jb[(row, free[k])]
            });
            let h = j.transpose() * &j + DMatrix::identity(free.len(), free.len()) * 1e-5;
            let step = h
                .lu()
                .solve(&(j.transpose() * DVector::from_column_slice(r.as_slice())))
                .unwrap();
            for (k, &dof) in free.iter().enumerate() {
                q[dof] = limits[dof].clamp(q[dof] - 0.5 * step[k]);
            }
        }
        let state = model.forward_new(&q).unwrap();
        let miss = ((state.position(thumb) - state.position(tip)).norm() - PINCH_GAP_M).abs();
        if miss < best.0 {
            best = (miss, q);
        }
    }
    assert!(
        best.0 < 5e-4,
        "{finger}: no robot pinch pose found (off by {} m)",
        best.0
    );
    best.1
}

fn scaled_keypoints(model: &HandModel, q: &[f64], scale: f64) -> Vec<Point3<f64>> {
    let points = model.synthetic_keypoints(&model.forward_new(q).unwrap(), KeypointLayout::Lab22);
    let wrist = points[KeypointLayout::Lab22.wrist()];
    points.iter().map(|p| wrist + (p - wrist) * scale).collect()
}

#[test]
fn human_pinches_close_the_robot_pinch_for_every_finger() {
    let (model, mut retargeter) = common::poses::orca_retargeter(RetargetConfig::default());
    let open = retargeter.neutral().to_vec();
    let thumb = model.frames().tip(Finger::Thumb);
    for finger in Finger::OPPOSING {
        let pinch = pinch_pose(&model, finger);
        let tip = model.frames().tip(finger);
        for scale in [0.8, 1.0, 1.25] {
            retargeter.reset();
            // One second from open to pinch at 25 Hz, then half a second held.
            let mut worst_held: f64 = 0.0;
            let mut human_gap: f64 = 0.0;
            for i in 0..=37 {
                let s = (i as f64 / 25.0).min(1.0);
                let q: Vec<f64> = open
                    .iter()
                    .zip(&pinch)
                    .map(|(a, b)| a + s * (b - a))
                    .collect();
                let keypoints = scaled_keypoints(&model, &q, scale);
                let solution = retargeter.retarget(&keypoints, 0.04).unwrap();
                if i >= 25 {
                    let layout = KeypointLayout::Lab22;
                    human_gap = (keypoints[layout.tip(Finger::Thumb)]
                        - keypoints[layout.tip(finger)])
                    .norm();
                    let state = model.forward_new(&solution.q).unwrap();
                    worst_held =
                        worst_held.max((state.position(thumb) - state.position(tip)).norm());
                }
            }
            println!(
                "{finger:<6} hand scale {scale:.2}: human thumb gap {:.1} mm, robot gap held ≤ {:.1} mm",
                human_gap * 1e3,
                worst_held * 1e3
            );
            assert!(
                human_gap < 0.01,
                "test set-up: the human must touch ({human_gap} m)"
            );
            assert!(
                worst_held <= 0.015,
                "{finger} at scale {scale}: robot gap {worst_held} m"
            );
        }
    }
}

/// Robot thumb-to-index gap after holding the 1.25× hand's index pinch for 1.6 s.
fn held_index_gap(config: RetargetConfig) -> f64 {
    let model = HandModel::orca_v1_right();
    let mut retargeter =
        Retargeter::new(model.clone(), config, &EmbodimentCatalog::builtin()).unwrap();
    let keypoints = scaled_keypoints(&model, &pinch_pose(&model, Finger::Index), 1.25);
    let mut q = Vec::new();
    for _ in 0..40 {
        q = retargeter.retarget(&keypoints, 0.04).unwrap().q;
    }
    let state = model.forward_new(&q).unwrap();
    (state.position(model.frames().tip(Finger::Thumb))
        - state.position(model.frames().tip(Finger::Index)))
    .norm()
}

#[test]
fn the_pinch_term_closes_what_the_key_vectors_leave_open() {
    // Control experiment: the same input with the pinch weight at zero closes less, so the
    // test above measures the pinch term, not only the key vectors.
    let with = held_index_gap(RetargetConfig::default());
    let mut config = RetargetConfig::default();
    config.pinch.weight = 0.0;
    let without = held_index_gap(config);
    println!(
        "index, hand scale 1.25: robot gap {:.1} mm with the pinch term, {:.1} mm without",
        with * 1e3,
        without * 1e3
    );
    assert!(without > with + 0.002, "with {with} m, without {without} m");
}
