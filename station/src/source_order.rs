//! Keypoint frames in their sender's order: a frame stamped (DDS source time) before the
//! newest accepted one arrived late — reordered, or a duplicate from the past — and is
//! rejected; a sender whose clock jumps is followed, not frozen out.
//!
//! ```text
//!  source stamp s, received at r; the newest accepted frame: (s0, r0); window w
//!
//!  s0 - w ≤ s < s0            late: rejected (out_of_order), changes nothing
//!  s < s0 - w                 the sender's clock jumped back: accepted, counted, s is the newest
//!  s ≥ s0, s - (s0 + r - r0) > w
//!                             the sender's clock jumped ahead (beyond what the receive clock
//!                             explains): accepted, counted
//!  otherwise                  in order: accepted
//! ```
//!
//! Every time here is a parameter. The window is `gate.reorder_window_ms`: longer than any
//! reordering the network produces (milliseconds), shorter than the disengage timeout, so a
//! small backward jump of the sender's clock costs at most one window of rejected frames (the
//! station holds, then follows again) and never disengages it. Frames without a source stamp
//! are not ordered. Freshness (hold, disengage) never uses source stamps: the watchdog runs on
//! the station's own receive clock.

/// What [`SourceOrder::check`] says about a frame's source stamp.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StampOrder {
    /// Newer than (or as new as) the newest accepted frame.
    InOrder,
    /// Older than the newest accepted frame, within the reorder window: reject.
    Late,
    /// The sender's clock jumped (back beyond the window, or ahead beyond what the receive
    /// clock explains): accept and start over from this stamp.
    ClockJump,
}

/// The newest accepted source stamp and when it was received.
#[derive(Debug, Clone)]
pub struct SourceOrder {
    window_ns: i64,
    newest: Option<(i64, i64)>,
}

impl SourceOrder {
    /// Ordering with a reorder window of `window_ms` milliseconds.
    pub fn new(window_ms: u64) -> SourceOrder {
        SourceOrder {
            window_ns: i64::try_from(window_ms)
                .unwrap_or(i64::MAX)
                .saturating_mul(1_000_000),
            newest: None,
        }
    }

    /// Where a frame stamped `source_ns` by its sender and received at `received_ns` stands.
    /// Changes nothing: call [`accept`](Self::accept) for a frame that is taken.
    pub fn check(&self, source_ns: i64, received_ns: i64) -> StampOrder {
        let Some((newest_source, newest_received)) = self.newest else {
            return StampOrder::InOrder;
        };
        if source_ns < newest_source {
            return if newest_source.saturating_sub(source_ns) <= self.window_ns {
                StampOrder::Late
            } else {
                StampOrder::ClockJump
            };
        }
        let expected = newest_source.saturating_add(received_ns.saturating_sub(newest_received));
        if source_ns.saturating_sub(expected) > self.window_ns {
            StampOrder::ClockJump
        } else {
            StampOrder::InOrder
        }
    }

    /// A frame stamped `source_ns`, received at `received_ns`, was taken (in order or after a
    /// clock jump): it is the newest now.
    pub fn accept(&mut self, source_ns: i64, received_ns: i64) {
        self.newest = Some((source_ns, received_ns));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: i64 = 1_000_000;
    const HOUR: i64 = 3_600_000 * MS;

    /// Check, and accept what is not late, as the station does.
    fn feed(order: &mut SourceOrder, source_ns: i64, received_ns: i64) -> StampOrder {
        let verdict = order.check(source_ns, received_ns);
        if verdict != StampOrder::Late {
            order.accept(source_ns, received_ns);
        }
        verdict
    }

    #[test]
    fn late_frames_are_rejected_and_change_nothing() {
        let mut order = SourceOrder::new(250);
        assert_eq!(feed(&mut order, 100 * MS, 1000 * MS), StampOrder::InOrder);
        assert_eq!(feed(&mut order, 120 * MS, 1020 * MS), StampOrder::InOrder);
        // 110 arrives after 120: late, and 120 stays the newest.
        assert_eq!(feed(&mut order, 110 * MS, 1021 * MS), StampOrder::Late);
        assert_eq!(feed(&mut order, 115 * MS, 1022 * MS), StampOrder::Late);
        // The same stamp again (a duplicated sample) is not late.
        assert_eq!(feed(&mut order, 120 * MS, 1023 * MS), StampOrder::InOrder);
        assert_eq!(feed(&mut order, 140 * MS, 1040 * MS), StampOrder::InOrder);
    }

    #[test]
    fn clock_jumps_either_way_are_followed() {
        let mut order = SourceOrder::new(250);
        feed(&mut order, 100 * MS, 1000 * MS);
        // Ahead by an hour: accepted, and the next frames follow on from there.
        assert_eq!(
            feed(&mut order, HOUR + 120 * MS, 1020 * MS),
            StampOrder::ClockJump
        );
        assert_eq!(
            feed(&mut order, HOUR + 140 * MS, 1040 * MS),
            StampOrder::InOrder
        );
        // Back by two hours: beyond the window, so a jump, not a late frame.
        assert_eq!(
            feed(&mut order, 160 * MS - HOUR, 1060 * MS),
            StampOrder::ClockJump
        );
        assert_eq!(
            feed(&mut order, 180 * MS - HOUR, 1080 * MS),
            StampOrder::InOrder
        );
        // Back by less than the window: those frames are late until the clock catches up.
        assert_eq!(
            feed(&mut order, 100 * MS - HOUR, 1100 * MS),
            StampOrder::Late
        );
        assert_eq!(
            feed(&mut order, 190 * MS - HOUR, 1190 * MS),
            StampOrder::InOrder
        );
    }

    #[test]
    fn a_sender_clock_running_at_the_receive_rate_is_in_order_however_far_off() {
        let mut order = SourceOrder::new(250);
        // A sender whose clock is a day behind, or stopped (the same stamp on every frame).
        for i in 0..100 {
            let received = 1000 * MS + i * 10 * MS;
            assert_eq!(
                feed(&mut order, received - 24 * HOUR, received),
                StampOrder::InOrder
            );
        }
        for i in 0..100 {
            assert_eq!(
                feed(&mut order, 5 * MS, 3000 * MS + i * 10 * MS),
                if i == 0 {
                    StampOrder::ClockJump
                } else {
                    StampOrder::InOrder
                }
            );
        }
        // After a minute of silence the sender's clock has moved as the receive clock did.
        assert_eq!(
            feed(&mut order, 59_000 * MS, 63_000 * MS),
            StampOrder::InOrder
        );
    }

    #[test]
    fn extreme_stamps_do_not_overflow() {
        let mut order = SourceOrder::new(u64::MAX);
        feed(&mut order, i64::MAX, i64::MIN);
        assert_eq!(order.check(i64::MIN, i64::MAX), StampOrder::Late);
        let mut order = SourceOrder::new(0);
        feed(&mut order, i64::MIN, i64::MAX);
        assert_eq!(order.check(i64::MAX, i64::MIN), StampOrder::ClockJump);
    }
}
