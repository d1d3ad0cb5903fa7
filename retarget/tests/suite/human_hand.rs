//! The parametric human hand model: geometry invariants, named poses, pinches, scripted
//! motions, the simulated glove's jitter, and the real retargeter driven by the simulated
//! glove (the ORCA hand must close each pinch the human makes).

use crate::common;

use nalgebra::{Isometry3, Matrix3, Point3, Vector3};
use retarget::human_hand::{
    Handedness, HumanHandPose, HumanHandShape, JOINT_RANGES_RAD, KeyPose, Motion, MotionKind,
    POSE_ANGLES, SimGlove, SplitMix64, WristSway, pinch_pose,
};
use retarget::{
    CalibrationTransform, Finger, HandModel, KeypointLayout, PalmFrame, PinchConfig,
    RetargetConfig, Retargeter, human_key_vectors,
};

const SCALES: [f64; 3] = [0.8, 1.0, 1.25];

/// Poses within the anatomical ranges, drawn from a fixed seed.
fn random_poses(count: usize, seed: u64) -> Vec<HumanHandPose> {
    let mut rng = SplitMix64::new(seed);
    (0..count)
        .map(|_| {
            HumanHandPose::from_array(&std::array::from_fn::<f64, POSE_ANGLES, _>(|i| {
                let (lo, hi) = JOINT_RANGES_RAD[i];
                lo + (hi - lo) * rng.next_f64()
            }))
        })
        .collect()
}

fn named_poses() -> Vec<(&'static str, HumanHandPose)> {
    vec![
        ("open", HumanHandPose::open()),
        ("open_spread", HumanHandPose::open_spread()),
        ("fist", HumanHandPose::fist()),
        ("relaxed", HumanHandPose::relaxed()),
        ("cylinder_grasp", HumanHandPose::cylinder_grasp()),
    ]
}

fn palm_frame(layout: KeypointLayout, points: &[Point3<f64>]) -> PalmFrame {
    PalmFrame::from_landmarks(&layout.palm_landmarks(points)).unwrap()
}

#[test]
fn bones_keep_their_lengths_in_every_pose_size_hand_and_layout() {
    let mut poses: Vec<HumanHandPose> = named_poses().into_iter().map(|(_, p)| p).collect();
    poses.extend(random_poses(200, 11));
    let average = HumanHandShape::average();
    let mut checked = 0;
    for scale in SCALES {
        for handedness in [Handedness::Right, Handedness::Left] {
            let shape = average.scaled(scale).with_handedness(handedness);
            for layout in KeypointLayout::ALL {
                for pose in &poses {
                    let points = shape.keypoints(pose, layout);
                    for finger in Finger::ALL {
                        let chain = layout.chain(finger);
                        let bones = average.bone_lengths_m(finger);
                        for k in 0..3 {
                            let got = (points[chain[k + 1]] - points[chain[k]]).norm();
                            let want = bones[k] * scale;
                            assert!(
                                (got - want).abs() < 1e-12,
                                "{layout} {finger} bone {k} at scale {scale}: {got} m, want {want} m"
                            );
                        }
                        // The palm is rigid: wrist to digit base does not depend on the pose.
                        let base = Vector3::from(average.digit(finger).base_m).norm() * scale;
                        let got = (points[chain[0]] - points[layout.wrist()]).norm();
                        assert!((got - base).abs() < 1e-12, "{finger} base moved");
                        checked += 1;
                    }
                }
            }
        }
    }
    assert_eq!(checked, 3 * 2 * 3 * 205 * 5);
}

