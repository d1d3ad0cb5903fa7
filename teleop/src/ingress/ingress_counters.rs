//! What the ingress counts, how it orders packets by their studio timestamp, and its status
//! report. Pure: times are parameters.
//!
//! Order, by `scene.timestamp` against the newest accepted one:
//! - newer: a new frame, published;
//! - equal: a duplicate (Studio or the network sent the same frame twice), dropped;
//! - older by less than `restart_after_backwards_s`: out of order (UDP reordering), dropped;
//! - older by more: maybe Studio restarted its clock, maybe a stray or spoofed packet. One
//!   such packet proves nothing: it is dropped and counted (`restart_unconfirmed`). Only
//!   `restart_confirm_packets` of them in a row, each newer than the one before by at most
//!   `restart_after_backwards_s` (a restarted stream running on), with no new packet of the
//!   current stream between them, are taken for a restart: the last is accepted as new and
//!   counted as a restart. A single old-stamped packet never resets the order, and a single
//!   far-future one is outlived the same way (the real stream, now "far older", restarts it).
//! - no timestamp: refused before ordering (`no_timestamp`, see the packet parser): nothing
//!   bypasses these checks.
//!
//! A message the DDS writer refuses is counted by topic (`publish_failed`); a frame counts as
//! published when both its keypoints and its wrist pose went out.

use std::collections::{BTreeMap, BTreeSet};

use serde::Serialize;
use serde_json::{Value, json};

/// The device an ingress reads, as its status report and the trial logs name it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct SourceInfo {
    /// The kind of source: `rokoko`, `avp`, `simulated`.
    pub kind: &'static str,
    /// Which device, for a person: its address or port.
    pub device: String,
}

/// A packet's place in the stream.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    /// Newer than every accepted packet (or unstamped): publish.
    New,
    /// Same timestamp as the newest: drop.
    Duplicate,
    /// Older than the newest, within the restart threshold: drop.
    OutOfOrder,
    /// Far older, but not yet confirmed as a restart: drop.
    RestartUnconfirmed,
    /// Far older, the last of a confirmed run: the stream restarted; publish.
    Restart,
}

/// The ordering rule's two settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrderRule {
    /// A timestamp this much older than the newest is a restart candidate, seconds.
    pub restart_after_s: f64,
    /// Candidates in a row needed to accept a restart (at least 2).
    pub confirm_packets: u32,
}

/// Counts since start, and the newest studio timestamp.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct IngressCounters {
    /// Datagrams received.
    pub received: u64,
    /// Frames published.
    pub published: u64,
    /// Dropped: same timestamp as the newest frame.
    pub duplicates: u64,
    /// Dropped: older than the newest frame.
    pub out_of_order: u64,
    /// Timestamps that jumped back past the restart threshold, confirmed (published).
    pub restarts: u64,
    /// Dropped: far older than the newest, not (yet) confirmed as a restart.
    pub restart_unconfirmed: u64,
    /// Refused packets by kind (`sender`, `oversized`, `truncated`, `malformed`, `version`,
    /// `no_timestamp`, `no_actor`, `missing_bone`).
    pub refused: BTreeMap<&'static str, u64>,
    /// Messages whose publishing failed (not sent), by topic.
    pub publish_failed: BTreeMap<String, u64>,
    /// For a source the ingress connects to: whether it is connected now.
    pub connected: Option<bool>,
    /// Connections made after the first (the source went away and came back).
    pub reconnects: u64,
    newest_timestamp_s: Option<f64>,
    /// The run of restart candidates: the last one's timestamp and how many in a row.
    restart_run: Option<(f64, u32)>,
    logged: BTreeSet<&'static str>,
    window_start_ns: Option<i64>,
    window_published: u64,
    rate_hz: f64,
    last_packet_ns: Option<i64>,
}

impl IngressCounters {
    /// Count a received datagram at `now_ns`.
    pub fn received(&mut self, now_ns: i64) {
        self.received += 1;
        self.last_packet_ns = Some(now_ns);
    }

