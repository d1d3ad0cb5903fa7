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
//! prediction by `min_jump_m` or more has leapt alone. The frame gate puts such a point back
//! where its digit predicts it ([`repaired`]) and passes the frame on: the rest of the hand
//! stays current, so the retargeter, whose command follows the frames with a smoothing term,
//! does not fall a frame behind and catch up over the frames after (a held frame did: its
//! joints lagged the clean command by 0.14, 0.09, 0.06 rad over the three frames after a hold
//! on a real recording). If the next frame confirms the new place (the leap was real, a fast
//! flick), it is accepted whatever it shows, so the point is one frame late; if the point is
//! back, the outlier never reached the retargeter.

use nalgebra::{Isometry3, Matrix3, Point3, UnitQuaternion, Vector3};
use retarget::{Finger, KeypointLayout};

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
    let wrist = layout.wrist();
    for finger in Finger::ALL {
        let digit = digit_chain(layout, finger);
        let moves = digit.map(|i| moved(points, last, wrist, i));
        for k in 1..digit.len() {
            if (moves[k] - predicted_move(&moves, k)).norm() >= min_jump_m {
                return Some(digit[k]);
            }
        }
    }
    None
}

/// `points` with one point of the digit that holds point `flagged` (as [`isolated_leap`] names
/// it) put back where the rest of the hand predicts it from `last`: carried by the palm's
/// rigid motion since `last` (wrist and digit bases, least squares, without this digit's
/// base), plus,
/// for a joint or tip, what its digit did beyond that motion (the mean of its neighbours'
/// for a joint, the chain's extrapolated for a tip; a base moves with the palm). After a gap
/// in the frames the hand may have turned: a prediction from the motion relative to the
/// wrist alone put a digit base 1.2 cm off after 70 ms, and with it the palm frame and every
/// joint.
///
/// Which point: the one whose repair leaves the digit most like itself, the least change of
/// its bone lengths since `last` plus the largest motion still off its prediction. A tip that
/// leapt also puts the joint before it off its prediction (by half the leap), and the check
/// may name that joint first; moving the joint halfway to the tip would make the motion
/// consistent too, but only putting the tip back keeps the bones' lengths. None for a
/// `flagged` index on no digit or a palm whose motion cannot be fitted.
pub fn repaired(
    layout: KeypointLayout,
    points: &[Point3<f64>],
    last: &[Point3<f64>],
    flagged: usize,
) -> Option<Vec<Point3<f64>>> {
    let wrist = layout.wrist();
    let digit = Finger::ALL
        .iter()
        .map(|&f| digit_chain(layout, f))
        .find(|d| d[1..].contains(&flagged))?;
    let carried = palm_motion(layout, points, last, digit[1])?;
    let beyond = digit.map(|i| points[i] - carried * last[i]);
    let candidate = |k: usize| {
        let own = match k {
            1 => Vector3::zeros(),
            _ => predicted_move(&beyond, k),
        };
        let mut out = points.to_vec();
        out[digit[k]] = carried * last[digit[k]] + own;
        (digit_change(&digit, &out, last, wrist), out)
    };
    (1..digit.len())
        .map(candidate)
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, out)| out)
}

/// The palm's rigid motion from `last` to `points`: least squares over the wrist and the
/// digit bases but `left_out` (the flagged digit's base, which may be the leapt point; the
/// four others and the wrist fit it). None where it cannot be fitted.
fn palm_motion(
    layout: KeypointLayout,
    points: &[Point3<f64>],
    last: &[Point3<f64>],
    left_out: usize,
) -> Option<Isometry3<f64>> {
    let palm: Vec<usize> = std::iter::once(layout.wrist())
        .chain(Finger::ALL.map(|f| layout.base(f)))
        .filter(|&i| i != left_out)
        .collect();
    let from: Vec<Point3<f64>> = palm.iter().map(|&i| last[i]).collect();
    let to: Vec<Point3<f64>> = palm.iter().map(|&i| points[i]).collect();
    rigid_motion(&from, &to)
}