#[test]
fn palm_frame_is_the_hand_frame_and_does_not_depend_on_size_or_pose() {
    let placement = Isometry3::new(Vector3::new(0.2, -0.1, 0.4), Vector3::new(0.3, -0.6, 1.1));
    for layout in KeypointLayout::ALL {
        let reference = palm_frame(
            layout,
            &HumanHandShape::average().keypoints(&HumanHandPose::open(), layout),
        );
        // Right hand: the palm frame's axes are the hand frame's (x to the thumb, y to the
        // fingers, z out of the palm).
        assert!(
            (reference.rotation.matrix() - Matrix3::identity()).norm() < 1e-12,
            "{layout}: {}",
            reference.rotation.matrix()
        );
        for scale in SCALES {
            let shape = HumanHandShape::average().scaled(scale);
            for pose in random_poses(20, 5) {
                let frame = palm_frame(layout, &shape.keypoints_in(&pose, layout, &placement));
                let r = frame.rotation.matrix();
                assert!((r.transpose() * r - Matrix3::identity()).norm() < 1e-12);
                assert!((r.determinant() - 1.0).abs() < 1e-12);
                let expected = placement.rotation.to_rotation_matrix();
                assert!(
                    frame.rotation.angle_to(&expected) < 1e-9,
                    "{layout} scale {scale}: the palm frame turned"
                );
                let origin = placement * (reference.origin * scale);
                assert!((frame.origin - origin).norm() < 1e-12);
            }
        }
    }
    // A left hand's keypoints give the documented mirror: z out of the back of the hand.
    let left = HumanHandShape::average().with_handedness(Handedness::Left);
    let layout = KeypointLayout::Lab21;
    let frame = palm_frame(layout, &left.keypoints(&HumanHandPose::open(), layout));
    assert!((frame.rotation.matrix().column(2) + Vector3::z()).norm() < 1e-12);
}

#[test]
fn open_hand_has_straight_digits_and_the_fist_is_closed_on_the_palm() {
    let layout = KeypointLayout::Lab22;
    for scale in SCALES {
        let shape = HumanHandShape::average().scaled(scale);
        let open = shape.keypoints(&HumanHandPose::open(), layout);
        for finger in Finger::ALL {
            let c = layout.chain(finger);
            let first = (open[c[1]] - open[c[0]]).normalize();
            for k in 1..3 {
                let bone = (open[c[k + 1]] - open[c[k]]).normalize();
                assert!(
                    first.angle(&bone) < 1e-9,
                    "{finger}: open bone {k} bent by {} rad",
                    first.angle(&bone)
                );
            }
        }
        let fist = shape.keypoints(&HumanHandPose::fist(), layout);
        let palm = palm_frame(layout, &fist);
        let wrist = palm.point_to_palm(&fist[layout.wrist()]);
        for finger in Finger::OPPOSING {
            let tip = palm.point_to_palm(&fist[layout.tip(finger)]);
            let base = palm.point_to_palm(&fist[layout.base(finger)]);
            let open_tip = palm.point_to_palm(&open[layout.tip(finger)]);
            println!(
                "scale {scale}: {finger} tip in the fist {:.0} mm above the palm plane, open {:.0} mm",
                tip.z / scale * 1e3,
                open_tip.z * 1e3
            );
            assert!(
                tip.z > 0.0 && tip.z < 0.03 * scale,
                "{finger}: fist tip {:.1} mm from the palm plane",
                tip.z * 1e3
            );
            assert!(
                tip.y > wrist.y && tip.y < base.y,
                "{finger}: fist tip is not over the palm"
            );
            assert!(
                (fist[layout.tip(finger)] - fist[layout.base(finger)]).norm()
                    < 0.5 * (open[layout.tip(finger)] - open[layout.base(finger)]).norm(),
                "{finger}: not curled"
            );
        }
        // The thumb folds over the fingers on the palm side: in front of the palm, between
        // the index and ring bases across it.
        let thumb = palm.point_to_palm(&fist[layout.tip(Finger::Thumb)]);
        let index = palm.point_to_palm(&fist[layout.base(Finger::Index)]);
        let ring = palm.point_to_palm(&fist[layout.base(Finger::Ring)]);
        assert!(
            thumb.z > 0.03 * scale && thumb.x < index.x && thumb.x > ring.x,
            "{thumb}"
        );
    }
}

#[test]
fn pinches_reach_the_requested_gap_for_every_finger_and_hand_size() {
    let release_m = PinchConfig::default().release_m;
    let layout = KeypointLayout::Lab22;
    for step in 0..=9 {
        let scale = 0.8 + 0.05 * step as f64;
        let shape = HumanHandShape::average().scaled(scale);
        for finger in Finger::OPPOSING {
            for gap_m in [0.0, 0.005, 0.01, 0.02] {
                let pinch = pinch_pose(&shape, finger, gap_m).unwrap();
                let points = shape.keypoints(&pinch.pose, layout);
                let thumb = points[layout.tip(Finger::Thumb)];
                let measured = (points[layout.tip(finger)] - thumb).norm();
                assert!(
                    (measured - gap_m).abs() < 1e-3,
                    "scale {scale:.2} {finger} gap {gap_m}: keypoints {measured} m apart"
                );
                assert!(pinch.pose.within_ranges(), "{finger}: out of range");
                // Only the pinching finger is near the thumb: the retargeter must not see a
                // second pinch.
                for other in Finger::OPPOSING.into_iter().filter(|&o| o != finger) {
                    let d = (points[layout.tip(other)] - thumb).norm();
                    assert!(
                        d > release_m,
                        "{finger} pinch: {other} tip {d} m from the thumb"
                    );
                }
            }
        }
    }
    let shape = HumanHandShape::average();
    for finger in Finger::OPPOSING {
        let p = pinch_pose(&shape, finger, 0.005).unwrap();
        println!(
            "{finger} pinch at 5 mm: reached {:.4} mm in {} iterations, angles {:.2?}",
            p.gap_m * 1e3,
            p.iterations,
            p.pose.to_array()
        );
    }
}