    /// Place a parsed packet's timestamp in the stream (and remember it when accepted).
    pub fn order(&mut self, t: f64, rule: OrderRule) -> Order {
        let Some(newest) = self.newest_timestamp_s else {
            self.newest_timestamp_s = Some(t);
            return Order::New;
        };
        if t > newest {
            self.newest_timestamp_s = Some(t);
            self.restart_run = None;
            return Order::New;
        }
        if t == newest {
            self.duplicates += 1;
            return Order::Duplicate;
        }
        if newest - t <= rule.restart_after_s {
            self.out_of_order += 1;
            return Order::OutOfOrder;
        }
        let run = match self.restart_run {
            Some((last, n)) if t > last && t - last <= rule.restart_after_s => n + 1,
            _ => 1,
        };
        if run >= rule.confirm_packets {
            self.newest_timestamp_s = Some(t);
            self.restart_run = None;
            self.restarts += 1;
            Order::Restart
        } else {
            self.restart_run = Some((t, run));
            self.restart_unconfirmed += 1;
            Order::RestartUnconfirmed
        }
    }

    /// Count a refused packet; `true` the first time this kind is seen (log it then only).
    pub fn refused(&mut self, kind: &'static str) -> bool {
        *self.refused.entry(kind).or_default() += 1;
        self.logged.insert(kind)
    }

    /// Count a published frame.
    pub fn published(&mut self) {
        self.published += 1;
        self.window_published += 1;
    }

    /// Count a message on `topic` that could not be published.
    pub fn publish_failed(&mut self, topic: &str) {
        *self.publish_failed.entry(topic.to_string()).or_default() += 1;
    }

    /// Count a frame whose keypoints (on `keypoints_topic`) and wrist pose (on `wrist_topic`)
    /// were (`true`) or were not sent: published when both went out.
    pub fn frame_sent(
        &mut self,
        (keypoints_topic, keypoints_sent): (&str, bool),
        (wrist_topic, wrist_sent): (&str, bool),
    ) {
        if !keypoints_sent {
            self.publish_failed(keypoints_topic);
        }
        if !wrist_sent {
            self.publish_failed(wrist_topic);
        }
        if keypoints_sent && wrist_sent {
            self.published();
        }
    }

    /// Dropped packets of every kind.
    pub fn dropped(&self) -> u64 {
        self.duplicates
            + self.out_of_order
            + self.restart_unconfirmed
            + self.refused.values().sum::<u64>()
    }

