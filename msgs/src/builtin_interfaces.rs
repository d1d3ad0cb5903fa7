//! `builtin_interfaces`: time.

use serde::{Deserialize, Serialize};

use crate::{MsgDefinition, RosMessage};

const NANOS_PER_SEC: i64 = 1_000_000_000;

/// `builtin_interfaces/msg/Time`: a point in time as seconds plus nanoseconds.
///
/// The time is `sec + nanosec·10⁻⁹` seconds with `nanosec` in `[0, 10⁹)`, so -1.5 s is
/// `{sec: -2, nanosec: 500_000_000}`. Which clock it is read from is the caller's business.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default, Serialize, Deserialize,
)]
pub struct Time {
    /// Whole seconds (may be negative).
    pub sec: i32,
    /// Nanoseconds added to `sec`, in `[0, 10⁹)` when well formed.
    pub nanosec: u32,
}

impl Time {
    /// The time `nanos` nanoseconds after the clock's zero.
    ///
    /// Times outside the representable range (`i32` seconds, about ±68 years around the
    /// zero) saturate to its first or last nanosecond.
    pub fn from_nanos(nanos: i64) -> Self {
        let sec = nanos.div_euclid(NANOS_PER_SEC);
        let nanosec = nanos.rem_euclid(NANOS_PER_SEC);
        match (i32::try_from(sec), u32::try_from(nanosec)) {
            (Ok(sec), Ok(nanosec)) => Time { sec, nanosec },
            _ if sec < 0 => Time {
                sec: i32::MIN,
                nanosec: 0,
            },
            _ => Time {
                sec: i32::MAX,
                nanosec: 999_999_999,
            },
        }
    }

    /// Nanoseconds since the clock's zero. Exact for every `Time`, including a malformed
    /// `nanosec` ≥ 10⁹ (it is simply added).
    pub fn to_nanos(&self) -> i64 {
        i64::from(self.sec) * NANOS_PER_SEC + i64::from(self.nanosec)
    }
}

impl RosMessage for Time {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "builtin_interfaces",
        name: "Time",
        text: "int32 sec\nuint32 nanosec\n",
        dependencies: &[],
    };
}

/// `builtin_interfaces/msg/Duration`: a span of time as seconds plus nanoseconds (a marker's
/// lifetime; zero means forever).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub struct Duration {
    /// Whole seconds (may be negative).
    pub sec: i32,
    /// Nanoseconds added to `sec`, in `[0, 10⁹)` when well formed.
    pub nanosec: u32,
}

impl RosMessage for Duration {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "builtin_interfaces",
        name: "Duration",
        text: "int32 sec\nuint32 nanosec\n",
        dependencies: &[],
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn negative_times_borrow_from_the_seconds() {
        assert_eq!(
            Time::from_nanos(-1_500_000_000),
            Time {
                sec: -2,
                nanosec: 500_000_000
            }
        );
        assert_eq!(
            Time::from_nanos(-1),
            Time {
                sec: -1,
                nanosec: 999_999_999
            }
        );
        assert_eq!(
            Time::from_nanos(1_700_000_000_123_456_789).nanosec,
            123_456_789
        );
    }

    #[test]
    fn out_of_range_times_saturate() {
        assert_eq!(Time::from_nanos(i64::MAX).sec, i32::MAX);
        assert_eq!(Time::from_nanos(i64::MAX).nanosec, 999_999_999);
        assert_eq!(
            Time::from_nanos(i64::MIN),
            Time {
                sec: i32::MIN,
                nanosec: 0
            }
        );
    }

    proptest! {
        #[test]
        fn nanos_round_trip(sec in any::<i32>(), nanosec in 0u32..1_000_000_000) {
            let t = Time { sec, nanosec };
            prop_assert_eq!(Time::from_nanos(t.to_nanos()), t);
        }

        #[test]
        fn from_nanos_is_normalised(nanos in any::<i64>()) {
            let t = Time::from_nanos(nanos);
            prop_assert!(t.nanosec < 1_000_000_000);
            let representable = (i64::from(i32::MIN) * NANOS_PER_SEC)
                ..=(i64::from(i32::MAX) * NANOS_PER_SEC + 999_999_999);
            if representable.contains(&nanos) {
                prop_assert_eq!(t.to_nanos(), nanos);
            }
        }
    }
}
