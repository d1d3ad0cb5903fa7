//! The relay's view of the two computers' clocks, and what it tells the station.
//!
//! `pomdar relay` judges a command's age as its receive time on the robot's computer minus its
//! send time on the station's ([`crate::robot_link::CommandAgeGate`]). That difference is the
//! link's delay plus the offset between the two clocks. On a lab network the smallest delay
//! over a couple of seconds is well under a millisecond, so the smallest age seen in a window
//! is the offset, to within that. An offset of `+d` leaves a command only `max_age − d` of
//! network time before it is dropped; `−d` lets commands up to `max_age + d` old through.
//! [`ClockOffsetMonitor`] keeps that estimate per window (so a clock step after start-up is
//! seen within two windows) and says when it matters: once the offset takes a quarter of the
//! limit, again when it moves by half that, and when the clocks are back in step.
//!
//! [`RelayStatus`] is what the relay publishes for the station: the robot side's readers of
//! each robot topic and the offset, so the station's "is a hand listening" looks past the relay
//! to the robot's own drivers ([`listeners_behind_relay`]).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

const MS: i64 = 1_000_000;

/// The window over which the smallest age is taken, nanoseconds.
pub const OFFSET_WINDOW_NS: i64 = 2_000 * MS;

/// A relay status older than this (its relay publishes twice a second) tells nothing about the
/// robot side any more, nanoseconds.
pub const RELAY_STATUS_STALE_NS: i64 = 2_000 * MS;

/// How the offset estimate changed, worth a line to the operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OffsetNews {
    /// The clocks are `offset_ns` apart (receive clock minus send clock), enough to eat into
    /// (positive) or stretch (negative) the age limit of `max_age_ns`.
    Apart {
        /// The smallest age seen in the last window, nanoseconds.
        offset_ns: i64,
        /// The age limit it applies to.
        max_age_ns: i64,
    },
    /// After a warning, the offset is small again.
    BackInStep {
        /// The smallest age seen in the last window, nanoseconds.
        offset_ns: i64,
    },
}

impl std::fmt::Display for OffsetNews {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let ms = |ns: i64| ns as f64 / MS as f64;
        let window_s = OFFSET_WINDOW_NS / 1_000 / MS;
        match *self {
            OffsetNews::Apart {
                offset_ns,
                max_age_ns,
            } if offset_ns >= 0 => write!(
                f,
                "the station's clock is about {:.0} ms behind this computer's (the smallest command age over {window_s} s): with the {:.0} ms age limit a command has only {:.0} ms of network time left before it is dropped; keep both clocks in step (chrony)",
                ms(offset_ns),
                ms(max_age_ns),
                ms(max_age_ns - offset_ns).max(0.0),
            ),
            OffsetNews::Apart {
                offset_ns,
                max_age_ns,
            } => write!(
                f,
                "the station's clock is about {:.0} ms ahead of this computer's (the smallest command age over {window_s} s is {:.0} ms): commands up to {:.0} ms old pass the {:.0} ms age limit; keep both clocks in step (chrony)",
                ms(-offset_ns),
                ms(offset_ns),
                ms(max_age_ns - offset_ns),
                ms(max_age_ns),
            ),
            OffsetNews::BackInStep { offset_ns } => write!(
                f,
                "the station's clock and this computer's are back in step (offset about {:.0} ms)",
                ms(offset_ns)
            ),
        }
    }
}

/// The smallest command age per window, and when to say so.
#[derive(Debug, Clone)]
pub struct ClockOffsetMonitor {
    max_age_ns: i64,
    /// The current window: its start and the smallest age in it so far.
    window: Option<(i64, i64)>,
    /// The last whole window's smallest age.
    estimate_ns: Option<i64>,
    /// The estimate last warned about, while warned.
    warned_ns: Option<i64>,
}

impl ClockOffsetMonitor {
    /// A monitor for a relay dropping commands older than `max_age_ms`.
    pub fn new(max_age_ms: u64) -> ClockOffsetMonitor {
        ClockOffsetMonitor {
            max_age_ns: i64::try_from(max_age_ms)
                .unwrap_or(i64::MAX / MS)
                .saturating_mul(MS),
            window: None,
            estimate_ns: None,
            warned_ns: None,
        }
    }

    /// An offset this large (either way) is worth a warning: a quarter of the age limit.
    pub fn warn_at_ns(&self) -> i64 {
        self.max_age_ns / 4
    }

    /// The last whole window's smallest age, nanoseconds (`None` before one ended).
    pub fn estimate_ns(&self) -> Option<i64> {
        self.estimate_ns
    }

    /// A stamped command received with age `age_ns` at `now_ns` (the receive clock); news
    /// when a window ends with an estimate worth telling.
    pub fn observe(&mut self, age_ns: i64, now_ns: i64) -> Option<OffsetNews> {
        let news = match self.window {
            Some((start, smallest)) if now_ns.saturating_sub(start) >= OFFSET_WINDOW_NS => {
                self.estimate_ns = Some(smallest);
                self.window = None;
                self.judge(smallest)
            }
            _ => None,
        };
        self.window = Some(match self.window {
            Some((start, smallest)) => (start, smallest.min(age_ns)),
            None => (now_ns, age_ns),
        });
        news
    }

