//! What any retargeter could reach: per digit, the distance from the scaled human fingertip
//! target to the nearest fingertip position the robot reaches on a grid over that digit's
//! joints within their limits.
//!
//! For digit `i`, the targets are `s*·h_{t,i}` (human fingertip in the human palm frame,
//! scaled by the global least-squares scale `s*` of [`super`]) over the frames with a finite
//! command. The reachable set is approximated by the fingertip, in the robot palm frame, of
//! every configuration on a regular grid over the joints that move that digit's tip alone
//! (limits included; the other joints at 0 clamped into their limits, which moves neither the
//! palm frame nor this tip). The bound is the mean over frames of the distance to the nearest
//! grid point, millimetres: it overestimates the true distance by at most half the grid's
//! spacing at the tip. Pure.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::report::global_scale;
use super::scale_free::own_scale;
use super::{FrameSample, QualityRecorder};
use crate::error::Error;
use crate::finger::Finger;
use crate::hand_model::{HandModel, Limits};

/// Default most grid configurations per digit: 58 steps per joint for a three-joint finger,
/// 21 for a four-joint thumb (ORCA v1), about a second for a recording of 700 frames.
pub const REACH_GRID_MAX_CONFIGURATIONS: usize = 200_000;

/// Reachability over a recording (see this module's doc).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Reachability {
    /// The global scale `s*` the targets are scaled by.
    pub tip_scale: f64,
    /// Most grid configurations per digit.
    pub grid_max_configurations: usize,
    /// Per digit, thumb to little.
    pub per_digit: Vec<DigitReach>,
}

/// One digit's reachability.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DigitReach {
    /// Digit name.
    pub digit: String,
    /// The digit's own scale `Σ r·h / Σ |h|²` (as [`super::DigitQuality::tip_own_scale`]).
    pub own_scale: Option<f64>,
    /// Joints moving this digit's tip alone (the grid's dimensions).
    pub joints: usize,
    /// Grid steps per joint (limits included).
    pub grid_steps_per_joint: usize,
    /// Mean over frames of the distance from `s*·h` to the nearest grid fingertip, mm;
    /// `None` without a frame with a finite command.
    pub nearest_reachable_mean_mm: Option<f64>,
}

/// The largest `s ≥ 2` with `s^joints ≤ max_configurations` (2 when even that is more, or
/// without joints).
pub fn grid_steps(joints: usize, max_configurations: usize) -> usize {
    let fits = |s: usize| {
        (0..joints)
            .try_fold(1usize, |n, _| n.checked_mul(s))
            .is_some_and(|n| n <= max_configurations)
    };
    if joints == 0 {
        return 2; // one configuration whatever the steps
    }
    let mut steps = 2;
    while fits(steps + 1) {
        steps += 1;
    }
    steps
}

/// Every grid configuration of `limits` with `steps` values per joint, limits included.
pub fn grid(limits: &[Limits], steps: usize) -> Vec<Vec<f64>> {
    let value = |l: &Limits, k: usize| {
        l.lower_rad + (l.upper_rad - l.lower_rad) * k as f64 / (steps.max(2) - 1) as f64
    };
    let mut configurations = vec![Vec::new()];
    for l in limits {
        configurations = configurations
            .into_iter()
            .flat_map(|c| {
                (0..steps.max(2)).map(move |k| {
                    let mut next = c.clone();
                    next.push(value(l, k));
                    next
                })
            })
            .collect();
    }
    configurations
}

/// Distance from `target` to the nearest of `points` (infinite when there are none).
pub fn nearest_distance(points: &[Vector3<f64>], target: &Vector3<f64>) -> f64 {
    points
        .iter()
        .map(|p| (p - target).norm_squared())
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}

/// The degrees of freedom moving `digit`'s tip alone, and the fingertips (robot palm frame,
/// metres) of every configuration of a grid over them with at most `max_configurations`.
fn reachable_tips(
    model: &HandModel,
    dof_digit: &[Option<Finger>],
    digit: Finger,
    max_configurations: usize,
) -> Result<(usize, usize, Vec<Vector3<f64>>), Error> {
    let dofs: Vec<usize> = (0..model.dof())
        .filter(|&j| dof_digit[j] == Some(digit))
        .collect();
    let limits: Vec<Limits> = dofs.iter().map(|&j| model.dofs()[j].limits).collect();
    let steps = grid_steps(dofs.len(), max_configurations);
    let mut q: Vec<f64> = model
        .limits()
        .map(|l| 0.0_f64.clamp(l.lower_rad, l.upper_rad))
        .collect();
    let mut fk = model.fk_state();
    let mut tips = Vec::new();
    for configuration in grid(&limits, steps) {
        for (&j, v) in dofs.iter().zip(&configuration) {
            q[j] = *v;
        }
        model.forward(&q, &mut fk)?;
        let palm = model.palm_frame(&fk)?;
        tips.push(palm.point_to_palm(&fk.position(model.frames.tip(digit))));
    }
    Ok((dofs.len(), steps, tips))
}

