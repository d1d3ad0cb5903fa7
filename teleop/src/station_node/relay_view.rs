//! The station's view of `pomdar relay`, when its commands go through one: the relay's last
//! status ([`RelayStatus`], best effort on `[robot_link]`'s status topic) and what it says
//! about the robot's own readers, so the status's `listeners` (and the console's "no hand is
//! listening") look past the relay to the robot's drivers.

use msgs::StringMsg;
use ros2_client::Subscription;
use serde_json::{Value, json};
use station::link_clock::{RelayStatus, listeners_behind_relay};

/// The relay's last status and when it was received (the station's clock).
#[derive(Debug, Default)]
pub struct RelayView {
    last: Option<(RelayStatus, i64)>,
    /// Statuses that could not be read or parsed.
    pub unreadable: u64,
}

impl RelayView {
    /// Take every status waiting on `subscription`, keeping the newest, received at `now_ns`.
    pub fn poll(&mut self, subscription: &Subscription<StringMsg>, now_ns: i64) {
        loop {
            match subscription.take() {
                Ok(Some((message, _))) => match serde_json::from_str(&message.data) {
                    Ok(status) => self.last = Some((status, now_ns)),
                    Err(_) => self.unreadable += 1,
                },
                Ok(None) => break,
                Err(_) => self.unreadable += 1,
            }
        }
    }

    /// The readers of `robot_topic` behind the relay, given the readers of its relay topic.
    pub fn listeners(&self, link_readers: usize, robot_topic: &str, now_ns: i64) -> Option<u64> {
        let last = self
            .last
            .as_ref()
            .map(|(status, at)| (status, now_ns.saturating_sub(*at)));
        listeners_behind_relay(link_readers, last, robot_topic)
    }

    /// The status's `relay` object: the relay topic's readers, the last status's age and what
    /// it said.
    pub fn document(&self, link_readers: Option<usize>, now_ns: i64) -> Value {
        let (age_ms, status) = match &self.last {
            Some((status, at)) => (
                Some(now_ns.saturating_sub(*at) as f64 * 1e-6),
                serde_json::to_value(status).ok(),
            ),
            None => (None, None),
        };
        json!({
            "link_readers": link_readers,
            "status_age_ms": age_ms,
            "status": status,
            "unreadable": self.unreadable,
        })
    }
}