/// The rigid motion that best carries `from` onto `to` (least squares over the pairs, no
/// reflection), or None for fewer than three pairs or a failed decomposition.
fn rigid_motion(from: &[Point3<f64>], to: &[Point3<f64>]) -> Option<Isometry3<f64>> {
    if from.len() < 3 || from.len() != to.len() {
        return None;
    }
    let n = from.len() as f64;
    let centre = |p: &[Point3<f64>]| p.iter().map(|q| q.coords).sum::<Vector3<f64>>() / n;
    let (cf, ct) = (centre(from), centre(to));
    let h: Matrix3<f64> = from
        .iter()
        .zip(to)
        .map(|(f, t)| (f.coords - cf) * (t.coords - ct).transpose())
        .sum();
    let svd = h.svd(true, true);
    let (u, v_t) = (svd.u?, svd.v_t?);
    let mut d = Matrix3::identity();
    d[(2, 2)] = (v_t.transpose() * u.transpose()).determinant().signum();
    let r = v_t.transpose() * d * u.transpose();
    let rotation = UnitQuaternion::from_matrix(&r);
    let translation = ct - rotation * cf;
    Some(Isometry3::from_parts(translation.into(), rotation))
}

/// How unlike itself a digit is from `last` to `points`: its bones' length changes summed,
/// plus the largest motion off its prediction, metres.
fn digit_change(
    digit: &[usize; 5],
    points: &[Point3<f64>],
    last: &[Point3<f64>],
    wrist: usize,
) -> f64 {
    let length = |p: &[Point3<f64>], a: usize, b: usize| (p[a] - p[b]).norm();
    let bones: f64 = digit
        .windows(2)
        .map(|w| (length(points, w[0], w[1]) - length(last, w[0], w[1])).abs())
        .sum();
    let moves = digit.map(|i| moved(points, last, wrist, i));
    let off = (1..digit.len())
        .map(|k| (moves[k] - predicted_move(&moves, k)).norm())
        .fold(0.0, f64::max);
    bones + off
}

/// A digit's chain from the wrist: wrist, base, the joints, the tip.
fn digit_chain(layout: KeypointLayout, finger: Finger) -> [usize; 5] {
    let chain = layout.chain(finger);
    [layout.wrist(), chain[0], chain[1], chain[2], chain[3]]
}

/// Point `i`'s motion relative to the wrist from `last` to `points`.
fn moved(points: &[Point3<f64>], last: &[Point3<f64>], wrist: usize, i: usize) -> Vector3<f64> {
    if i == wrist {
        return Vector3::zeros();
    }
    (points[i] - points[wrist]) - (last[i] - last[wrist])
}

/// What the points beside chain point `k` predict of its motion: their mean for a point
/// between two, the chain's motion extrapolated for the tip.
fn predicted_move(moves: &[Vector3<f64>; 5], k: usize) -> Vector3<f64> {
    match moves.get(k + 1) {
        Some(next) => (moves[k - 1] + next) / 2.0,
        None => moves[k - 1] * 2.0 - moves[k - 2],
    }
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
    fn a_repaired_point_is_back_on_its_digit_and_no_longer_a_leap() {
        // The hand closes a little (every point moves) while the index tip leaps 4 cm.
        let (before, moved_on) = (hand(0.30), hand(0.33));
        let tip = LAYOUT.tip(Finger::Index);
        let mut outlier = moved_on.clone();
        outlier[tip] += Vector3::new(0.0, 0.04, 0.0);
        // The check names the joint before the tip (off its prediction by half the leap).
        let flagged = isolated_leap(LAYOUT, &outlier, &before, 0.02).unwrap();
        assert!(LAYOUT.chain(Finger::Index).contains(&flagged));
        let fixed = repaired(LAYOUT, &outlier, &before, flagged).unwrap();
        assert_eq!(isolated_leap(LAYOUT, &fixed, &before, 0.02), None);
        assert!(
            (fixed[tip] - moved_on[tip]).norm() < 0.005,
            "near where the tip went: {} m off",
            (fixed[tip] - moved_on[tip]).norm()
        );
        let others_kept = (0..fixed.len())
            .filter(|&i| i != tip)
            .all(|i| fixed[i] == outlier[i]);
        assert!(others_kept, "only the leapt point is replaced");
        // A middle joint is put at its neighbours' mean motion.
        let joint = LAYOUT.chain(Finger::Ring)[1];
        let mut off = moved_on.clone();
        off[joint] += Vector3::new(0.04, 0.0, 0.0);
        let flagged = isolated_leap(LAYOUT, &off, &before, 0.02).unwrap();
        let fixed = repaired(LAYOUT, &off, &before, flagged).unwrap();
        let others_kept = (0..fixed.len())
            .filter(|&i| i != joint)
            .all(|i| fixed[i] == off[i]);
        assert!(others_kept, "the joint is the one replaced");
        assert!((fixed[joint] - moved_on[joint]).norm() < 0.005);
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
