//! Pinch poses: thumb and finger angles that bring the thumb tip to a given distance from a
//! fingertip.
//!
//! ## Problem
//!
//! For a finger `f` and a requested gap `g` (metres), find angles `θ` (the thumb's four, and
//! the finger's MCP flexion, MCP abduction and PIP flexion, with DIP = [`DIP_PER_PIP`] · PIP as
//! in a natural curl) such that the tip-to-tip vector `d(θ) = p_thumb(θ) − p_f(θ)` has length
//! `g`. The residual is the vector
//!
//! ```text
//! r(θ) = d(θ) − g · d(θ)/‖d(θ)‖          (zero exactly when ‖d‖ = g)
//! ```
//!
//! three equations in seven unknowns. Starting from a hand-picked pinch posture for that
//! finger (thumb opposed towards it, finger half curled, the other fingers
//! [`HumanHandPose::relaxed`]), damped least-squares (Levenberg–Marquardt in its minimum-norm
//! form) steps
//!
//! ```text
//! Δ = −Jᵀ (J Jᵀ + λ² I)⁻¹ r,      λ = 2 mm · scale,
//! ```
//!
//! with `J = ∂r/∂θ` by central differences (`h = 10⁻⁶ rad`), each iterate clamped into
//! [`super::pose::JOINT_RANGES_RAD`]; a step that does not lower `‖r‖` is halved (up to four
//! times), and the solve stops when none does, after 100 steps, or at `‖r‖ < 0.1 µm`. Minimum-norm steps change the start posture as little as
//! the gap requires, so the result stays natural and is the same every time (no randomness).
//! Every length scales with the hand and the angles do not, so the solution does not depend
//! on [`HumanHandShape::scale`]; λ scales with it to keep the steps identical.

use nalgebra::{Matrix3, SMatrix, Vector3};

use super::pose::{HumanHandPose, JOINT_RANGES_RAD, POSE_ANGLES};
use super::shape::HumanHandShape;
use crate::error::Error;
use crate::finger::Finger;

/// DIP flexion per radian of PIP flexion in a pinch (the usual natural coupling, ≈ 2/3).
pub const DIP_PER_PIP: f64 = 0.67;

/// Largest gap [`pinch_pose`] accepts, metres.
pub const MAX_PINCH_GAP_M: f64 = 0.03;

/// Gauss–Newton iterations at most.
const MAX_ITERATIONS: u32 = 100;

/// Stop when `|‖d‖ − g|` is below this, metres (at scale 1).
const TOLERANCE_M: f64 = 1e-7;

/// A pinch pose and how well it met the request.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinchPose {
    /// The pose.
    pub pose: HumanHandPose,
    /// Thumb-tip to fingertip distance it achieves, metres.
    pub gap_m: f64,
    /// Damped Gauss–Newton iterations used.
    pub iterations: u32,
}

/// Positions of the free angles in [`HumanHandPose::to_array`]: thumb CMC flexion, CMC
/// abduction, MCP, IP; the finger's MCP flexion, MCP abduction, PIP (DIP follows PIP).
fn free_angles(finger: Finger) -> [usize; 7] {
    let f = 4 * finger.index();
    [0, 1, 2, 3, f, f + 1, f + 2]
}

/// The start posture for a pinch with `finger` (index, middle, ring or little).
fn start_pose(finger: Finger) -> HumanHandPose {
    let k = finger.index() as f64 - 1.0; // 0 for the index … 3 for the little finger
    let mut pose = HumanHandPose::relaxed();
    pose.thumb.cmc_flexion_rad = 0.25 + 0.2 * k;
    pose.thumb.cmc_abduction_rad = 0.7 + 0.05 * k;
    pose.thumb.mcp_flexion_rad = 0.25;
    pose.thumb.ip_flexion_rad = 0.25;
    if let Some(f) = pose.finger_mut(finger) {
        f.mcp_flexion_rad = 0.6 + 0.1 * k;
        f.mcp_abduction_rad = 0.0;
        f.pip_flexion_rad = 0.6 + 0.1 * k;
        f.dip_flexion_rad = DIP_PER_PIP * f.pip_flexion_rad;
    }
    pose
}

/// Set the free angles of `pose` (clamped to their ranges) and the coupled DIP.
fn with_free(pose: &mut [f64; POSE_ANGLES], idx: &[usize; 7], values: &[f64; 7]) {
    for (&i, &v) in idx.iter().zip(values) {
        pose[i] = v.clamp(JOINT_RANGES_RAD[i].0, JOINT_RANGES_RAD[i].1);
    }
    let (pip, dip) = (idx[6], idx[6] + 1);
    pose[dip] = (DIP_PER_PIP * pose[pip]).clamp(JOINT_RANGES_RAD[dip].0, JOINT_RANGES_RAD[dip].1);
}

fn tip_vector(shape: &HumanHandShape, pose: &[f64; POSE_ANGLES], finger: Finger) -> Vector3<f64> {
    let chains = shape.digit_chains(&HumanHandPose::from_array(pose));
    chains[Finger::Thumb.index()][3] - chains[finger.index()][3]
}

