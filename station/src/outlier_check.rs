//! A tracker's one-frame outlier: one point that leaps away from its own digit while the
//! points beside it on the digit stay put. Real motion moves a digit's points together (a
//! fingertip swings about the joint before it, the hand turns as a whole, the arm carries the
//! wrist); a camera tracker that misplaces one point for one frame (a fingertip snapping onto
//! its neighbour's, a point lost behind another finger) moves it alone, and a retargeter that
//! followed it would close a pinch the person never made.
//!
//! The test is on each point's motion relative to the wrist since the last accepted frame,
//! against what the points beside it on its digit's chain (wrist, base, the joints, the tip)
//! predict: their mean motion for a point between two, the chain's motion extrapolated for
//! the tip. A turn of the whole hand moves the points in proportion to their place, which the
//! prediction follows; a finger curling moves its points together. A point off its
//! prediction by `min_jump_m` or more has leapt alone. The frame gate holds such a frame back
//! for one frame: if the next frame confirms the new place (the leap was real, a fast flick),
//! it is accepted one frame late; if the point is back, the outlier never reached the
//! retargeter.

use nalgebra::{Point3, Vector3};
use retarget::{Finger, KeypointLayout};

/// When a point has leapt alone: off its prediction by `min_jump_m`, or, with `stretch`, off
/// it by that part's own jump and stretching or shrinking a bone of its digit's chain (to the
/// point before or after it) by its `min_stretch_m`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeapLimits {
    /// Off the prediction by this much, metres.
    pub min_jump_m: f64,
    /// The bone test, if any.
    pub stretch: Option<StretchLimits>,
}

/// A leap that stretches a bone. A hand's bones keep their length however far apart two
/// frames are, so these limits need not grow with the time between them as
/// [`LeapLimits::min_jump_m`] does: a tracker's outlier seen after a gap in the frames is still
/// one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StretchLimits {
    /// Off the prediction by this much, metres.
    pub min_jump_m: f64,
    /// A bone longer or shorter by this much, metres.
    pub min_stretch_m: f64,
}

/// The first point (layout index) that leapt alone from `last` to `points` by at least
/// `min_jump_m`, or None.
///
/// Both frames must have the layout's number of points (the gate checks that first).
pub fn isolated_leap(
    layout: KeypointLayout,
    points: &[Point3<f64>],
    last: &[Point3<f64>],
    min_jump_m: f64,
) -> Option<usize> {
    let limits = LeapLimits {
        min_jump_m,
        stretch: None,
    };
    leapt_point(layout, points, last, limits)
}

/// The first point that leapt alone from `last` to `points` under `limits`, or None, in one
/// pass over the digits.
pub fn leapt_point(
    layout: KeypointLayout,
    points: &[Point3<f64>],
    last: &[Point3<f64>],
    limits: LeapLimits,
) -> Option<usize> {
    let stretch =
        |a: usize, b: usize| ((points[a] - points[b]).norm() - (last[a] - last[b]).norm()).abs();
    first_leap(layout, points, last, |off_m, (digit, k)| {
        off_m >= limits.min_jump_m
            || limits.stretch.is_some_and(|s| {
                let after = digit
                    .get(k + 1)
                    .map_or(0.0, |&next| stretch(digit[k], next));
                off_m >= s.min_jump_m
                    && stretch(digit[k], digit[k - 1]).max(after) >= s.min_stretch_m
            })
    })
}

