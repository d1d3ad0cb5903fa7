//! How long the station's loop spent in one handler at most: the loop waits on nothing else,
//! so a long turn is time in which no glove frame was taken and no command sent. It is in the
//! status (`longest_turn`), and a console that finds the glove stale names it, so a stall can
//! be told apart from frames that never arrived.

use std::time::Instant;

use serde::Serialize;

/// The longest turn so far.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct LoopTurns {
    /// Its length, ms (0 before the first turn).
    pub ms: f64,
    /// What the loop was doing: `keypoints`, `status`, `operator`, ...
    pub handler: &'static str,
}

impl LoopTurns {
    /// A turn of `handler` that began at `started` has ended.
    pub fn ended(&mut self, handler: &'static str, started: Instant) {
        let ms = started.elapsed().as_secs_f64() * 1e3;
        if ms > self.ms {
            *self = LoopTurns { ms, handler };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_longest_turn_and_its_handler_are_kept() {
        let mut turns = LoopTurns::default();
        let long_ago = Instant::now() - std::time::Duration::from_millis(40);
        turns.ended("status", long_ago);
        turns.ended("keypoints", Instant::now());
        assert_eq!(turns.handler, "status");
        assert!(turns.ms >= 40.0, "{turns:?}");
    }
}
