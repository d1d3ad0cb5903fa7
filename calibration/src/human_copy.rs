//! How a user performs a calibration pose: by copying the robot hand, which the station sends
//! to the pose. The synthetic users' (and the simulated glove's) version of each pose is the
//! human hand model's posture whose digit points, in the human palm frame, lie closest to the
//! robot's in the robot palm frame.
//!
//! Least squares over the 20 angles of [`HumanHandPose`] (within [`JOINT_RANGES_RAD`]) of the
//! distances between the three chain points after each digit's base (tips weighted 1, the
//! other two 0.5), with a light pull (1e-4 per rad²) toward the relaxed hand so angles the
//! points do not determine stay natural. Damped Gauss–Newton with forward-difference
//! Jacobians, from the relaxed hand, projected into the ranges after every step.

use nalgebra::{DMatrix, DVector, Point3, Vector3};
use retarget::human_hand::{HumanHandPose, HumanHandShape, JOINT_RANGES_RAD, POSE_ANGLES};
use retarget::{Finger, HandModel, KeypointLayout, PalmFrame};

use crate::error::Error;
use crate::poses::PoseSet;

const ITERATIONS: usize = 60;
const REST_WEIGHT: f64 = 1e-4;
const STEP_RAD: f64 = 1e-6;

/// The digit points compared: per digit, chain points 1..=3 (15 points), in the palm frame.
fn palm_points(layout: KeypointLayout, points: &[Point3<f64>]) -> Result<Vec<Vector3<f64>>, Error> {
    let palm = PalmFrame::from_landmarks(&layout.palm_landmarks(points))?;
    Ok(Finger::ALL
        .iter()
        .flat_map(|&f| layout.chain(f)[1..].to_vec())
        .map(|i| palm.point_to_palm(&points[i]))
        .collect())
}

fn weights() -> impl Iterator<Item = f64> {
    (0..15).map(|i| if i % 3 == 2 { 1.0 } else { 0.5 })
}

fn residuals(
    shape: &HumanHandShape,
    angles: &[f64; POSE_ANGLES],
    target: &[Vector3<f64>],
    rest: &[f64; POSE_ANGLES],
) -> Result<DVector<f64>, Error> {
    let layout = KeypointLayout::Lab22;
    let points = palm_points(
        layout,
        &shape.keypoints(&HumanHandPose::from_array(angles), layout),
    )?;
    let mut r = DVector::zeros(45 + POSE_ANGLES);
    for (k, ((h, t), w)) in points.iter().zip(target).zip(weights()).enumerate() {
        let d = (h - t) * w.sqrt();
        r.fixed_rows_mut::<3>(3 * k).copy_from(&d);
    }
    for i in 0..POSE_ANGLES {
        r[45 + i] = REST_WEIGHT.sqrt() * (angles[i] - rest[i]);
    }
    Ok(r)
}

fn clamp(angles: &mut [f64; POSE_ANGLES]) {
    for (a, (lo, hi)) in angles.iter_mut().zip(JOINT_RANGES_RAD) {
        *a = a.clamp(lo, hi);
    }
}

/// The posture of `shape` that copies the robot hand `model` at joint configuration `q`.
pub fn human_copy(
    shape: &HumanHandShape,
    model: &HandModel,
    q: &[f64],
) -> Result<HumanHandPose, Error> {
    let layout = KeypointLayout::Lab22;
    let robot = model.synthetic_keypoints(&model.forward_new(q)?, layout);
    let target = palm_points(layout, &robot)?;
    let rest = HumanHandPose::relaxed().to_array();
    let mut angles = rest;
    let mut r = residuals(shape, &angles, &target, &rest)?;
    let mut lambda = 1e-3;
    for _ in 0..ITERATIONS {
        let mut jac = DMatrix::zeros(r.len(), POSE_ANGLES);
        for i in 0..POSE_ANGLES {
            let mut moved = angles;
            moved[i] += STEP_RAD;
            let ri = residuals(shape, &moved, &target, &rest)?;
            jac.set_column(i, &((ri - &r) / STEP_RAD));
        }
        let jt = jac.transpose();
        let mut h = &jt * &jac;
        for i in 0..POSE_ANGLES {
            h[(i, i)] += lambda * (1.0 + h[(i, i)]);
        }
        let Some(step) = h.cholesky().map(|c| c.solve(&(-&jt * &r))) else {
            break;
        };
        let mut trial = angles;
        for (a, s) in trial.iter_mut().zip(step.iter()) {
            *a += s;
        }
        clamp(&mut trial);
        let rt = residuals(shape, &trial, &target, &rest)?;
        if rt.norm_squared() < r.norm_squared() {
            let gain = r.norm_squared() - rt.norm_squared();
            angles = trial;
            r = rt;
            lambda = (lambda * 0.3).max(1e-9);
            if gain < 1e-14 {
                break;
            }
        } else {
            lambda *= 10.0;
            if lambda > 1e6 {
                break;
            }
        }
    }
    Ok(HumanHandPose::from_array(&angles))
}

/// The average hand's copy of each of the seven poses, in capture order (the same angles serve
/// every hand size: the model's proportions do not change with scale).
pub fn human_copies(model: &HandModel, poses: &PoseSet) -> Result<[HumanHandPose; 7], Error> {
    let shape = HumanHandShape::average();
    let mut out = [HumanHandPose::open(); 7];
    for (slot, pose) in out.iter_mut().zip(&poses.poses) {
        *slot = human_copy(&shape, model, &pose.joint_vector(model)?)?;
    }
    Ok(out)
}