/// The first point of a digit chain (wrist, base, joints, tip) whose motion relative to the
/// wrist is off what its neighbours predict by `off_m` for which `leapt(off_m, (chain, k))`.
fn first_leap(
    layout: KeypointLayout,
    points: &[Point3<f64>],
    last: &[Point3<f64>],
    leapt: impl Fn(f64, ([usize; 5], usize)) -> bool,
) -> Option<usize> {
    let wrist = layout.wrist();
    let moved = |i: usize| -> Vector3<f64> {
        if i == wrist {
            return Vector3::zeros();
        }
        (points[i] - points[wrist]) - (last[i] - last[wrist])
    };
    for finger in Finger::ALL {
        let chain = layout.chain(finger);
        let digit = [wrist, chain[0], chain[1], chain[2], chain[3]];
        let moves = digit.map(moved);
        for k in 1..digit.len() {
            let predicted = match moves.get(k + 1) {
                Some(next) => (moves[k - 1] + next) / 2.0,
                None => moves[k - 1] * 2.0 - moves[k - 2],
            };
            if leapt((moves[k] - predicted).norm(), (digit, k)) {
                return Some(digit[k]);
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use retarget::HandModel;

    fn hand(fraction: f64) -> Vec<Point3<f64>> {
        let model = HandModel::orca_v1_right();
        let q: Vec<f64> = model
            .limits()
            .map(|l| l.lower_rad + fraction * (l.upper_rad - l.lower_rad))
            .collect();
        model.synthetic_keypoints(&model.forward_new(&q).unwrap(), KeypointLayout::Lab22)
    }

    const LAYOUT: KeypointLayout = KeypointLayout::Lab22;

    #[test]
    fn one_fingertip_leaping_alone_is_named() {
        let before = hand(0.3);
        let mut after = before.clone();
        let tip = LAYOUT.tip(Finger::Index);
        after[tip] += Vector3::new(0.0, 0.03, 0.0);
        assert_eq!(isolated_leap(LAYOUT, &after, &before, 0.02), Some(tip));
        // Under the jump, it is not one.
        after[tip] = before[tip] + Vector3::new(0.0, 0.015, 0.0);
        assert_eq!(isolated_leap(LAYOUT, &after, &before, 0.02), None);
    }

    #[test]
    fn a_leap_that_stretches_a_bone_is_named_and_a_swing_about_the_joint_is_not() {
        let before = hand(0.3);
        let tip = LAYOUT.tip(Finger::Index);
        let joint = LAYOUT.chain(Finger::Index)[2];
        // 3 cm straight away from the joint before it: the last bone 3 cm longer.
        let bone = (before[tip] - before[joint]).normalize();
        let mut stretched = before.clone();
        stretched[tip] += bone * 0.03;
        let limits = LeapLimits {
            min_jump_m: 0.05,
            stretch: Some(StretchLimits {
                min_jump_m: 0.02,
                min_stretch_m: 0.01,
            }),
        };
        assert_eq!(leapt_point(LAYOUT, &stretched, &before, limits), Some(tip));
        // The same 3 cm across the bone, swinging about the joint: the bone keeps its length
        // to first order (under 1 cm), so the stretch test lets it be.
        let across = bone.cross(&Vector3::z()).normalize();
        let radius = (before[tip] - before[joint]).norm();
        let turned = nalgebra::Rotation3::from_axis_angle(
            &nalgebra::Unit::new_normalize(bone.cross(&across)),
            0.03 / radius,
        );
        let mut swung = before.clone();
        swung[tip] = before[joint] + turned * (before[tip] - before[joint]);
        assert!((swung[tip] - before[tip]).norm() > 0.025);
        assert_eq!(leapt_point(LAYOUT, &swung, &before, limits), None);
        assert_eq!(isolated_leap(LAYOUT, &swung, &before, 0.02), Some(tip));
    }

    #[test]
    fn a_middle_joint_leaping_alone_is_named() {
        let before = hand(0.3);
        let mut after = before.clone();
        let joint = LAYOUT.chain(Finger::Ring)[1];
        after[joint] += Vector3::new(0.04, 0.0, 0.0);
        assert_eq!(isolated_leap(LAYOUT, &after, &before, 0.02), Some(joint));
    }

    #[test]
    fn fingers_closing_together_and_the_whole_hand_turning_are_not_leaps() {
        // Every joint from 20 % to 32 % of its range in one frame: tips move centimetres,
        // and the joints before them move with them.
        let (open, closed) = (hand(0.2), hand(0.32));
        let tip_moved =
            (closed[LAYOUT.tip(Finger::Index)] - open[LAYOUT.tip(Finger::Index)]).norm();
        assert!(tip_moved > 0.02, "the tip moved {tip_moved} m");
        assert_eq!(isolated_leap(LAYOUT, &closed, &open, 0.02), None);
        // The whole hand carried and turned 0.3 rad about the wrist in one frame.
        let wrist = open[LAYOUT.wrist()];
        let turn = nalgebra::Rotation3::from_axis_angle(&Vector3::y_axis(), 0.3);
        let carried: Vec<_> = open
            .iter()
            .map(|p| wrist + turn * (p - wrist) + Vector3::new(0.3, -0.2, 0.1))
            .collect();
        let tip_moved = ((carried[LAYOUT.tip(Finger::Middle)] - carried[LAYOUT.wrist()])
            - (open[LAYOUT.tip(Finger::Middle)] - wrist))
            .norm();
        assert!(
            tip_moved > 0.04,
            "the tip moved {tip_moved} m relative to the wrist"
        );
        assert_eq!(isolated_leap(LAYOUT, &carried, &open, 0.02), None);
    }
}
