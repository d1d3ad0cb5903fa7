//! A copy of what the station publishes and records, for a live viewer (`--view`): each
//! message already encoded as on the wire (CDR) with its ROS type name and its MCAP `ros2msg`
//! schema, so a viewer needs no knowledge of the message types.

use msgs::RosMessage;
use serde::Serialize;
use tokio::sync::broadcast;

/// One message the station sent (or published once, like the hand's drawing).
#[derive(Debug, Clone, PartialEq)]
pub struct TappedMessage {
    /// The ROS topic, e.g. `/tf`.
    pub topic: String,
    /// `pkg/msg/Type`, e.g. `tf2_msgs/msg/TFMessage`.
    pub ros_type_name: String,
    /// The complete `ros2msg` schema text (as in the MCAP log).
    pub schema_text: String,
    /// The CDR payload with its 4-byte encapsulation header.
    pub cdr: Vec<u8>,
    /// When the station sent it, nanoseconds on the station's clock.
    pub log_time_ns: i64,
    /// Whether a viewer that connects later should still be given it (the hand's drawing,
    /// `/tf_static`, `/robot_description`): the last such message per topic is kept.
    pub latched: bool,
}

impl TappedMessage {
    /// Encode `message` for `topic`; `None` if it cannot be encoded (never expected for the
    /// `msgs` types).
    pub fn encode<M: RosMessage + Serialize>(
        topic: &str,
        message: &M,
        log_time_ns: i64,
        latched: bool,
    ) -> Option<TappedMessage> {
        Some(TappedMessage {
            topic: topic.to_string(),
            ros_type_name: M::ros_type_name(),
            schema_text: M::schema_text(),
            cdr: msgs::to_cdr(message).ok()?,
            log_time_ns,
            latched,
        })
    }
}

/// The sending end; cheap to clone. A slow viewer loses the oldest messages, never stalls the
/// station.
#[derive(Debug, Clone)]
pub struct Tap {
    sender: broadcast::Sender<TappedMessage>,
}

impl Tap {
    /// A tap keeping up to `capacity` messages for each lagging receiver.
    pub fn new(capacity: usize) -> Tap {
        let (sender, _) = broadcast::channel(capacity.max(1));
        Tap { sender }
    }

    /// A new receiver (sees messages sent from now on).
    pub fn subscribe(&self) -> broadcast::Receiver<TappedMessage> {
        self.sender.subscribe()
    }

    /// Send a copy of `message` on `topic` if anyone listens.
    pub fn send<M: RosMessage + Serialize>(
        &self,
        topic: &str,
        message: &M,
        log_time_ns: i64,
        latched: bool,
    ) {
        if self.sender.receiver_count() == 0 {
            return;
        }
        if let Some(tapped) = TappedMessage::encode(topic, message, log_time_ns, latched) {
            self.sender.send(tapped).ok();
        }
    }
}