fn residual(d: &Vector3<f64>, gap_m: f64) -> Vector3<f64> {
    let n = d.norm();
    if n > 0.0 { d - d * (gap_m / n) } else { *d }
}

/// A pose of `shape` whose thumb tip is `gap_m` from the tip of `finger` (index, middle, ring
/// or little); see the module documentation for the method. `Err` for the thumb, or a gap
/// outside `[0, MAX_PINCH_GAP_M]` or not finite. Whether the gap was met is data: compare
/// [`PinchPose::gap_m`] with the request (within 1 µm for every realistic hand).
pub fn pinch_pose(shape: &HumanHandShape, finger: Finger, gap_m: f64) -> Result<PinchPose, Error> {
    if finger == Finger::Thumb {
        return Err(Error::ConfigRange {
            key: "pinch.finger".into(),
            value: finger.to_string(),
            allowed: "the thumb pinches one of index, middle, ring, little".into(),
        });
    }
    if !(gap_m.is_finite() && (0.0..=MAX_PINCH_GAP_M).contains(&gap_m)) {
        return Err(Error::ConfigRange {
            key: "pinch.gap_m".into(),
            value: gap_m.to_string(),
            allowed: format!("must be in [0, {MAX_PINCH_GAP_M}] m"),
        });
    }
    shape.validate()?;
    Ok(solve(shape, finger, gap_m))
}

/// The damped Gauss–Newton solve, for a validated request.
fn solve(shape: &HumanHandShape, finger: Finger, gap_m: f64) -> PinchPose {
    let idx = free_angles(finger);
    let mut pose = start_pose(finger).to_array();
    let lambda = 2e-3 * shape.scale;
    let h = 1e-6;
    let mut iterations = 0;
    let mut r = residual(&tip_vector(shape, &pose, finger), gap_m);
    while iterations < MAX_ITERATIONS && r.norm() > TOLERANCE_M * shape.scale {
        let x: [f64; 7] = idx.map(|i| pose[i]);
        let mut jacobian = SMatrix::<f64, 3, 7>::zeros();
        for k in 0..7 {
            let (mut plus, mut minus) = (x, x);
            plus[k] += h;
            minus[k] -= h;
            let (mut pp, mut pm) = (pose, pose);
            with_free(&mut pp, &idx, &plus);
            with_free(&mut pm, &idx, &minus);
            let rp = residual(&tip_vector(shape, &pp, finger), gap_m);
            let rm = residual(&tip_vector(shape, &pm, finger), gap_m);
            jacobian.set_column(k, &((rp - rm) / (2.0 * h)));
        }
        let jjt = jacobian * jacobian.transpose() + Matrix3::identity() * lambda * lambda;
        let Some(inverse) = jjt.try_inverse() else {
            break;
        };
        let step = -(jacobian.transpose() * inverse * r);
        iterations += 1;
        // Take the step, halved up to four times until it lowers the residual.
        let mut accepted = false;
        let mut fraction = 1.0;
        for _ in 0..5 {
            let next: [f64; 7] = std::array::from_fn(|k| x[k] + fraction * step[k]);
            let mut trial = pose;
            with_free(&mut trial, &idx, &next);
            let r_trial = residual(&tip_vector(shape, &trial, finger), gap_m);
            if r_trial.norm() < r.norm() {
                (pose, r, accepted) = (trial, r_trial, true);
                break;
            }
            fraction *= 0.5;
        }
        if !accepted {
            break;
        }
    }
    let pose = HumanHandPose::from_array(&pose);
    PinchPose {
        gap_m: shape.thumb_gap_m(&pose, finger),
        pose,
        iterations,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_finger_reaches_the_gap_within_ranges() {
        let shape = HumanHandShape::average();
        for finger in Finger::OPPOSING {
            let start = shape.thumb_gap_m(&start_pose(finger), finger);
            let p = pinch_pose(&shape, finger, 0.005).unwrap();
            println!(
                "{finger}: start gap {:.1} mm → {:.4} mm in {} iterations",
                start * 1e3,
                p.gap_m * 1e3,
                p.iterations
            );
            assert!((p.gap_m - 0.005).abs() < 1e-6, "{finger}: {}", p.gap_m);
            assert!(p.pose.within_ranges(), "{finger}");
            let f = p.pose.finger(finger).unwrap();
            assert!((f.dip_flexion_rad - DIP_PER_PIP * f.pip_flexion_rad).abs() < 1e-12);
        }
    }

    #[test]
    fn bad_requests_are_errors() {
        let shape = HumanHandShape::average();
        assert!(pinch_pose(&shape, Finger::Thumb, 0.005).is_err());
        assert!(pinch_pose(&shape, Finger::Index, -0.001).is_err());
        assert!(pinch_pose(&shape, Finger::Index, f64::NAN).is_err());
        assert!(pinch_pose(&shape.scaled(0.1), Finger::Index, 0.005).is_err());
    }
}
