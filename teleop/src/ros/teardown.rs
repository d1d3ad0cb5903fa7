//! Taking a DDS participant down in order, and the one RustDDS record that teardown logs
//! although nothing is wrong.
//!
//! RustDDS removes an endpoint by sending its GUID to the participant's event loop; an
//! endpoint dropped after the participant's last handle logs `ERROR rustdds::dds::pubsub]
//! Cannot remove Writer/Reader … TrySendError::Disconnected` (`InnerPublisher::remove_writer`,
//! `InnerSubscriber::remove_reader`). The participant lives as long as the last
//! `ros2_client::Context` clone, so the order is: endpoints, then the node, then the context.
//! [`RosNode`](crate::ros::RosNode) keeps it for what it owns: its spinner task (ros2-client's
//! parameter services and parameter-event writer) drops its endpoints while the task still
//! holds a context clone (its `SpinnerTask`); the endpoints a caller creates must be dropped
//! before the node (declare the node first in a function, last in a struct).
//!
//! One record no order avoids: a participant restricted to some interfaces
//! (`with_only_networks`, `--interface`) joins SPDP multicast on each of those interfaces, but
//! `impl Drop for UDPListener` (rustdds `network/udp_listener.rs`) leaves the group with
//! `leave_multicast_v4(group, 0.0.0.0)`, which the kernel resolves to the default route's
//! interface: no such membership, `EADDRNOTAVAIL`, logged as `ERROR
//! rustdds::network::udp_listener] leave_multicast_group: …`. Benign: the socket closes on
//! the next line of that drop, and closing a socket drops all its memberships. The logger
//! leaves out exactly that record, and only while this process is taking a participant down
//! ([`tearing_down`]).

use std::future::Future;
use std::pin::Pin;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::task::{Context as TaskContext, Poll};

use ros2_client::Context;

/// How many participant teardowns are in progress (any thread).
static TEARDOWNS: AtomicUsize = AtomicUsize::new(0);

/// Whether some thread of this process is dropping a participant handle now (the last one
/// tears the participant down: its event loop stops and its sockets close).
pub fn tearing_down() -> bool {
    TEARDOWNS.load(Ordering::SeqCst) > 0
}

/// The RustDDS target and message prefix of the benign teardown record (see the module docs).
const MULTICAST_LEAVE_TARGET: &str = "rustdds::network::udp_listener";
const MULTICAST_LEAVE_PREFIX: &str = "leave_multicast_group: ";

/// Whether a log record is RustDDS's benign `leave_multicast_group` error of a participant
/// teardown: that exact target and message, logged while `tearing_down`. Everything else,
/// and that record at any other time, is shown.
pub fn is_benign_teardown_record(
    level: log::Level,
    target: &str,
    message: &str,
    tearing_down: bool,
) -> bool {
    tearing_down
        && level == log::Level::Error
        && target == MULTICAST_LEAVE_TARGET
        && message.starts_with(MULTICAST_LEAVE_PREFIX)
}

/// Marks a participant teardown in progress from [`TeardownScope::enter`] until it is dropped.
/// As the last field of a struct whose `Drop` calls `enter`, it spans the drops of the fields
/// before it.
#[derive(Debug, Default)]
pub(crate) struct TeardownScope {
    entered: bool,
}

impl TeardownScope {
    /// Mark the teardown as begun (once).
    pub(crate) fn enter(&mut self) {
        if !self.entered {
            self.entered = true;
            TEARDOWNS.fetch_add(1, Ordering::SeqCst);
        }
    }
}

impl Drop for TeardownScope {
    fn drop(&mut self) {
        if self.entered {
            TEARDOWNS.fetch_sub(1, Ordering::SeqCst);
        }
    }
}

/// Drop `context` inside a teardown scope (it may be the participant's last handle).
pub(crate) fn release_context(context: Context) {
    let mut scope = TeardownScope::default();
    scope.enter();
    drop(context);
    drop(scope);
}

/// ros2-client's spinner future with a context clone that outlives it: when the spinner ends
/// (its node was dropped) or the task is dropped (the runtime shut down), the spinner and its
/// endpoints go first, the context after, so the participant is never gone before them.
pub(crate) struct SpinnerTask<F> {
    spin: Option<Pin<Box<F>>>,
    context: Option<Context>,
}

impl<F> SpinnerTask<F> {
    /// `spin` (the spinner's `spin()` future) holding `context` alive until it is gone.
    pub(crate) fn new(spin: F, context: Context) -> SpinnerTask<F> {
        SpinnerTask {
            spin: Some(Box::pin(spin)),
            context: Some(context),
        }
    }

    fn finish(&mut self) {
        self.spin = None;
        if let Some(context) = self.context.take() {
            release_context(context);
        }
    }
}

impl<F: Future> Future for SpinnerTask<F> {
    type Output = F::Output;

    fn poll(mut self: Pin<&mut Self>, cx: &mut TaskContext<'_>) -> Poll<F::Output> {
        // `SpinnerTask` is `Unpin` (its future is boxed), so the pin gives `&mut Self`.
        let this = &mut *self;
        let Some(spin) = this.spin.as_mut() else {
            return Poll::Pending;
        };
        let output = std::task::ready!(spin.as_mut().poll(cx));
        this.finish();
        Poll::Ready(output)
    }
}

impl<F> Drop for SpinnerTask<F> {
    fn drop(&mut self) {
        self.finish();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LEAVE: &str = "leave_multicast_group: Os { code: 99, kind: AddrNotAvailable, message: \"Cannot assign requested address\" }";

    #[test]
    fn only_the_multicast_leave_error_during_a_teardown_is_benign() {
        let target = "rustdds::network::udp_listener";
        assert!(is_benign_teardown_record(
            log::Level::Error,
            target,
            LEAVE,
            true
        ));
        // Not during a teardown: shown.
        assert!(!is_benign_teardown_record(
            log::Level::Error,
            target,
            LEAVE,
            false
        ));
        // Another RustDDS error of the same module, or of teardown: shown.
        assert!(!is_benign_teardown_record(
            log::Level::Error,
            target,
            "join_multicast_v4 failed",
            true
        ));
        assert!(!is_benign_teardown_record(
            log::Level::Error,
            "rustdds::dds::pubsub",
            "Cannot remove Writer GUID {..} : TrySendError::Disconnected(..)",
            true
        ));
        // Our own records never match.
        assert!(!is_benign_teardown_record(
            log::Level::Error,
            "teleop::ros",
            LEAVE,
            true
        ));
        assert!(!is_benign_teardown_record(
            log::Level::Warn,
            target,
            LEAVE,
            true
        ));
    }

    #[test]
    fn a_teardown_scope_marks_a_teardown_until_dropped() {
        let mut scope = TeardownScope::default();
        scope.enter();
        scope.enter();
        assert!(tearing_down());
        drop(scope);
    }
}
