//! Which side stalled: the longest gap between new glove frames as the station received them,
//! beside the gap between the same two frames by their senders' stamps.
//!
//! A receive gap much longer than its send gap means the frames were captured on time and
//! reached the station late (the network, or the station's own loop was busy); a send gap as
//! long as the receive gap means the glove (or its driver) stopped sending. The status carries
//! the longest gap since the station started, so a stale-input refusal can say which it was.

use serde::Serialize;

/// One gap between consecutive new frames.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct InputGap {
    /// Between the two frames' receive times, milliseconds.
    pub received_ms: f64,
    /// Between the two frames' senders' stamps, milliseconds (negative after a sender's clock
    /// stepped back).
    pub sent_ms: f64,
    /// The receive time of the frame that ended the gap (the station's clock), nanoseconds.
    #[serde(skip)]
    pub ended_ns: i64,
}

/// The longest receive gap between new frames so far.
#[derive(Debug, Clone, Default)]
pub struct GapMeter {
    /// The last new frame: (receive time, sender's stamp), nanoseconds.
    last: Option<(i64, i64)>,
    longest: Option<InputGap>,
}

impl GapMeter {
    /// A new frame received at `received_ns`, stamped `source_ns` by its sender.
    pub fn record(&mut self, received_ns: i64, source_ns: i64) {
        if let Some((last_received, last_source)) = self.last {
            let gap = InputGap {
                received_ms: received_ns.saturating_sub(last_received) as f64 * 1e-6,
                sent_ms: source_ns.saturating_sub(last_source) as f64 * 1e-6,
                ended_ns: received_ns,
            };
            if self
                .longest
                .is_none_or(|longest| gap.received_ms > longest.received_ms)
            {
                self.longest = Some(gap);
            }
        }
        self.last = Some((received_ns, source_ns));
    }

    /// The longest gap so far (`None` before two new frames).
    pub fn longest(&self) -> Option<InputGap> {
        self.longest
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: i64 = 1_000_000;

    #[test]
    fn keeps_the_longest_receive_gap_with_the_senders_gap_of_the_same_two_frames() {
        let mut meter = GapMeter::default();
        meter.record(0, 5 * MS);
        assert_eq!(meter.longest(), None);
        meter.record(10 * MS, 15 * MS);
        // Sent 10 ms apart, received 250 ms apart: delivered late.
        meter.record(260 * MS, 25 * MS);
        meter.record(270 * MS, 35 * MS);
        // Sent and received 120 ms apart: shorter, so not kept.
        meter.record(390 * MS, 155 * MS);
        let longest = meter.longest().unwrap();
        assert_eq!(longest.received_ms, 250.0);
        assert_eq!(longest.sent_ms, 10.0);
        assert_eq!(longest.ended_ns, 260 * MS);
    }

    #[test]
    fn a_sender_that_stopped_shows_the_same_gap_on_both_sides() {
        let mut meter = GapMeter::default();
        meter.record(0, 1_000 * MS);
        meter.record(300 * MS, 1_300 * MS);
        let longest = meter.longest().unwrap();
        assert_eq!((longest.received_ms, longest.sent_ms), (300.0, 300.0));
    }
}
