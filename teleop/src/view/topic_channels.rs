//! One Foxglove channel per tapped topic, made on the topic's first message, and the last
//! latched message of each topic for viewers that subscribe later.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, PoisonError};

use foxglove::websocket::{ChannelView, Client, ServerListener};
use foxglove::{ChannelId, Context, PartialMetadata, RawChannel, Schema};
use serde::Serialize;

use crate::station_node::tap::TappedMessage;

/// The message encoding of every channel: the CDR the station puts on the wire.
pub const MESSAGE_ENCODING: &str = "cdr";
/// The schema encoding of every channel: ROS 2 `.msg` text with its dependencies (as in MCAP).
pub const SCHEMA_ENCODING: &str = "ros2msg";

/// What the live view did with the tapped messages.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct ViewCounts {
    /// Messages handed to the server (sent to the viewers subscribed to their topic).
    pub forwarded: u64,
    /// Messages the view fell too far behind to take (the oldest were dropped).
    pub lagged: u64,
    /// Messages whose type differed from the first one seen on their topic (not sent).
    pub type_mismatch: u64,
    /// Latched messages sent again to a viewer that subscribed after them.
    pub replayed: u64,
}

/// A topic's channel and the type it was made for.
#[derive(Debug)]
struct TopicChannel {
    channel: Arc<RawChannel>,
    ros_type_name: String,
}

/// The last latched message of a channel.
#[derive(Debug, Clone)]
struct Latched {
    channel: Arc<RawChannel>,
    cdr: Arc<[u8]>,
    log_time_ns: Option<u64>,
}

/// The latched messages by channel, shared with the server's subscribe callback.
#[derive(Debug, Default)]
pub(crate) struct LatchedStore {
    by_channel: Mutex<HashMap<ChannelId, Latched>>,
    replayed: std::sync::atomic::AtomicU64,
}

impl LatchedStore {
    fn keep(&self, latched: Latched) {
        let mut map = self
            .by_channel
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        map.insert(latched.channel.id(), latched);
    }

    fn get(&self, id: ChannelId) -> Option<Latched> {
        let map = self
            .by_channel
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        map.get(&id).cloned()
    }

    /// How many latched messages were sent again to late subscribers.
    pub(crate) fn replayed(&self) -> u64 {
        self.replayed.load(std::sync::atomic::Ordering::Relaxed)
    }
}

/// The server's callback: a viewer that subscribes to a channel gets that channel's last
/// latched message (the hand's drawing, `/tf_static`) at once, and only that viewer.
///
/// The SDK registers the subscription before it calls back, and logging to a client only
/// queues the message (lossy, never blocking), so this never holds up the client's loop.
#[derive(Debug)]
pub(crate) struct ReplayLatched(pub(crate) Arc<LatchedStore>);

impl ServerListener for ReplayLatched {
    fn on_subscribe(&self, client: Client, channel: ChannelView) {
        let Some(latched) = self.0.get(channel.id()) else {
            return;
        };
        latched.channel.log_with_meta_to_sink(
            &latched.cdr,
            PartialMetadata {
                log_time: latched.log_time_ns,
            },
            client.sink_id(),
        );
        self.0
            .replayed
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }
}

/// The channels of one view, by topic.
pub(crate) struct TopicChannels {
    context: Arc<Context>,
    by_topic: HashMap<String, TopicChannel>,
    latched: Arc<LatchedStore>,
    pub(crate) counts: ViewCounts,
}

impl TopicChannels {
    pub(crate) fn new(context: Arc<Context>, latched: Arc<LatchedStore>) -> TopicChannels {
        TopicChannels {
            context,
            by_topic: HashMap::new(),
            latched,
            counts: ViewCounts::default(),
        }
    }

    /// The topics with a channel, sorted.
    pub(crate) fn topics(&self) -> Vec<String> {
        let mut topics: Vec<String> = self.by_topic.keys().cloned().collect();
        topics.sort();
        topics
    }

    /// Send `message` to the viewers subscribed to its topic (making the topic's channel on
    /// its first message); keep it for later viewers when it is latched.
    pub(crate) fn forward(&mut self, message: TappedMessage) {
        let Some(channel) = self.channel_for(&message) else {
            self.counts.type_mismatch += 1;
            return;
        };
        let log_time_ns = u64::try_from(message.log_time_ns).ok();
        channel.log_with_meta(
            &message.cdr,
            PartialMetadata {
                log_time: log_time_ns,
            },
        );
        self.counts.forwarded += 1;
        if message.latched {
            self.latched.keep(Latched {
                channel,
                cdr: message.cdr.into(),
                log_time_ns,
            });
        }
    }

    /// The topic's channel, made now if this is its first message; `None` if the topic's
    /// channel carries another type.
    fn channel_for(&mut self, message: &TappedMessage) -> Option<Arc<RawChannel>> {
        if let Some(existing) = self.by_topic.get(&message.topic) {
            return (existing.ros_type_name == message.ros_type_name)
                .then(|| existing.channel.clone());
        }
        let schema = Schema::new(
            message.ros_type_name.clone(),
            SCHEMA_ENCODING,
            message.schema_text.clone().into_bytes(),
        );
        // Fails only without a message encoding, which is always given.
        let channel = self
            .context
            .channel_builder(message.topic.clone())
            .message_encoding(MESSAGE_ENCODING)
            .schema(schema)
            .build_raw()
            .ok()?;
        self.by_topic.insert(
            message.topic.clone(),
            TopicChannel {
                channel: channel.clone(),
                ros_type_name: message.ros_type_name.clone(),
            },
        );
        Some(channel)
    }
}