/// Keypoints of a motion at `t`, for a right hand at scale 1.1 (Lab22).
fn motion_points(motion: &Motion, shape: &HumanHandShape, t: f64) -> Vec<Point3<f64>> {
    shape.keypoints(&motion.sample(t), KeypointLayout::Lab22)
}

fn max_distance(a: &[Point3<f64>], b: &[Point3<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max)
}

#[test]
fn motions_are_smooth_and_periodic() {
    let shape = HumanHandShape::average().scaled(1.1);
    for kind in MotionKind::ALL {
        let motion = Motion::new(kind, kind.default_period_s(), &shape).unwrap();
        let cycle = motion.cycle_s();
        // Continuity: over two cycles (the wrap included), 1 ms moves no point more than
        // 1 mm (1 m/s).
        let h = 1e-3;
        let mut worst_step: f64 = 0.0;
        // C¹: the second difference stays O(h²) (bounded acceleration), so no velocity jumps
        // at segment boundaries; a jump Δv would show as Δv·h.
        let h2 = 1e-4;
        let mut worst_accel: f64 = 0.0;
        let n = (2.0 * cycle / h).round() as usize;
        for i in 0..n {
            let t = i as f64 * h;
            let p = motion_points(&motion, &shape, t);
            worst_step = worst_step.max(max_distance(&p, &motion_points(&motion, &shape, t + h)));
            if i % 5 == 0 {
                let (a, b) = (
                    motion_points(&motion, &shape, t - h2),
                    motion_points(&motion, &shape, t + h2),
                );
                let second = p
                    .iter()
                    .zip(&a)
                    .zip(&b)
                    .map(|((p, a), b)| (a.coords + b.coords - 2.0 * p.coords).norm())
                    .fold(0.0, f64::max);
                worst_accel = worst_accel.max(second / (h2 * h2));
            }
        }
        println!(
            "{kind:?}: cycle {cycle} s, fastest point {:.3} m/s, peak acceleration {:.2} m/s²",
            worst_step / h,
            worst_accel
        );
        assert!(
            worst_step < 1e-3,
            "{kind:?}: a point jumps {worst_step} m in 1 ms"
        );
        assert!(
            worst_accel < 20.0,
            "{kind:?}: acceleration {worst_accel} m/s²"
        );
        // It moves, and it repeats.
        let rest = motion_points(&motion, &shape, 0.0);
        let mut travelled: f64 = 0.0;
        for i in 0..50 {
            let t = cycle * i as f64 / 50.0 + 0.013;
            let p = motion_points(&motion, &shape, t);
            travelled = travelled.max(max_distance(&p, &rest));
            for k in [-1.0, 1.0, 3.0] {
                let q = motion_points(&motion, &shape, t + k * cycle);
                assert!(
                    max_distance(&p, &q) < 1e-9,
                    "{kind:?}: not periodic at {t} s"
                );
            }
        }
        assert!(
            travelled > 0.03,
            "{kind:?}: the hand barely moves ({travelled} m)"
        );
        // Every cycle starts where it ends: the open hand, or for the calibration poses the
        // closed hand (the last pose), from which it moves to the first pinch.
        let start = if kind == MotionKind::CalibrationPoses {
            HumanHandPose::fist()
        } else {
            HumanHandPose::open()
        };
        assert_eq!(motion.sample(0.0), start, "{kind:?} starts where it ends");
    }
}

