//! When the station's timer ticks, for every loop that drives it: the live node's tokio
//! interval ([`tick_period`]), a glove recording's log clock (ticks every `1 / rate_hz` from the
//! first message, in nanoseconds) and the lock step (a tick every `n` simulated steps, in step
//! counts). One schedule, [`TickSchedule`], on whatever integer clock the loop keeps.

use std::time::Duration;

/// The station timer's period for a `control.rate_hz` of `rate_hz` (the live node's interval).
pub fn tick_period(rate_hz: f64) -> Duration {
    Duration::from_secs_f64(1.0 / rate_hz)
}

/// The same period in whole nanoseconds (a log's clock).
pub fn tick_period_ns(rate_hz: f64) -> i64 {
    (1e9 / rate_hz).round() as i64
}

/// Ticks every this many steps of a loop stepped at `step_rate_hz` (at least every step).
pub fn steps_per_tick(step_rate_hz: f64, rate_hz: f64) -> i64 {
    (step_rate_hz / rate_hz).round().max(1.0) as i64
}

/// A tick every `period` from `first` on an integer clock (nanoseconds or step counts).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TickSchedule {
    next: i64,
    period: i64,
}

impl TickSchedule {
    /// The first tick at `first`, then every `period` (at least 1).
    pub fn starting_at(first: i64, period: i64) -> Self {
        Self {
            next: first,
            period: period.max(1),
        }
    }

    /// The next tick's time if it is due at `now` (at or before it), the schedule moved past
    /// it; call again until `None` for every tick due.
    pub fn due(&mut self, now: i64) -> Option<i64> {
        (self.next <= now).then(|| {
            let tick = self.next;
            self.next += self.period;
            tick
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_count_schedule_ticks_every_nth_step_from_zero() {
        let mut schedule = TickSchedule::starting_at(0, steps_per_tick(200.0, 50.0));
        let ticked: Vec<i64> = (0..10).filter(|k| schedule.due(*k).is_some()).collect();
        assert_eq!(ticked, vec![0, 4, 8]);
    }

    #[test]
    fn a_late_caller_gets_every_tick_it_missed_in_order() {
        let mut schedule = TickSchedule::starting_at(100, tick_period_ns(1e8));
        let mut ticks = Vec::new();
        while let Some(t) = schedule.due(125) {
            ticks.push(t);
        }
        assert_eq!(ticks, vec![100, 110, 120]);
        assert_eq!(schedule.due(129), None);
    }

    #[test]
    fn the_period_matches_the_rate() {
        assert_eq!(tick_period(100.0), Duration::from_millis(10));
        assert_eq!(tick_period_ns(100.0), 10_000_000);
        assert_eq!(steps_per_tick(100.0, 400.0), 1);
    }
}
