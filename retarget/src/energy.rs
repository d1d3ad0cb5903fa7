//! The retargeting energy over 20 key vectors, with the pinch blend and the robust residual.
//!
//! All vectors live in the palm frame (human palm frame for targets, robot palm frame for the
//! robot), metres. The points are the five fingertips (indices 0–4, thumb first) and the five
//! digit mid points (5–9: finger PIP, thumb MCP). Key vector `k` runs from `from` (the palm
//! centre, or a point) to a point; its residual is `e_k(q) = r_k(q) − t_k` and its energy `w_k · ρ(‖e_k‖)` with the
//! Huber function `ρ(x) = ½x²` for `x ≤ δ`, `δ(x − ½δ)` beyond.

#![allow(non_snake_case)] // H, g: the Gauss–Newton normal equations

use nalgebra::{DMatrix, DVector, Matrix3xX, Vector3};

use crate::finger::Finger;
use crate::human_key_vectors::HumanKeyVectors;
use crate::retarget_config::RetargetConfig;

/// Number of key vectors: 5 palm → tip, 10 tip → tip, 5 palm → mid.
pub const KEY_VECTORS: usize = 20;

/// Number of points the key vectors connect: 5 fingertips, then 5 digit mid points.
pub const POINTS: usize = 10;

/// Index of a digit's mid point among the [`POINTS`].
pub const fn mid(finger: Finger) -> usize {
    5 + finger.index()
}

/// One weighted key vector target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KeyVector {
    /// Start: `None` for the palm centre, else a point (fingertip `0..5`, mid point `5..10`).
    pub from: Option<usize>,
    /// End point.
    pub to: usize,
    /// Target vector in the palm frame, metres.
    pub target: Vector3<f64>,
    /// Weight (dimensionless).
    pub weight: f64,
}

impl KeyVector {
    /// The robot's version of this vector, from points in the robot palm frame.
    pub fn robot(&self, points: &[Vector3<f64>; POINTS]) -> Vector3<f64> {
        match self.from {
            None => points[self.to],
            Some(from) => points[self.to] - points[from],
        }
    }
}