/// One digit's reachability over `samples`, targets scaled by `scale`.
fn digit_reach(
    samples: &[FrameSample],
    scale: f64,
    digit: Finger,
    (joints, steps, tips): (usize, usize, Vec<Vector3<f64>>),
) -> DigitReach {
    let i = digit.index();
    let distances: Vec<f64> = samples
        .iter()
        .filter(|s| s.robot_tips.is_some())
        .map(|s| nearest_distance(&tips, &(s.human_tips[i] * scale)) * 1e3)
        .collect();
    DigitReach {
        digit: digit.name().into(),
        own_scale: own_scale(samples, digit).scale,
        joints,
        grid_steps_per_joint: steps,
        nearest_reachable_mean_mm: (!distances.is_empty())
            .then(|| distances.iter().sum::<f64>() / distances.len() as f64),
    }
}

impl QualityRecorder {
    /// The reachability of the frames pushed so far (see the module's doc), on
    /// grids of at most `max_configurations` per digit. `Err` only when the model's forward
    /// kinematics fails (a collapsed palm).
    pub fn reachability(&self, max_configurations: usize) -> Result<Reachability, Error> {
        let (scale, _) = global_scale(&self.samples);
        let per_digit = Finger::ALL
            .into_iter()
            .map(|digit| {
                let tips = reachable_tips(&self.model, &self.dof_digit, digit, max_configurations)?;
                Ok(digit_reach(&self.samples, scale, digit, tips))
            })
            .collect::<Result<Vec<_>, Error>>()?;
        Ok(Reachability {
            tip_scale: scale,
            grid_max_configurations: max_configurations,
            per_digit,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::keypoint_layout::KeypointLayout;

    #[test]
    fn grid_steps_are_the_largest_that_fit() {
        assert_eq!(grid_steps(3, 200_000), 58); // 58³ = 195,112; 59³ = 205,379
        assert_eq!(grid_steps(4, 200_000), 21); // 21⁴ = 194,481; 22⁴ = 234,256
        assert_eq!(grid_steps(2, 3), 2);
        assert_eq!(grid_steps(0, 10), 2); // no joint: one configuration, any step count
    }

    #[test]
    fn the_grid_spans_the_limits_inclusively() {
        let limits = [
            Limits {
                lower_rad: -1.0,
                upper_rad: 1.0,
            },
            Limits {
                lower_rad: 0.0,
                upper_rad: 0.5,
            },
        ];
        let g = grid(&limits, 3);
        assert_eq!(g.len(), 9);
        assert_eq!(g[0], vec![-1.0, 0.0]);
        assert_eq!(g[4], vec![0.0, 0.25]);
        assert_eq!(g[8], vec![1.0, 0.5]);
    }

    #[test]
    fn a_set_containing_the_target_is_at_distance_zero() {
        let points = [Vector3::new(1.0, 0.0, 0.0), Vector3::new(0.0, 2.0, 0.0)];
        assert_eq!(nearest_distance(&points, &Vector3::new(0.0, 2.0, 0.0)), 0.0);
        assert!((nearest_distance(&points, &Vector3::new(0.0, 0.0, 0.0)) - 1.0).abs() < 1e-12);
        assert!(nearest_distance(&[], &Vector3::zeros()).is_infinite());
    }

    #[test]
    fn the_robot_at_grid_points_as_its_own_human_is_reachable_with_unit_scales() {
        let model = HandModel::orca_v1_right();
        let layout = KeypointLayout::Lab22;
        let mut recorder = QualityRecorder::new(model.clone(), layout);
        // Lower limits and upper limits are grid points of every digit's grid.
        for q in [
            model.limits().map(|l| l.lower_rad).collect::<Vec<_>>(),
            model.limits().map(|l| l.upper_rad).collect(),
        ] {
            let keypoints = model.synthetic_keypoints(&model.forward_new(&q).unwrap(), layout);
            recorder.push(&keypoints, &q).unwrap();
        }
        let reach = recorder.reachability(2_000).unwrap();
        assert!((reach.tip_scale - 1.0).abs() < 1e-9, "{reach:?}");
        assert_eq!(reach.per_digit.len(), 5);
        for d in &reach.per_digit {
            assert!(d.joints >= 3, "{d:?}");
            assert!((d.own_scale.unwrap() - 1.0).abs() < 1e-9, "{d:?}");
            assert!(d.nearest_reachable_mean_mm.unwrap() < 1e-6, "{d:?}");
        }
    }
}
