//! The per-digit model's length factors, fitted after the global transform.
//!
//! For each digit `i` and each pose, the robot's fingertip and mid point at the pose's ground
//! truth `x_R` (robot palm frame) are what the human points should map to. Under the global
//! map `M = s · R` and a factor `f_i` about the digit's base `b`, a human point `x` maps to
//! `M b + f_i · M (x − b)`; the factor that brings the seven poses' tips and mid points
//! closest, in least squares, is
//!
//! ```text
//! f_i = Σ (x_R − M b) · M (x − b)  /  Σ ‖M (x − b)‖²
//! ```
//!
//! clamped to [`FACTOR_RANGE`]. Closed form: no objective evaluation, so it adds nothing to
//! the fit's time; the fit then keeps the factors only if the objective says they help.
//!
//! [`Objective::digit_scales_searched`] instead minimises the objective itself, one digit at
//! a time (thumb first), by a golden-section search of each factor within [`FACTOR_RANGE`].

use nalgebra::Vector3;
use retarget::{CalibrationTransform, Finger, PalmFrame};

use crate::error::Error;
use crate::objective::Objective;

/// The factors a fit may return (a digit 25 % shorter to a third longer, relative to the
/// palm, than the global map makes it).
pub const FACTOR_RANGE: (f64, f64) = (0.75, 1.33);

impl Objective {
    /// Each digit's least-squares length factor about its base under `global` (indexed by
    /// [`Finger::index`]).
    pub fn digit_scales(&mut self, global: &CalibrationTransform) -> Result<[f64; 5], Error> {
        let layout = self.retargeter.config().layout;
        let map = global.matrix();
        let mut num = [0.0; 5];
        let mut den = [0.0; 5];
        for target in &self.targets {
            let (tips, mids) = self.retargeter.robot_tips_and_mids(&target.q_truth)?;
            let points = &target.keypoints;
            let palm = PalmFrame::from_landmarks(&layout.palm_landmarks(points))?;
            let in_palm = |i: usize| palm.point_to_palm(&points[i]);
            for finger in Finger::ALL {
                let k = finger.index();
                let base = in_palm(layout.chain(finger)[0]);
                let human = [
                    in_palm(layout.tip(finger)),
                    in_palm(layout.chain(finger)[1]),
                ];
                for (x, robot) in human.iter().zip([tips[k], mids[k]]) {
                    let u: Vector3<f64> = map * (x - base);
                    let r: Vector3<f64> = robot - map * base;
                    num[k] += r.dot(&u);
                    den[k] += u.norm_squared();
                }
            }
        }
        let (low, high) = FACTOR_RANGE;
        Ok(std::array::from_fn(|k| {
            if den[k] > 0.0 {
                (num[k] / den[k]).clamp(low, high)
            } else {
                1.0
            }
        }))
    }
}

/// Objective evaluations of the golden-section search per digit.
pub const SEARCH_EVALUATIONS_PER_DIGIT: usize = 8;

impl Objective {
    /// Each digit's length factor that minimises the objective with the others held, one
    /// digit after the other from `start` (thumb first); returns the factors and the
    /// evaluations made.
    pub fn digit_scales_searched(
        &mut self,
        start: &CalibrationTransform,
        cancelled: &dyn Fn() -> bool,
    ) -> Result<(CalibrationTransform, usize), Error> {
        let mut best = *start;
        let mut evaluations = 0;
        let golden = (5f64.sqrt() - 1.0) / 2.0;
        for digit in 0..5 {
            let mut value_at = |f: f64, objective: &mut Objective| -> Result<f64, Error> {
                if cancelled() {
                    return Err(Error::Interrupted);
                }
                let mut t = best;
                t.digit_scale[digit] = f;
                evaluations += 1;
                Ok(objective.evaluate(&t)?.value)
            };
            let (mut a, mut b) = FACTOR_RANGE;
            let mut c = b - golden * (b - a);
            let mut d = a + golden * (b - a);
            let (mut fc, mut fd) = (value_at(c, self)?, value_at(d, self)?);
            for _ in 2..SEARCH_EVALUATIONS_PER_DIGIT {
                if fc < fd {
                    (b, d, fd) = (d, c, fc);
                    c = b - golden * (b - a);
                    fc = value_at(c, self)?;
                } else {
                    (a, c, fc) = (c, d, fd);
                    d = a + golden * (b - a);
                    fd = value_at(d, self)?;
                }
            }
            best.digit_scale[digit] = if fc < fd { c } else { d };
        }
        Ok((best, evaluations))
    }
}
