//! Rotation and distance: whole units forward of the start, on the best position reached.

use super::{Direction, ProgressEvent};

/// Degrees per radian.
const DEG_PER_RAD: f64 = 180.0 / std::f64::consts::PI;
/// Millimetres per metre.
const MM_PER_M: f64 = 1000.0;
/// Slack on whole steps so that a value just under a whole unit (359.99999999° for a full
/// turn read back in radians, or printed with 9 decimals) still counts: a millionth of a
/// degree or millimetre, far below any physical meaning.
const STEP_SLACK: f64 = 1e-6;

/// A ratchet on the best forward progress; emits whole units (1° or 1 mm) as they are due.
#[derive(Debug, Clone)]
pub(super) struct Ratchet {
    /// Catalog units per joint unit, with the direction's sign.
    scale: f64,
    /// Whether readings are angles to unwrap.
    unwrap: bool,
    /// The last raw reading.
    last_raw: f64,
    /// The joint position, unwrapped, minus the first reading.
    travelled: f64,
    /// The best forward progress reached, catalog units.
    best: f64,
    /// The progress emitted so far, catalog units (whole).
    emitted: f64,
}

impl Ratchet {
    /// A hinge's rotation in degrees, starting at angle `q0` (rad).
    pub(super) fn rotation(direction: Direction, q0: f64) -> Ratchet {
        Ratchet::new(direction.sign() * DEG_PER_RAD, true, q0)
    }

    /// A slide's distance in millimetres, starting at position `q0` (m).
    pub(super) fn distance(direction: Direction, q0: f64) -> Ratchet {
        Ratchet::new(direction.sign() * MM_PER_M, false, q0)
    }

    fn new(scale: f64, unwrap: bool, q0: f64) -> Ratchet {
        Ratchet {
            scale,
            unwrap,
            last_raw: q0,
            travelled: 0.0,
            best: 0.0,
            emitted: 0.0,
        }
    }

    /// One event with the whole units due since the last one, if any.
    pub(super) fn update(&mut self, q: f64) -> Vec<ProgressEvent> {
        let step = q - self.last_raw;
        self.travelled += if self.unwrap { wrap_to_pi(step) } else { step };
        self.last_raw = q;
        self.best = self.best.max(self.scale * self.travelled);
        let due = (self.best - self.emitted + STEP_SLACK).floor();
        if due >= 1.0 {
            self.emitted += due;
            vec![ProgressEvent::Progress(due)]
        } else {
            Vec::new()
        }
    }
}

/// `angle` (rad) wrapped into [−π, π).
fn wrap_to_pi(angle: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    (angle + PI).rem_euclid(TAU) - PI
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wrapped_hinge_reading_is_unwrapped() {
        let mut ratchet = Ratchet::rotation(Direction::Increasing, 3.0);
        let events = ratchet.update(-3.0); // +0.283 rad across the ±π seam
        let degrees = (std::f64::consts::TAU - 6.0).to_degrees().floor();
        assert_eq!(events, vec![ProgressEvent::Progress(degrees)]);
    }
}