    /// The status report at `now_ns` for `source` (also closes the rate window).
    pub fn status(&mut self, now_ns: i64, source: &SourceInfo) -> Value {
        if let Some(start) = self.window_start_ns
            && now_ns > start
        {
            self.rate_hz = self.window_published as f64 / ((now_ns - start) as f64 * 1e-9);
        }
        self.window_start_ns = Some(now_ns);
        self.window_published = 0;
        json!({
            "node": format!("{}_ingress", source.kind),
            "source": source,
            "connected": self.connected,
            "reconnects": self.reconnects,
            "received": self.received,
            "published": self.published,
            "rate_hz": (self.rate_hz * 10.0).round() / 10.0,
            "dropped": self.dropped(),
            "duplicates": self.duplicates,
            "out_of_order": self.out_of_order,
            "restarts": self.restarts,
            "restart_unconfirmed": self.restart_unconfirmed,
            "refused": self.refused,
            "publish_failed": self.publish_failed,
            "last_packet_age_s": self.last_packet_ns.map(|t| (now_ns - t) as f64 * 1e-9),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rokoko() -> SourceInfo {
        SourceInfo {
            kind: "rokoko",
            device: "UDP 0.0.0.0:14043".into(),
        }
    }

    const RULE: OrderRule = OrderRule {
        restart_after_s: 1.0,
        confirm_packets: 3,
    };

    #[test]
    fn packets_are_ordered_by_their_timestamps() {
        let mut c = IngressCounters::default();
        assert_eq!(c.order(10.0, RULE), Order::New);
        assert_eq!(c.order(10.01, RULE), Order::New);
        assert_eq!(c.order(10.01, RULE), Order::Duplicate);
        assert_eq!(c.order(10.0, RULE), Order::OutOfOrder);
        assert_eq!(c.order(10.02, RULE), Order::New);
        // Studio restarted: its clock starts again near 0; the third packet in a row confirms.
        assert_eq!(c.order(0.5, RULE), Order::RestartUnconfirmed);
        assert_eq!(c.order(0.51, RULE), Order::RestartUnconfirmed);
        assert_eq!(c.order(0.52, RULE), Order::Restart);
        assert_eq!(c.order(0.53, RULE), Order::New);
        assert_eq!(c.order(0.525, RULE), Order::OutOfOrder);
        assert_eq!((c.duplicates, c.out_of_order, c.restarts), (1, 2, 1));
        assert_eq!(c.restart_unconfirmed, 2);
        assert_eq!(c.dropped(), 5);
    }

    #[test]
    fn one_spoofed_old_packet_does_not_reset_the_order() {
        let mut c = IngressCounters::default();
        let mut t = 100.0;
        for _ in 0..5 {
            t += 0.01;
            assert_eq!(c.order(t, RULE), Order::New);
            // One old-stamped packet between each pair of real ones, even rising: each new
            // packet of the real stream ends the run.
            assert_eq!(c.order(t - 50.0, RULE), Order::RestartUnconfirmed);
        }
        assert_eq!(
            c.order(t - 0.005, RULE),
            Order::OutOfOrder,
            "still ordered by {t}"
        );
        assert_eq!(c.restarts, 0);
        // Candidates must rise and be close together: these three are not one stream.
        assert_eq!(c.order(1.0, RULE), Order::RestartUnconfirmed);
        assert_eq!(c.order(0.5, RULE), Order::RestartUnconfirmed);
        assert_eq!(c.order(30.0, RULE), Order::RestartUnconfirmed);
        assert_eq!(c.restarts, 0);
    }

    #[test]
    fn a_spoofed_future_packet_is_outlived_by_the_real_stream() {
        let mut c = IngressCounters::default();
        assert_eq!(c.order(10.0, RULE), Order::New);
        assert_eq!(c.order(1e9, RULE), Order::New);
        assert_eq!(c.order(10.01, RULE), Order::RestartUnconfirmed);
        assert_eq!(c.order(10.02, RULE), Order::RestartUnconfirmed);
        assert_eq!(c.order(10.03, RULE), Order::Restart);
        assert_eq!(c.order(10.04, RULE), Order::New);
    }

    #[test]
    fn each_refusal_kind_is_logged_once() {
        let mut c = IngressCounters::default();
        assert!(c.refused("malformed"));
        assert!(!c.refused("malformed"));
        assert!(c.refused("truncated"));
        assert_eq!(c.refused["malformed"], 2);
        assert_eq!(c.dropped(), 3);
    }

    #[test]
    fn publish_failures_are_counted_by_topic_and_reported() {
        let mut c = IngressCounters::default();
        c.frame_sent(("/k", true), ("/w", true));
        c.frame_sent(("/k", false), ("/w", true));
        c.frame_sent(("/k", false), ("/w", false));
        c.publish_failed("/s");
        assert_eq!(c.published, 1);
        let status = c.status(0, &rokoko());
        assert_eq!(status["publish_failed"]["/k"], 2);
        assert_eq!(status["publish_failed"]["/w"], 1);
        assert_eq!(status["publish_failed"]["/s"], 1);
        assert_eq!(c.dropped(), 0);
    }

    #[test]
    fn the_status_reports_the_rate_over_its_window() {
        let mut c = IngressCounters::default();
        c.status(0, &rokoko());
        for k in 0..50 {
            c.received(k * 20_000_000);
            c.published();
        }
        let status = c.status(1_000_000_000, &rokoko());
        assert_eq!(status["rate_hz"], 50.0);
        assert_eq!(status["published"], 50);
        assert_eq!(status["node"], "rokoko_ingress");
        assert_eq!(status["source"]["kind"], "rokoko");
        assert_eq!(status["source"]["device"], "UDP 0.0.0.0:14043");
        assert!((status["last_packet_age_s"].as_f64().unwrap() - 0.02).abs() < 1e-9);
    }
}
