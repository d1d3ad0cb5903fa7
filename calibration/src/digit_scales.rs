//! The per-digit model's length factors, fitted after the global transform.
//!
//! A digit's factor scales its points about its base before the global map (see
//! [`CalibrationTransform`]). [`Objective::digit_scales_searched`] minimises the objective
//! itself, one digit at a time (thumb first), by a golden-section search of each factor within
//! [`FACTOR_RANGE`]; the fit keeps the factors only if they lower the objective.
//!
//! (A closed-form least-squares fit of each factor against the robot's tips and mid points at
//! the poses' ground truth was tried first: it never lowered the objective for any of 24
//! non-uniform synthetic users, so the fit kept the global transform every time.)

use retarget::CalibrationTransform;

use crate::error::Error;
use crate::objective::Objective;

/// The factors a fit may return (a digit 25 % shorter to a third longer, relative to the
/// palm, than the global map makes it).
pub const FACTOR_RANGE: (f64, f64) = (0.75, 1.33);

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
