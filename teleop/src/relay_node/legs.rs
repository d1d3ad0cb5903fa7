//! One relayed topic: its subscription on the relay topic, its publisher on the robot's, the
//! age gate between them, and the relay's lines about what it dropped or could not publish
//! (each kind at most once per [`WARNING_PERIOD_NS`] per topic).

use std::sync::Mutex;

use futures::StreamExt as _;
use msgs::RosMessage;
use ros2_client::{Publisher, Subscription};
use station::link_clock::ClockOffsetMonitor;
use station::robot_link::{AgeCounts, AgeVerdict, CommandAgeGate, CommandTimes};
use tokio::sync::watch;

use super::{RelayReport, RelayRoute, RelaySettings};
use crate::clock::WallClock;
use crate::ingress::log_limit::LogLimiter;
use crate::ros::probe_timing::HeaderStamp;
use crate::ros::{RosError, RosNode};

/// How often at most the relay says it dropped commands, or could not publish them, per
/// topic, nanoseconds.
pub const WARNING_PERIOD_NS: i64 = 5_000_000_000;

/// One topic's subscription and publisher.
pub struct Leg<M: RosMessage + 'static> {
    pub route: RelayRoute,
    pub subscription: Subscription<M>,
    pub publisher: Publisher<M>,
}

/// The leg of `route`, if the configuration has it.
pub fn open_leg<M: RosMessage + 'static>(
    node: &mut RosNode,
    route: Option<&RelayRoute>,
    settings: &RelaySettings,
) -> Result<Option<Leg<M>>, RosError> {
    let Some(route) = route else { return Ok(None) };
    Ok(Some(Leg {
        route: route.clone(),
        subscription: node.subscription(&route.from, settings.link_qos)?,
        publisher: node.publisher(&route.to, settings.robot_qos)?,
    }))
}

/// What every leg shares.
pub struct LegContext<'a> {
    pub max_age_ms: u64,
    pub clock: WallClock,
    pub report: &'a Mutex<RelayReport>,
    /// One estimate of the clock offset from every topic's commands (one station sends them).
    pub offset: Mutex<ClockOffsetMonitor>,
}

impl LegContext<'_> {
    /// A stamped command's age into the offset estimate; its news said.
    fn observe_age(&self, age_ns: i64, now_ns: i64) {
        let Ok(mut monitor) = self.offset.lock() else {
            return;
        };
        if let Some(news) = monitor.observe(age_ns, now_ns) {
            eprintln!("relay: warning: {news}");
        }
        if let Ok(mut report) = self.report.lock() {
            report.clock_offset_ms = monitor.estimate_ns().map(|ns| ns as f64 * 1e-6);
        }
    }
}

/// A leg's lines to the operator: drops and publish failures since the last line of each.
struct LegWarnings {
    limiter: LogLimiter,
    counts_at_last: AgeCounts,
    failed_at_last: u64,
}

impl LegWarnings {
    fn new() -> LegWarnings {
        LegWarnings {
            limiter: LogLimiter::new(WARNING_PERIOD_NS),
            counts_at_last: AgeCounts::default(),
            failed_at_last: 0,
        }
    }

    fn drops(&mut self, topic: &str, counts: &AgeCounts, max_age_ms: u64, now_ns: i64) {
        if self.limiter.allow("dropped", now_ns).is_none() {
            return;
        }
        let old = counts.too_old - self.counts_at_last.too_old;
        let late_input = counts.too_old_by_stamp - self.counts_at_last.too_old_by_stamp;
        let ahead = counts.from_the_future - self.counts_at_last.from_the_future;
        let unstamped = counts.unstamped - self.counts_at_last.unstamped;
        let mut parts = Vec::new();
        if old > 0 {
            parts.push(format!(
                "{old} older than {max_age_ms} ms (the oldest dropped so far {:.0} ms; {late_input} of them by their stamp only: the glove input was late, not the link)",
                counts.oldest_dropped_ns as f64 * 1e-6
            ));
        }
        if ahead > 0 {
            parts.push(format!(
                "{ahead} sent or stamped more than {max_age_ms} ms ahead of this computer's clock (keep the lab's clocks in step, e.g. chrony: a hand command's stamp is its glove frame's time)"
            ));
        }
        if unstamped > 0 {
            parts.push(format!("{unstamped} with neither a send time nor a stamp"));
        }
        eprintln!("relay: {topic}: dropped {}", parts.join(", "));
        self.counts_at_last = counts.clone();
    }

    fn publish_failures(&mut self, topic: &str, failed: u64, now_ns: i64) {
        if self.limiter.allow("publish", now_ns).is_none() {
            return;
        }
        eprintln!(
            "relay: warning: {topic}: {} commands could not be published to the robot's topic ({failed} so far); the robot's drivers may miss them",
            failed - self.failed_at_last
        );
        self.failed_at_last = failed;
    }
}

/// Relay one topic until `shutdown` or its subscription ends.
pub async fn relay_leg<M: RosMessage + HeaderStamp + 'static>(
    leg: Option<&Leg<M>>,
    context: &LegContext<'_>,
    mut shutdown: watch::Receiver<bool>,
) {
    let Some(leg) = leg else { return };
    let topic = leg.route.to.as_str();
    let mut gate = CommandAgeGate::new(context.max_age_ms);
    let mut warnings = LegWarnings::new();
    let mut stream = Box::pin(leg.subscription.async_stream());
    loop {
        let received = tokio::select! {
            _ = shutdown.changed() => if *shutdown.borrow() { break } else { continue },
            next = stream.next() => match next { Some(received) => received, None => break },
        };
        let now = context.clock.now_ns();
        let (verdict, failed) = match received {
            Ok((message, info)) => {
                let sent = info.source_timestamp().map(|t| t.to_nanos());
                if let Some(sent) = sent {
                    context.observe_age(now.saturating_sub(sent), now);
                }
                let times = CommandTimes::new(sent, message.header_stamp_ns());
                let verdict = gate.judge(times, now);
                let failed =
                    verdict.forwards() && leg.publisher.async_publish(message).await.is_err();
                (Some(verdict), failed)
            }
            Err(_) => (None, false),
        };
        let Ok(mut report) = context.report.lock() else {
            break;
        };
        let entry = report.topics.entry(topic.to_string()).or_default();
        entry.ages = gate.counts().clone();
        entry.input_errors += u64::from(verdict.is_none());
        entry.publish_failed += u64::from(failed);
        let publish_failed = entry.publish_failed;
        drop(report);
        if verdict.is_some_and(|v| !matches!(v, AgeVerdict::Forward)) {
            warnings.drops(topic, gate.counts(), context.max_age_ms, now);
        }
        if failed {
            warnings.publish_failures(topic, publish_failed, now);
        }
    }
}
