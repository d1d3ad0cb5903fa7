//! What `pomdar probe` says about the timing of a topic's samples: how old each stamped one
//! was when it arrived (receive time minus its header stamp, both wall clocks) and when the
//! topic went silent. On the robot's computer this shows whether old commands reach the robot
//! (after a cut link, docs/DEPLOYMENT.md) and how soon commands resume.

use msgs::{Float32MultiArray, JointState, PoseArray, PoseStamped, StringMsg};
use serde::Serialize;

/// A pause between two samples at least this long is a silence, nanoseconds.
pub const SILENCE_NS: i64 = 250_000_000;

/// The header stamp of a message type that has one.
pub trait HeaderStamp {
    /// The header stamp, nanoseconds since the epoch; None for a type without a header.
    fn header_stamp_ns(&self) -> Option<i64>;
}

impl HeaderStamp for JointState {
    fn header_stamp_ns(&self) -> Option<i64> {
        Some(self.header.stamp.to_nanos())
    }
}

impl HeaderStamp for PoseStamped {
    fn header_stamp_ns(&self) -> Option<i64> {
        Some(self.header.stamp.to_nanos())
    }
}

impl HeaderStamp for PoseArray {
    fn header_stamp_ns(&self) -> Option<i64> {
        Some(self.header.stamp.to_nanos())
    }
}

impl HeaderStamp for Float32MultiArray {
    fn header_stamp_ns(&self) -> Option<i64> {
        None
    }
}

impl HeaderStamp for StringMsg {
    fn header_stamp_ns(&self) -> Option<i64> {
        None
    }
}

/// One sample's arrival.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Arrival {
    /// Receive time, nanoseconds since the epoch.
    pub received_ns: i64,
    /// Its header stamp, if its type has one.
    pub stamp_ns: Option<i64>,
}

/// A pause in a topic.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Silence {
    /// The last sample before it, nanoseconds since the epoch.
    pub from_unix_ns: i64,
    /// The first sample after it.
    pub to_unix_ns: i64,
    /// Its length, seconds.
    pub seconds: f64,
}

/// Ages and silences of one topic.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TopicTiming {
    /// Median age of the stamped samples, milliseconds (receive time − header stamp).
    pub age_p50_ms: Option<f64>,
    /// The oldest stamped sample's age, milliseconds.
    pub age_max_ms: Option<f64>,
    /// The age limit counted against, milliseconds.
    pub age_limit_ms: u64,
    /// Stamped samples older than the limit when they arrived.
    pub older_than_limit: u64,
    /// Pauses of at least [`SILENCE_NS`], in order.
    pub silences: Vec<Silence>,
}

impl TopicTiming {
    /// The timing of `arrivals` (in arrival order), ages counted against `age_limit_ms`.
    pub fn of(arrivals: &[Arrival], age_limit_ms: u64) -> TopicTiming {
        let mut ages: Vec<i64> = arrivals
            .iter()
            .filter_map(|a| a.stamp_ns.map(|s| a.received_ns - s))
            .collect();
        ages.sort_unstable();
        let limit_ns = i64::try_from(age_limit_ms)
            .unwrap_or(i64::MAX / 1_000_000)
            .saturating_mul(1_000_000);
        let silences = arrivals
            .windows(2)
            .filter(|w| w[1].received_ns - w[0].received_ns >= SILENCE_NS)
            .map(|w| Silence {
                from_unix_ns: w[0].received_ns,
                to_unix_ns: w[1].received_ns,
                seconds: (w[1].received_ns - w[0].received_ns) as f64 * 1e-9,
            })
            .collect();
        TopicTiming {
            age_p50_ms: ages.get(ages.len() / 2).map(|a| *a as f64 * 1e-6),
            age_max_ms: ages.last().map(|a| *a as f64 * 1e-6),
            age_limit_ms,
            older_than_limit: ages.iter().filter(|a| **a > limit_ns).count() as u64,
            silences,
        }
    }

    /// The longest silence.
    pub fn longest_silence(&self) -> Option<&Silence> {
        self.silences
            .iter()
            .max_by(|a, b| a.seconds.total_cmp(&b.seconds))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: i64 = 1_000_000;

    fn at(received_ms: i64, age_ms: i64) -> Arrival {
        Arrival {
            received_ns: received_ms * MS,
            stamp_ns: Some((received_ms - age_ms) * MS),
        }
    }

    #[test]
    fn ages_count_what_was_old_on_arrival_and_silences_are_the_long_pauses() {
        let arrivals = [
            at(0, 2),
            at(40, 3),
            at(80, 1),
            // a 3 s cut, then the old commands resent at once and the current one
            at(3080, 3000),
            at(3081, 2960),
            at(3082, 2),
            at(3120, 2),
        ];
        let timing = TopicTiming::of(&arrivals, 100);
        assert_eq!(timing.older_than_limit, 2);
        assert_eq!(timing.age_max_ms, Some(3000.0));
        assert_eq!(timing.age_p50_ms, Some(2.0));
        assert_eq!(timing.silences.len(), 1);
        let silence = timing.longest_silence().unwrap();
        assert_eq!(
            (silence.from_unix_ns, silence.to_unix_ns),
            (80 * MS, 3080 * MS)
        );
        assert!((silence.seconds - 3.0).abs() < 1e-12);
    }

    #[test]
    fn unstamped_types_have_no_ages_but_silences() {
        let arrivals = [0, 300, 340].map(|ms| Arrival {
            received_ns: ms * MS,
            stamp_ns: None,
        });
        let timing = TopicTiming::of(&arrivals, 100);
        assert_eq!((timing.age_p50_ms, timing.age_max_ms), (None, None));
        assert_eq!(timing.older_than_limit, 0);
        assert_eq!(timing.silences.len(), 1);
        assert_eq!(Float32MultiArray::default().header_stamp_ns(), None);
    }
}