    fn judge(&mut self, offset_ns: i64) -> Option<OffsetNews> {
        let warn_at = self.warn_at_ns();
        let apart = offset_ns.saturating_abs() >= warn_at;
        match (apart, self.warned_ns) {
            (true, Some(warned)) if offset_ns.abs_diff(warned) < (warn_at / 2).unsigned_abs() => {
                None
            }
            (true, _) => {
                self.warned_ns = Some(offset_ns);
                Some(OffsetNews::Apart {
                    offset_ns,
                    max_age_ns: self.max_age_ns,
                })
            }
            (false, Some(_)) => {
                self.warned_ns = None;
                Some(OffsetNews::BackInStep { offset_ns })
            }
            (false, None) => None,
        }
    }
}

/// What `pomdar relay` publishes for the station, twice a second.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RelayStatus {
    /// Readers of each robot topic on the robot's side (its drivers), by topic.
    pub robot_listeners: BTreeMap<String, u64>,
    /// The clock offset estimate (receive clock minus send clock), milliseconds; `None` before
    /// a window of commands ended.
    pub clock_offset_ms: Option<f64>,
    /// Commands republished and dropped so far, all topics.
    pub forwarded: u64,
    /// Commands dropped by the age check so far, all topics.
    pub dropped: u64,
    /// Forwarded commands the robot-side writer refused so far, all topics.
    pub publish_failed: u64,
}

/// The readers of `robot_topic` behind a relay, as the station can know them: 0 when no relay
/// reads the station's relay topic (`link_readers`), the relay's count when its status is at
/// most [`RELAY_STATUS_STALE_NS`] old, otherwise unknown.
pub fn listeners_behind_relay(
    link_readers: usize,
    status: Option<(&RelayStatus, i64)>,
    robot_topic: &str,
) -> Option<u64> {
    if link_readers == 0 {
        return Some(0);
    }
    let (status, age_ns) = status?;
    (age_ns <= RELAY_STATUS_STALE_NS).then(|| {
        status
            .robot_listeners
            .get(robot_topic)
            .copied()
            .unwrap_or(0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Feed ages `offset + jitter` at 100 Hz from `t0` for `seconds`; the news said.
    fn feed(monitor: &mut ClockOffsetMonitor, t0: i64, seconds: i64, offset: i64) -> Vec<String> {
        let mut said = Vec::new();
        for k in 0..seconds * 100 {
            let jitter = (k % 7) * MS / 2 + 300_000;
            if let Some(news) = monitor.observe(offset + jitter, t0 + k * 10 * MS) {
                said.push(news.to_string());
            }
        }
        said
    }

    #[test]
    fn an_offset_that_eats_into_the_limit_is_named_once_and_its_end_too() {
        let mut monitor = ClockOffsetMonitor::new(100);
        assert!(feed(&mut monitor, 0, 5, 2 * MS).is_empty());
        let estimate = monitor.estimate_ns().unwrap();
        assert!((2 * MS..3 * MS).contains(&estimate), "{estimate}");
        // The station's clock steps 80 ms back: seen within two windows, said once.
        let said = feed(&mut monitor, 5_000 * MS, 10, 80 * MS);
        assert_eq!(said.len(), 1, "{said:?}");
        assert!(said[0].contains("about 80 ms behind"), "{}", said[0]);
        assert!(said[0].contains("only 20 ms"), "{}", said[0]);
        assert!((80 * MS..81 * MS).contains(&monitor.estimate_ns().unwrap()));
        // Back in step.
        let said = feed(&mut monitor, 15_000 * MS, 5, MS);
        assert_eq!(said.len(), 1, "{said:?}");
        assert!(said[0].contains("back in step"), "{}", said[0]);
    }

    #[test]
    fn a_station_clock_ahead_stretches_the_limit_and_a_further_step_is_said_again() {
        let mut monitor = ClockOffsetMonitor::new(100);
        let said = feed(&mut monitor, 0, 5, -60 * MS);
        assert_eq!(said.len(), 1, "{said:?}");
        assert!(said[0].contains("about 60 ms ahead"), "{}", said[0]);
        assert!(said[0].contains("up to 160 ms old pass"), "{}", said[0]);
        // A small drift is not news; a step of half the warning threshold is.
        assert!(feed(&mut monitor, 5_000 * MS, 5, -65 * MS).is_empty());
        let said = feed(&mut monitor, 10_000 * MS, 5, -90 * MS);
        assert_eq!(said.len(), 1, "{said:?}");
        assert!(said[0].contains("about 90 ms ahead"), "{}", said[0]);
    }

    #[test]
    fn one_slow_command_does_not_move_the_estimate_but_a_burst_cannot_hide_a_fast_one() {
        let mut monitor = ClockOffsetMonitor::new(100);
        // Commands delayed 0–90 ms by a busy link, one of them quick: the offset is the quick one.
        for k in 0..400 {
            let age = if k % 50 == 7 { MS } else { (k % 90 + 5) * MS };
            assert_eq!(monitor.observe(age, k * 10 * MS), None);
        }
        assert_eq!(monitor.estimate_ns(), Some(MS));
    }

    #[test]
    fn the_station_sees_past_the_relay_to_the_robots_readers() {
        let topic = "/pomdar/hand/joint_targets";
        let mut status = RelayStatus::default();
        status.robot_listeners.insert(topic.into(), 2);
        let fresh = Some((&status, 400 * MS));
        assert_eq!(listeners_behind_relay(1, fresh, topic), Some(2));
        assert_eq!(listeners_behind_relay(1, fresh, "/other"), Some(0));
        assert_eq!(listeners_behind_relay(0, fresh, topic), Some(0));
        let stale = Some((&status, 2_500 * MS));
        assert_eq!(listeners_behind_relay(1, stale, topic), None);
        assert_eq!(listeners_behind_relay(1, None, topic), None);
    }
}
