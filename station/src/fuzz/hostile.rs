//! Hostile values: keypoint frames and poses a broken or malicious sender could produce, each
//! named for the counts.

use msgs::{Point, Pose, Quaternion};
use nalgebra::{Point3, Vector3};

use super::rng::FuzzRng;

/// Values that are not finite or far beyond any hand.
const WILD: [f64; 7] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e30,
    -1e30,
    f64::MAX,
    f64::MIN_POSITIVE,
];

/// A hostile version of the plausible frame `valid`, and its kind's name.
pub fn hostile_points(
    rng: &mut FuzzRng,
    valid: &[Point3<f64>],
) -> (Vec<Point3<f64>>, &'static str) {
    let mut points = valid.to_vec();
    let n = points.len().max(1);
    let kind = match rng.below(9) {
        0 => {
            let i = rng.below(n);
            if let Some(p) = points.get_mut(i) {
                p.coords[rng.below(3)] = rng.pick(&[f64::NAN, f64::INFINITY, f64::NEG_INFINITY]);
            }
            "non_finite"
        }
        1 => {
            let value = rng.pick(&WILD);
            let i = rng.below(n);
            if let Some(p) = points.get_mut(i) {
                p.coords[rng.below(3)] = value;
            }
            "wild_value"
        }
        2 => {
            points = (0..n)
                .map(|_| {
                    Point3::new(
                        rng.range(-1.0, 1.0),
                        rng.range(-1.0, 1.0),
                        rng.range(-1.0, 1.0),
                    )
                })
                .collect();
            "garbage"
        }
        3 => {
            let len = rng.pick(&[0, 1, n - 1, n + 1, 3 * n]);
            points.resize(len, Point3::origin());
            "wrong_size"
        }
        4 => {
            let scale = rng.pick(&[1e30, 1e3, 3.0, 0.5, 1e-3, 1e-300, 0.0]);
            points.iter_mut().for_each(|p| p.coords *= scale);
            "scaled"
        }
        5 => {
            let i = 1 + rng.below(n.saturating_sub(1).max(1));
            let jump = Vector3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            );
            if let Some(p) = points.get_mut(i) {
                *p += jump * rng.range(0.05, 0.6);
            }
            "finger_jump"
        }
        6 => {
            // Every point on one line through the wrist: bones may pass, the palm collapses.
            let wrist = points.first().copied().unwrap_or_else(Point3::origin);
            let axis = Vector3::new(0.0, 0.0, 1.0);
            points
                .iter_mut()
                .for_each(|p| *p = wrist + axis * (*p - wrist).norm());
            "collapsed_palm"
        }
        7 => {
            let offset = Vector3::new(
                rng.range(-5.0, 5.0),
                rng.range(-5.0, 5.0),
                rng.range(-5.0, 5.0),
            );
            points.iter_mut().for_each(|p| *p += offset);
            "whole_hand_teleport"
        }
        _ => {
            let scale = rng.range(0.7, 1.4);
            let wrist = points.first().copied().unwrap_or_else(Point3::origin);
            points
                .iter_mut()
                .for_each(|p| *p = wrist + (*p - wrist) * scale);
            "resized_hand"
        }
    };
    (points, kind)
}

/// A hostile version of the pose `valid`, and its kind's name.
pub fn hostile_pose(rng: &mut FuzzRng, valid: &Pose) -> (Pose, &'static str) {
    let mut pose = *valid;
    let kind = match rng.below(8) {
        0 => {
            *position_field(&mut pose, rng.below(3)) = rng.pick(&WILD);
            "wild_position"
        }
        1 => {
            *orientation_field(&mut pose, rng.below(4)) = rng.pick(&WILD);
            "wild_orientation"
        }
        2 => {
            *position_field(&mut pose, rng.below(3)) = rng.pick(&[150.0, -150.0, 99.0, -99.0]);
            "far_position"
        }
        3 => {
            let scale = rng.pick(&[0.0, 2.0, 0.5, 1.0 + 5e-7, 1.0 + 2e-6]);
            let q = &mut pose.orientation;
            (q.x, q.y, q.z, q.w) = (q.x * scale, q.y * scale, q.z * scale, q.w * scale);
            "scaled_quaternion"
        }
        4 => {
            pose.orientation = random_unit_quaternion(rng);
            "random_orientation"
        }
        5 => {
            for axis in 0..3 {
                *position_field(&mut pose, axis) += rng.range(-0.8, 0.8);
            }
            "position_jump"
        }
        6 => {
            pose.orientation = Quaternion {
                x: -pose.orientation.x,
                y: -pose.orientation.y,
                z: -pose.orientation.z,
                w: -pose.orientation.w,
            };
            "negated_quaternion"
        }
        _ => {
            pose.position = Point {
                x: rng.range(-2.0, 2.0),
                y: rng.range(-2.0, 2.0),
                z: rng.range(-2.0, 2.0),
            };
            "random_position"
        }
    };
    (pose, kind)
}

/// A uniformly random unit quaternion.
pub fn random_unit_quaternion(rng: &mut FuzzRng) -> Quaternion {
    loop {
        let v = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let norm = v.iter().map(|c| c * c).sum::<f64>().sqrt();
        if norm > 0.1 && norm <= 1.0 {
            return Quaternion {
                x: v[0] / norm,
                y: v[1] / norm,
                z: v[2] / norm,
                w: v[3] / norm,
            };
        }
    }
}

fn position_field(pose: &mut Pose, axis: usize) -> &mut f64 {
    match axis {
        0 => &mut pose.position.x,
        1 => &mut pose.position.y,
        _ => &mut pose.position.z,
    }
}

fn orientation_field(pose: &mut Pose, axis: usize) -> &mut f64 {
    match axis {
        0 => &mut pose.orientation.x,
        1 => &mut pose.orientation.y,
        2 => &mut pose.orientation.z,
        _ => &mut pose.orientation.w,
    }
}