/// Smooth pinch activation: 1 at or below `engage`, 0 at or above `release`, C¹ in between.
pub fn pinch_activation(distance_m: f64, engage_m: f64, release_m: f64) -> f64 {
    let x = ((release_m - distance_m) / (release_m - engage_m)).clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// Per finger (index first), the extra weight of the thumb → finger vector while the human's
/// thumb approaches it: only the finger the thumb is nearest, rising smoothly from 0 at
/// `pinch.approach_m` to `w_pt − w_tt` at `pinch.release_m`, where the pinch takes over.
///
/// **Why.** Before a pinch begins, the robot's thumb–finger gap is set by where each tip is
/// placed. For a thumb the robot cannot reproduce (a camera tracker's thumb, a hand unlike
/// the robot's), that gap stays far wider than the human's: on a 30 Hz recording the
/// human's thumb–index distance fell 60 → 43 → 33 → 19 mm while the robot's stayed at 68 mm
/// until the pinch began at 40 mm, and then the step limit could not close it in the pinch's
/// first frame. Weighted as much as a fingertip's placement by the time the pinch begins, the
/// vector makes the robot's gap follow the human's on the way in (64 → 43 → 15.0 mm there: the
/// pinch's first frame closed, just).
/// Only the nearest finger gains it: the others' vectors would hold the thumb where they are.
pub fn approach_weights(pinch_distances_m: &[f64; 4], config: &RetargetConfig) -> [f64; 4] {
    let p = &config.pinch;
    let w = &config.weights;
    let extra = (w.palm_to_tip - w.tip_to_tip).max(0.0);
    if p.approach_m <= p.release_m || p.weight <= 0.0 || extra <= 0.0 {
        return [0.0; 4];
    }
    let nearest = (0..4).min_by(|&a, &b| pinch_distances_m[a].total_cmp(&pinch_distances_m[b]));
    std::array::from_fn(|i| {
        if Some(i) == nearest {
            extra * pinch_activation(pinch_distances_m[i], p.release_m, p.approach_m)
        } else {
            0.0
        }
    })
}

fn unit_or_zero(v: &Vector3<f64>) -> Vector3<f64> {
    let n = v.norm();
    if n > 1e-9 { v / n } else { Vector3::zeros() }
}

/// The 20 key vector targets for one frame of human input.
///
/// - palm → tip `i`: target `t = h_i`, weight `w_pt · (1 − β_i)` (`β_thumb = 0`);
/// - palm → mid point `i`: target `t = m_i`, weight `w_pm` (keeps flexion on the human's
///   branch: a straight-ish finger reaches the same tip with its PIP bent either way);
/// - thumb → finger `k`: with `β_k` the pinch activation of the human thumb–finger distance,
///   target `ĥ · ((1 − β_k)‖h‖ + β_k · gap)` (the human vector with no pinch, the closed gap
///   at a full one), weight `w_tt + max(β_k w_pinch, a_k)`, `a_k` the approach weight of
///   [`approach_weights`];
/// - finger `a` → finger `b`: with `β = max(β_a, β_b)`, the human vector at weight
///   `w_tt · (1 − β)` and the separation goal `ĥ · max(‖h‖, separation)` at `β · w_sep`: a
///   finger next to a pinching one keeps its distance.
///
/// **A pinching finger goes to the thumb.** The robot's thumb reaches a smaller region than
/// a human's (the ORCA's thumb abduction sits on its limit in most frames of a real glove
/// recording), so the place a human pinches is often out of its reach. A finger held at the
/// human's place by its palm → tip vector and its vectors to the other fingers then stops
/// between that place and the robot's thumb, and the pinch closes only part of the way: on
/// synthetic hands of varied proportions, held thumb–index pinches ended 8.7 mm apart (median,
/// 12.9 mm worst of 16) where the pinch aims at 5 mm, and one user's pinches closed in 72 % of
/// the frames. So as a finger's pinch activation grows, its own placement gives way to the
/// thumb → finger vector: its palm → tip and finger → finger vectors fade with `1 − β` (its
/// mid point and its neighbours' separation stay), and where it pinches follows where the
/// robot's thumb can go. Without a pinch (`β = 0`) every weight is as configured.
pub fn key_vector_targets(
    human: &HumanKeyVectors,
    config: &RetargetConfig,
) -> [KeyVector; KEY_VECTORS] {
    let p = &config.pinch;
    let w = &config.weights;
    let approach = approach_weights(&human.pinch_distances_m, config);
    let beta: [f64; 5] = std::array::from_fn(|i| {
        if i == 0 {
            0.0
        } else {
            pinch_activation(human.pinch_distances_m[i - 1], p.engage_m, p.release_m)
        }
    });
    let mut out = [KeyVector {
        from: None,
        to: 0,
        target: Vector3::zeros(),
        weight: 0.0,
    }; KEY_VECTORS];
    let mut k = 0;
    for f in Finger::ALL {
        out[k] = KeyVector {
            from: None,
            to: f.index(),
            target: human.tips[f.index()],
            weight: w.palm_to_tip * (1.0 - beta[f.index()]),
        };
        k += 1;
    }
    for a in 0..5 {
        for b in a + 1..5 {
            let h = human.tips[b] - human.tips[a];
            if a == 0 {
                out[k] = thumb_pair(b, h, beta[b], approach[b - 1], config);
                k += 1;
                continue;
            }
            // The separation term adds `β w_sep ‖r − goal‖²` to `w_tt ‖r − h‖²`; the sum is one
            // quadratic with the blended target below and weight `w_tt + β w_sep`.
            let activation = beta[a].max(beta[b]);
            let extra = p.separation_weight;
            let goal = unit_or_zero(&h) * h.norm().max(p.separation_m);
            let weight = w.tip_to_tip * (1.0 - activation) + activation * extra;
            let blend = if weight > 0.0 {
                activation * extra / weight
            } else {
                0.0
            };
            let target = h * (1.0 - blend) + goal * blend;
            out[k] = KeyVector {
                from: Some(a),
                to: b,
                target,
                weight,
            };
            k += 1;
        }
    }
    for f in Finger::ALL {
        out[k] = KeyVector {
            from: None,
            to: mid(f),
            target: human.mids[f.index()],
            weight: w.palm_to_mid,
        };
        k += 1;
    }
    out
}

/// The thumb → finger key vector at pinch activation `beta` of a human vector `h`: the
/// distance aimed for slides from the human's to the closed gap, `(1 − β)‖h‖ + β · gap`, along
/// the human direction, and the weight grows from `w_tt` to `w_tt + w_pinch` (a pinch weight
/// of 0 turns the pinch off); on the way in, the weight is at least `w_tt + approach`.
fn thumb_pair(
    to: usize,
    h: Vector3<f64>,
    beta: f64,
    approach: f64,
    config: &RetargetConfig,
) -> KeyVector {
    let p = &config.pinch;
    let target = if beta > 0.0 && p.weight > 0.0 {
        unit_or_zero(&h) * ((1.0 - beta) * h.norm() + beta * p.closed_gap_m)
    } else {
        h // no pinch (or the pinch term off): the human vector itself
    };
    KeyVector {
        from: Some(Finger::Thumb.index()),
        to,
        target,
        weight: config.weights.tip_to_tip + (beta * p.weight).max(approach),
    }
}

/// Huber function of a residual norm.
pub fn huber(norm: f64, delta: f64) -> f64 {
    if norm <= delta {
        0.5 * norm * norm
    } else {
        delta * (norm - 0.5 * delta)
    }
}

/// Key-vector part of the energy for robot points (robot palm frame).
pub fn key_vector_energy(
    vectors: &[KeyVector; KEY_VECTORS],
    points: &[Vector3<f64>; POINTS],
    delta: f64,
) -> f64 {
    vectors
        .iter()
        .map(|v| v.weight * huber((v.robot(points) - v.target).norm(), delta))
        .sum()
}

/// Add the key vectors' Gauss–Newton terms to `H` and `g` (iteratively reweighted: each
/// residual counts with weight `w · min(1, δ/‖e‖)`), for point Jacobians `jacobians`
/// (robot palm frame, one column per free joint). `scratch` is a 3 × n buffer.
pub fn accumulate_key_vectors(
    vectors: &[KeyVector; KEY_VECTORS],
    points: &[Vector3<f64>; POINTS],
    jacobians: &[Matrix3xX<f64>; POINTS],
    delta: f64,
    H: &mut DMatrix<f64>,
    g: &mut DVector<f64>,
    scratch: &mut Matrix3xX<f64>,
) {
    for v in vectors {
        let e = v.robot(points) - v.target;
        let norm = e.norm();
        let robust = if norm > delta { delta / norm } else { 1.0 };
        let weight = v.weight * robust;
        if weight == 0.0 {
            continue;
        }
        scratch.copy_from(&jacobians[v.to]);
        if let Some(from) = v.from {
            *scratch -= &jacobians[from];
        }
        H.gemm_tr(weight, scratch, scratch, 1.0);
        g.gemv_tr(weight, scratch, &e, 1.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pinch_activation_is_continuous_and_saturates() {
        assert_eq!(pinch_activation(0.0, 0.015, 0.04), 1.0);
        assert_eq!(pinch_activation(0.015, 0.015, 0.04), 1.0);
        assert_eq!(pinch_activation(0.04, 0.015, 0.04), 0.0);
        assert_eq!(pinch_activation(0.2, 0.015, 0.04), 0.0);
        let mid = pinch_activation(0.0275, 0.015, 0.04);
        assert!((mid - 0.5).abs() < 1e-12);
        // No snapping: small distance changes give small activation changes.
        let mut previous = 1.0;
        for i in 0..=1000 {
            let a = pinch_activation(0.01 + 0.04 * i as f64 / 1000.0, 0.015, 0.04);
            assert!((a - previous).abs() < 0.01);
            previous = a;
        }
    }

    #[test]
    fn the_thumb_approaching_its_nearest_finger_weighs_their_vector_more() {
        let config = RetargetConfig::default();
        let (p, w) = (&config.pinch, &config.weights);
        let full = w.palm_to_tip - w.tip_to_tip;
        // Index nearest: only it gains weight, none at the approach range, all at release.
        let at = |index_m: f64| approach_weights(&[index_m, 0.065, 0.07, 0.09], &config);
        assert_eq!(at(p.approach_m), [0.0; 4]);
        assert_eq!(at(p.release_m), [full, 0.0, 0.0, 0.0]);
        let between = at(0.5 * (p.approach_m + p.release_m))[0];
        assert!(between > 0.0 && between < full, "{between}");
        // The middle finger nearer than the index: the index gains nothing.
        let middle = approach_weights(&[0.045, 0.042, 0.07, 0.09], &config);
        assert_eq!(middle[0], 0.0);
        assert!(middle[1] > 0.0);
        // Into the pinch the weight never drops: max(β w_pinch, approach) is continuous.
        let human = |index_m: f64| HumanKeyVectors {
            tips: [Vector3::zeros(); 5],
            mids: [Vector3::zeros(); 5],
            pinch_distances_m: [index_m, 0.12, 0.12, 0.12],
        };
        let weight = |index_m: f64| {
            let v = key_vector_targets(&human(index_m), &config);
            v.iter()
                .find(|k| k.from == Some(0) && k.to == 1)
                .unwrap()
                .weight
        };
        let mut previous = weight(0.1);
        assert_eq!(previous, w.tip_to_tip);
        for i in 1..=200 {
            let now = weight(0.1 - 0.1 * f64::from(i) / 200.0);
            assert!(now >= previous - 1e-12, "falls at step {i}");
            assert!(now - previous < 1.0, "jumps at step {i}");
            previous = now;
        }
        // Off when the approach range is not beyond the release, or the pinch is off.
        let mut off = config.clone();
        off.pinch.approach_m = off.pinch.release_m;
        assert_eq!(approach_weights(&[0.045, 0.1, 0.1, 0.1], &off), [0.0; 4]);
        off.pinch.approach_m = 0.06;
        off.pinch.weight = 0.0;
        assert_eq!(approach_weights(&[0.045, 0.1, 0.1, 0.1], &off), [0.0; 4]);
    }

    #[test]
    fn huber_is_quadratic_then_linear_and_continuous() {
        assert_eq!(huber(0.01, 0.02), 0.5e-4);
        assert!((huber(0.02, 0.02) - 2e-4).abs() < 1e-18);
        assert!((huber(0.05, 0.02) - 0.02 * 0.04).abs() < 1e-15);
    }

    #[test]
    fn a_pinching_finger_gives_way_to_the_thumb_and_nothing_changes_without_a_pinch() {
        let config = RetargetConfig::default();
        let w = &config.weights;
        let tips = [
            Vector3::new(0.03, 0.05, 0.02),
            Vector3::new(0.035, 0.09, 0.02),
            Vector3::new(0.0, 0.17, 0.0),
            Vector3::new(-0.02, 0.16, 0.0),
            Vector3::new(-0.04, 0.14, 0.0),
        ];
        let human = |index_m: f64| HumanKeyVectors {
            tips,
            mids: tips,
            pinch_distances_m: [index_m, 0.12, 0.12, 0.12],
        };
        let pair = |v: &[KeyVector; KEY_VECTORS], a: Option<usize>, b: usize| {
            *v.iter().find(|k| k.from == a && k.to == b).unwrap()
        };
        let apart = key_vector_targets(&human(0.1), &config);
        for f in 0..5 {
            assert_eq!(pair(&apart, None, f).weight, w.palm_to_tip);
        }
        assert_eq!(pair(&apart, Some(1), 2).weight, w.tip_to_tip);
        let pinched = key_vector_targets(&human(0.005), &config);
        assert_eq!(pair(&pinched, None, 1).weight, 0.0, "index placement");
        assert_eq!(
            pair(&pinched, None, 0).weight,
            w.palm_to_tip,
            "the thumb keeps its place"
        );
        assert_eq!(pair(&pinched, None, 2).weight, w.palm_to_tip);
        assert_eq!(
            pair(&pinched, None, mid(Finger::Index)).weight,
            w.palm_to_mid
        );
        // Index → middle keeps only the separation, at its full weight and goal.
        let neighbour = pair(&pinched, Some(1), 2);
        assert!((neighbour.weight - config.pinch.separation_weight).abs() < 1e-12);
        let h = tips[2] - tips[1];
        let goal = h.normalize() * h.norm().max(config.pinch.separation_m);
        assert!((neighbour.target - goal).norm() < 1e-12);
        // Middle → ring, away from the pinch, is unchanged.
        assert_eq!(pair(&pinched, Some(2), 3), pair(&apart, Some(2), 3));
    }

    #[test]
    fn a_full_pinch_targets_the_closed_gap() {
        let mut tips = [Vector3::zeros(); 5];
        for (i, t) in tips.iter_mut().enumerate() {
            *t = Vector3::new(0.02 * i as f64, 0.1, 0.0);
        }
        tips[1] = tips[0] + Vector3::new(0.005, 0.0, 0.0); // index 5 mm from thumb
        let human = HumanKeyVectors {
            tips,
            mids: tips.map(|t| t * 0.5),
            pinch_distances_m: [0.005, 0.04, 0.06, 0.08],
        };
        let config = RetargetConfig::default();
        let v = key_vector_targets(&human, &config);
        let thumb_index = v.iter().find(|k| k.from == Some(0) && k.to == 1).unwrap();
        // A full pinch aims at the closed gap, along the human direction.
        assert!((thumb_index.target.norm() - config.pinch.closed_gap_m).abs() < 1e-12);
        assert!(thumb_index.target.x > 0.0);
        assert_eq!(
            thumb_index.weight,
            config.weights.tip_to_tip + config.pinch.weight
        );
        let thumb_ring = v.iter().find(|k| k.from == Some(0) && k.to == 3).unwrap();
        assert_eq!(thumb_ring.target, tips[3] - tips[0]);
        // The middle finger, next to the pinching index, is kept at least separation_m away.
        let index_middle = v.iter().find(|k| k.from == Some(1) && k.to == 2).unwrap();
        assert!(index_middle.target.norm() > 0.02 + 1e-3);
        // With the extra weights at zero the targets are the human vectors.
        let mut plain = config.clone();
        plain.pinch.weight = 0.0;
        plain.pinch.separation_weight = 0.0;
        for k in key_vector_targets(&human, &plain)
            .iter()
            .filter(|k| k.from.is_some())
        {
            assert_eq!(k.target, tips[k.to] - tips[k.from.unwrap()]);
        }
        let palm_mid = v.iter().filter(|k| k.from.is_none() && k.to >= 5).count();
        assert_eq!(palm_mid, 5);
    }
}
