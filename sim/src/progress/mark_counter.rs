//! Notches and curves: marks passed along a joint, with a hysteresis band.

use super::{PhysicsMapping, ProgressEvent};

/// Counts the marks a joint has passed; positions are taken in the forward sense
/// (`direction`'s sign times the joint position), so the marks increase.
#[derive(Debug, Clone)]
pub(super) struct MarkCounter {
    /// The marks in the forward sense, increasing.
    marks: Vec<f64>,
    band: f64,
    sign: f64,
    /// Marks passed now.
    passed: usize,
    /// Marks passed in the first reading: the start, not progress.
    passed_at_start: usize,
}

impl MarkCounter {
    /// A counter for a validated mapping, starting at joint position `q0`.
    pub(super) fn new(mapping: &PhysicsMapping, q0: f64) -> MarkCounter {
        let sign = mapping.direction.sign();
        let marks: Vec<f64> = mapping.marks.iter().map(|m| sign * m).collect();
        let passed = marks.iter().filter(|m| sign * q0 >= **m).count();
        MarkCounter {
            marks,
            band: mapping.mark_band,
            sign,
            passed,
            passed_at_start: passed,
        }
    }

    /// +1 per mark passed forward, −1 per mark passed back, since the last reading; marks
    /// behind the start give no events.
    pub(super) fn update(&mut self, q: f64) -> Vec<ProgressEvent> {
        let x = self.sign * q;
        let mut events = Vec::new();
        loop {
            if self.passed < self.marks.len() && x >= self.marks[self.passed] + self.band {
                self.passed += 1;
                if self.passed > self.passed_at_start {
                    events.push(ProgressEvent::Progress(1.0));
                }
            } else if self.passed > 0 && x <= self.marks[self.passed - 1] - self.band {
                if self.passed > self.passed_at_start {
                    events.push(ProgressEvent::Progress(-1.0));
                }
                self.passed -= 1;
            } else {
                return events;
            }
        }
    }
}