#[test]
fn the_pinches_motion_holds_each_pinch_in_turn() {
    let shape = HumanHandShape::average();
    let motion = Motion::new(MotionKind::Pinches, 2.0, &shape).unwrap();
    for (k, finger) in Finger::OPPOSING.into_iter().enumerate() {
        // Middle of the hold of pinch k: 2 s · (k + 0.5).
        let t = 2.0 * (k as f64 + 0.5);
        let phase = motion.phase(t);
        assert_eq!(
            (phase.from, phase.to),
            (KeyPose::Pinch(finger), KeyPose::Pinch(finger))
        );
        let gap = shape.thumb_gap_m(&motion.sample(t), finger);
        assert!((gap - 0.005).abs() < 1e-4, "{finger}: held gap {gap} m");
    }
}

#[test]
fn every_layout_carries_the_same_hand() {
    let shape = HumanHandShape::average().scaled(0.9);
    let pose = HumanHandPose::cylinder_grasp();
    let lab22 = shape.keypoints(&pose, KeypointLayout::Lab22);
    let mut reference = None;
    for layout in KeypointLayout::ALL {
        let points = shape.keypoints(&pose, layout);
        assert_eq!(points.len(), layout.len());
        assert_eq!(points[layout.wrist()], Point3::origin());
        for finger in Finger::ALL {
            let a = layout.chain(finger).map(|i| points[i]);
            let b = KeypointLayout::Lab22.chain(finger).map(|i| lab22[i]);
            assert_eq!(a, b, "{layout} {finger}");
        }
        if let Some(forearm) = layout.forearm() {
            // Behind the wrist, along the palm's y axis, at the scaled forearm length.
            let palm = palm_frame(layout, &points);
            let v = palm.vector_to_palm(&(points[forearm] - points[layout.wrist()]));
            assert!(
                (v - Vector3::new(0.0, -0.25 * 0.9, 0.0)).norm() < 1e-12,
                "{v}"
            );
        }
        let keys = human_key_vectors(layout, &points, &CalibrationTransform::IDENTITY).unwrap();
        match reference {
            None => reference = Some(keys),
            Some(r) => assert_eq!(keys, r, "{layout}: different key vectors"),
        }
    }
}

#[test]
fn jitter_is_seeded_and_of_the_requested_size() {
    let shape = HumanHandShape::average();
    let motion = Motion::new(MotionKind::TaskLike, 12.0, &shape).unwrap();
    let placement = Isometry3::new(Vector3::new(0.1, 0.2, 0.3), Vector3::new(0.2, -0.3, 0.1));
    let clean = SimGlove::new(shape, motion, KeypointLayout::Lab22)
        .unwrap()
        .with_hand_in_glove(placement)
        .with_wrist_sway(WristSway::GENTLE)
        .unwrap();
    let sd_m = 0.002;
    let noisy = clean.clone().with_jitter(sd_m, 42).unwrap();
    let same = clean.clone().with_jitter(sd_m, 42).unwrap();
    let other = clean.clone().with_jitter(sd_m, 43).unwrap();

    let (mut sum, mut sum_sq, mut count) = (Vector3::zeros(), Vector3::zeros(), 0.0);
    for i in 0..2000 {
        let t = i as f64 * 0.04;
        let (p, wrist) = noisy.frame(t);
        let (q, wrist_clean) = clean.frame(t);
        assert_eq!(wrist, wrist_clean, "the wrist pose is not jittered");
        assert_eq!((p.clone(), wrist), same.frame(t), "same seed, same frame");
        assert_eq!(
            noisy.frame(t).0,
            p,
            "the same time twice gives the same frame"
        );
        assert_ne!(other.frame(t).0, p, "another seed, other noise");
        for (a, b) in p.iter().zip(&q) {
            let d = a - b;
            sum += d;
            sum_sq += d.component_mul(&d);
            count += 1.0;
        }
    }
    let mean = sum / count;
    let sd = (sum_sq / count - mean.component_mul(&mean)).map(f64::sqrt);
    println!(
        "jitter {sd_m} m requested: per-axis mean {mean:?} m, sd {sd:?} m over {count} points"
    );
    for axis in 0..3 {
        assert!(
            mean[axis].abs() < 0.05 * sd_m,
            "axis {axis} mean {}",
            mean[axis]
        );
        assert!(
            (sd[axis] / sd_m - 1.0).abs() < 0.03,
            "axis {axis} sd {}",
            sd[axis]
        );
    }
    // Consecutive frames get independent noise.
    let (a, _) = noisy.frame(1.0);
    let (b, _) = noisy.frame(1.04);
    let (ca, _) = clean.frame(1.0);
    let (cb, _) = clean.frame(1.04);
    let correlation: f64 = a
        .iter()
        .zip(&ca)
        .zip(b.iter().zip(&cb))
        .map(|((a, ca), (b, cb))| (a - ca).dot(&(b - cb)))
        .sum::<f64>()
        / (a.len() as f64 * 3.0 * sd_m * sd_m);
    assert!(correlation.abs() < 0.5, "correlation {correlation}");
}

