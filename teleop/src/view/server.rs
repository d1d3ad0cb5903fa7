//! The live view's WebSocket server (the Foxglove SDK's) fed from the station's tap.

use std::net::SocketAddr;
use std::sync::Arc;

use foxglove::{Context, WebSocketServer, WebSocketServerHandle};
use tokio::sync::{broadcast, oneshot};
use tokio::task::JoinHandle;

use super::address::ViewAddress;
use super::error::ViewError;
use super::topic_channels::{LatchedStore, ReplayLatched, TopicChannels, ViewCounts};
use crate::station_node::tap::TappedMessage;

/// Messages queued for each viewer before the oldest are dropped (the SDK's default is 1024;
/// at the station's rates this is a few seconds of every topic).
const BACKLOG_PER_VIEWER: usize = 1024;

/// How long stopping waits for the viewers' connections to close.
const STOP_GRACE: std::time::Duration = std::time::Duration::from_secs(2);

/// A running live view: a Foxglove WebSocket server with one channel per tapped topic.
///
/// It takes the tap's messages in its own task: the station only ever copies a message into
/// the tap's broadcast, and a view that falls behind loses the oldest messages (counted in
/// [`ViewCounts::lagged`]), never slows the station.
pub struct ViewServer {
    handle: WebSocketServerHandle,
    address: SocketAddr,
    forwarder: JoinHandle<(ViewCounts, Vec<String>)>,
    stop: oneshot::Sender<()>,
    latched: Arc<LatchedStore>,
}

impl std::fmt::Debug for ViewServer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ViewServer")
            .field("address", &self.address)
            .finish_non_exhaustive()
    }
}

/// What a stopped view did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ViewReport {
    /// What happened to the tapped messages.
    pub counts: ViewCounts,
    /// The topics that had a channel, sorted.
    pub topics: Vec<String>,
}

impl ViewServer {
    /// Start the server on `address` (on the current tokio runtime) and forward `messages`
    /// (a receiver of the station's tap) to it until [`ViewServer::stop`] or until the tap is
    /// dropped.
    pub async fn start(
        address: ViewAddress,
        messages: broadcast::Receiver<TappedMessage>,
    ) -> Result<ViewServer, ViewError> {
        // A context of its own: several views (tests) in one process never share channels.
        let context = Context::new();
        let latched = Arc::new(LatchedStore::default());
        let handle = WebSocketServer::new()
            .name("POMDAR station")
            .bind(address.0.ip().to_string(), address.0.port())
            .context(&context)
            .listener(Arc::new(ReplayLatched(latched.clone())))
            .message_backlog_size(BACKLOG_PER_VIEWER)
            .start()
            .await
            .map_err(|e| ViewError::starting(address.0, e))?;
        let bound = SocketAddr::new(address.0.ip(), handle.port());
        let channels = TopicChannels::new(context, latched.clone());
        let (stop, stop_rx) = oneshot::channel();
        let forwarder = tokio::spawn(forward(messages, channels, stop_rx));
        Ok(ViewServer {
            handle,
            address: bound,
            forwarder,
            stop,
            latched,
        })
    }

    /// The address it listens on (the port chosen when 0 was asked for).
    pub fn local_address(&self) -> SocketAddr {
        self.address
    }

    /// `ws://ADDR:PORT`.
    pub fn url(&self) -> String {
        format!("ws://{}", self.address)
    }

    /// The line the commands print on start.
    pub fn announcement(&self) -> String {
        let all = if self.address.ip().is_unspecified() {
            " (all interfaces: use this host's address)"
        } else {
            ""
        };
        format!(
            "live view: {}{all} — open it in the Foxglove app (Open connection → Foxglove WebSocket)",
            self.url()
        )
    }

    /// Viewers connected now.
    pub fn client_count(&self) -> usize {
        self.handle.client_count()
    }

    /// Stop forwarding, close the server and say what it did.
    pub async fn stop(self) -> ViewReport {
        self.stop.send(()).ok();
        let (mut counts, topics) = self.forwarder.await.unwrap_or_default();
        counts.replayed = self.latched.replayed();
        // A viewer that stopped reading must not hold up the command's exit: past the grace
        // period the remaining client tasks are dropped (aborted).
        tokio::time::timeout(STOP_GRACE, self.handle.stop().wait())
            .await
            .ok();
        ViewReport { counts, topics }
    }
}

/// Forward the tap's messages until told to stop (then those already queued as well) or the
/// tap closes.
async fn forward(
    mut messages: broadcast::Receiver<TappedMessage>,
    mut channels: TopicChannels,
    mut stop: oneshot::Receiver<()>,
) -> (ViewCounts, Vec<String>) {
    loop {
        tokio::select! {
            received = messages.recv() => match received {
                Ok(message) => channels.forward(message),
                Err(broadcast::error::RecvError::Lagged(lost)) => channels.counts.lagged += lost,
                Err(broadcast::error::RecvError::Closed) => break,
            },
            _ = &mut stop => {
                loop {
                    match messages.try_recv() {
                        Ok(message) => channels.forward(message),
                        Err(broadcast::error::TryRecvError::Lagged(lost)) => {
                            channels.counts.lagged += lost;
                        }
                        Err(_) => break,
                    }
                }
                break;
            }
        }
    }
    (channels.counts, channels.topics())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use msgs::StringMsg;

    use super::*;
    use crate::station_node::tap::Tap;

    #[tokio::test]
    async fn an_address_in_use_is_named() {
        let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        let address = ViewAddress(taken.local_addr().unwrap());
        let tap = Tap::new(4);
        let error = ViewServer::start(address, tap.subscribe())
            .await
            .unwrap_err();
        assert!(matches!(error, ViewError::AddressInUse { address: a, .. } if a == address.0));
        let text = error.to_string();
        assert!(text.contains(&address.to_string()), "{text}");
        assert!(text.contains("--view"), "{text}");
    }

    /// The station's side never waits: with the view's task not running at all (one thread,
    /// no await between sends), a burst far larger than the tap goes through at once, and the
    /// view counts what it lost instead of slowing anyone.
    #[tokio::test]
    async fn a_view_that_falls_behind_drops_the_oldest() {
        let tap = Tap::new(8);
        let view = ViewServer::start(ViewAddress::loopback(0), tap.subscribe())
            .await
            .unwrap();
        let burst = 1000;
        for i in 0..burst {
            let text = StringMsg {
                data: format!("message {i}"),
            };
            tap.send("/pomdar/test", &text, i, false);
        }
        let report = view.stop().await;
        assert!(report.counts.lagged >= burst as u64 - 8, "{report:?}");
        assert_eq!(report.counts.forwarded + report.counts.lagged, burst as u64);
        assert_eq!(report.topics, vec!["/pomdar/test".to_string()]);
    }

    #[tokio::test]
    async fn a_second_type_on_a_topic_is_refused() {
        let tap = Tap::new(8);
        let view = ViewServer::start(ViewAddress::loopback(0), tap.subscribe())
            .await
            .unwrap();
        tap.send("/t", &StringMsg { data: "a".into() }, 1, true);
        tap.send("/t", &msgs::Float64MultiArray::default(), 2, false);
        let report = view.stop().await;
        assert_eq!(report.counts.forwarded, 1);
        assert_eq!(report.counts.type_mismatch, 1);
    }
}