fn orca() -> (HandModel, Retargeter) {
    common::poses::orca_retargeter(RetargetConfig::default())
}

/// A glove as a lab would see it: the hand turned and moved in the tracker frame, swaying,
/// with 1 mm jitter.
fn lab_glove(kind: MotionKind, scale: f64, jitter_sd_m: f64) -> SimGlove {
    let shape = HumanHandShape::average().scaled(scale);
    let motion = Motion::new(kind, kind.default_period_s(), &shape).unwrap();
    SimGlove::new(shape, motion, KeypointLayout::Lab22)
        .unwrap()
        .with_hand_in_glove(Isometry3::new(
            Vector3::new(0.05, 1.1, 0.3),
            Vector3::new(-0.4, 0.9, 0.2),
        ))
        .with_wrist_sway(WristSway::GENTLE)
        .unwrap()
        .with_jitter(jitter_sd_m, 2024)
        .unwrap()
}

#[test]
fn the_retargeter_runs_on_ten_seconds_of_every_motion() {
    for kind in MotionKind::ALL {
        for scale in SCALES {
            let (model, mut retargeter) = orca();
            let glove = lab_glove(kind, scale, 0.001);
            let mut worst_tip_error: f64 = 0.0;
            let mut mean_tip_error = 0.0;
            for i in 0..250 {
                let (points, _) = glove.frame(i as f64 / 25.0);
                let solution = retargeter
                    .retarget(&points, 0.04)
                    .unwrap_or_else(|e| panic!("{kind:?} scale {scale} frame {i}: {e}"));
                assert!(model.within_limits(&solution.q));
                assert!(solution.q.iter().all(|q| q.is_finite()));
                worst_tip_error = worst_tip_error.max(solution.tip_error_m);
                mean_tip_error += solution.tip_error_m / 250.0;
            }
            println!(
                "{kind:?} scale {scale}: 250 frames, palm-to-tip error mean {:.1} mm, worst {:.1} mm",
                mean_tip_error * 1e3,
                worst_tip_error * 1e3
            );
        }
    }
}

/// Per opposing finger: the smallest ORCA thumb-to-fingertip distance while the simulated
/// human holds that pinch, over 10 s of the Pinches motion at 25 Hz.
fn robot_pinch_gaps(glove: &SimGlove) -> [f64; 4] {
    let (model, mut retargeter) = orca();
    let thumb = model.frames().tip(Finger::Thumb);
    let mut closest = [f64::INFINITY; 4];
    for i in 0..250 {
        let t = i as f64 / 25.0;
        let (points, _) = glove.frame(t);
        let solution = retargeter.retarget(&points, 0.04).unwrap();
        let phase = glove.motion().phase(t);
        if let (KeyPose::Pinch(a), KeyPose::Pinch(b)) = (phase.from, phase.to)
            && a == b
        {
            let state = model.forward_new(&solution.q).unwrap();
            let gap = (state.position(thumb) - state.position(model.frames().tip(a))).norm();
            let k = a.index() - 1;
            closest[k] = closest[k].min(gap);
        }
    }
    closest
}

#[test]
fn orca_closes_every_pinch_of_the_simulated_glove() {
    let clean = robot_pinch_gaps(&lab_glove(MotionKind::Pinches, 1.0, 0.0));
    let noisy = robot_pinch_gaps(&lab_glove(MotionKind::Pinches, 1.0, 0.002));
    for (k, finger) in Finger::OPPOSING.into_iter().enumerate() {
        println!(
            "scale 1.0, {finger:<6} pinch (human gap 5 mm): ORCA thumb-tip gap during the hold \
             ≥ {:.1} mm (no jitter), {:.1} mm (2 mm jitter)",
            clean[k] * 1e3,
            noisy[k] * 1e3
        );
    }
    for (k, finger) in Finger::OPPOSING.into_iter().enumerate() {
        assert!(
            clean[k] < 0.015,
            "{finger}: ORCA thumb stays {:.1} mm from the tip",
            clean[k] * 1e3
        );
        assert!(
            noisy[k] < 0.015,
            "{finger} (2 mm jitter): ORCA thumb stays {:.1} mm from the tip",
            noisy[k] * 1e3
        );
    }
}
