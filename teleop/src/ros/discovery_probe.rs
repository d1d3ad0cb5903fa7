//! `pomdar probe`: what this host's DDS participant discovers and hears, to check a
//! multi-host deployment without a ROS installation (the `ros2 topic list` / `ros2 topic hz`
//! of the station's own stack).
//!
//! The probe joins the domain on the configured interfaces, waits until a publisher of each
//! requested topic is discovered (SPDP then SEDP), subscribes to it with the type the
//! publisher announced, and counts samples for the given time. It reports every publisher it
//! discovered with the unicast addresses it announced (which host it runs on), and per topic
//! the time to discovery, the samples received and their rate over the receive window, how old
//! the stamped samples were on arrival and when the topic went silent (`ros::probe_timing`).

use std::collections::BTreeSet;
use std::net::SocketAddr;
use std::time::{Duration, Instant};

use futures::StreamExt;
use msgs::{Float32MultiArray, JointState, PoseArray, PoseStamped, RosMessage, StringMsg};
use ros2_client::MessageTypeName;
use serde::Serialize;
use tokio::sync::watch;
use tokio::task::JoinHandle;

use crate::clock::StationClock;
use crate::ros::probe_timing::{Arrival, HeaderStamp, TopicTiming};
use crate::ros::{NetworkConfig, QosConfig, RosError, RosNode};

/// What to probe.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbeOptions {
    /// ROS topic names to listen to (`/pomdar/hand/joint_targets`).
    pub topics: Vec<String>,
    /// How long to count samples once a topic's publisher is discovered.
    pub duration: Duration,
    /// How long to wait for a publisher of each topic.
    pub discovery_timeout: Duration,
    /// Subscribe reliably, as a robot driver does (a reliable publisher then resends what was
    /// lost); otherwise best effort, which matches any publisher.
    pub reliable: bool,
    /// Stamped samples older than this on arrival are counted, milliseconds.
    pub age_limit_ms: u64,
}

/// A publisher the probe discovered.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Serialize)]
pub struct DiscoveredPublisher {
    /// ROS topic name (`/pomdar/hand/joint_targets`).
    pub topic: String,
    /// DDS type name (`sensor_msgs::msg::dds_::JointState_`).
    pub type_name: String,
    /// The unicast addresses the publisher announced (where its host is reachable).
    pub addresses: Vec<SocketAddr>,
}

/// One requested topic.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TopicProbe {
    /// ROS topic name.
    pub topic: String,
    /// The publisher's DDS type name; `None` when no publisher was discovered.
    pub type_name: Option<String>,
    /// Seconds from the probe's start until a publisher was discovered.
    pub discovered_after_s: Option<f64>,
    /// Samples received.
    pub samples: u64,
    /// Seconds from the first to the last sample.
    pub window_s: f64,
    /// Samples per second over the window (`samples − 1` intervals); `None` below 2 samples.
    pub rate_hz: Option<f64>,
    /// Ages on arrival and silences; None without samples.
    pub timing: Option<TopicTiming>,
    /// Why the topic could not be counted (no publisher, a type the probe cannot decode).
    pub problem: Option<String>,
}

/// What the probe found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProbeReport {
    /// The DDS domain probed.
    pub domain_id: u16,
    /// Every publisher of a ROS topic discovered, by topic.
    pub publishers: Vec<DiscoveredPublisher>,
    /// The requested topics, in the order asked.
    pub topics: Vec<TopicProbe>,
}

impl ProbeReport {
    /// Whether every requested topic was discovered and heard at least once.
    pub fn all_heard(&self) -> bool {
        self.topics.iter().all(|t| t.samples > 0)
    }
}

/// The DDS type name of `M` (`pkg::msg::dds_::Type_`).
fn dds_type<M: RosMessage>() -> String {
    MessageTypeName::new(M::DEFINITION.package, M::DEFINITION.name).dds_msg_type()
}

/// The ROS name of a DDS topic (`rt/ingress/mano` → `/ingress/mano`).
fn ros_topic(dds_topic: &str) -> String {
    match dds_topic.strip_prefix("rt/") {
        Some(rest) => format!("/{rest}"),
        None => dds_topic.to_string(),
    }
}

/// Every publisher of a ROS topic the participant knows (DDS topics `rt/...`; services and
/// DDS-internal topics are left out), sorted.
fn discovered_publishers(node: &RosNode) -> Vec<DiscoveredPublisher> {
    let mut out: BTreeSet<DiscoveredPublisher> = BTreeSet::new();
    for writer in node.context().domain_participant().discovered_writers() {
        let data = &writer.publication_topic_data;
        if !data.topic_name.starts_with("rt/") {
            continue;
        }
        let addresses = writer
            .writer_proxy
            .unicast_locator_list
            .iter()
            .filter(|l| l.is_udp())
            .map(|l| SocketAddr::from(*l))
            .collect::<BTreeSet<_>>()
            .into_iter()
            .collect();
        out.insert(DiscoveredPublisher {
            topic: ros_topic(&data.topic_name),
            type_name: data.type_name.clone(),
            addresses,
        });
    }
    out.into_iter().collect()
}

/// How a counter subscribes and times.
#[derive(Debug, Clone, Copy)]
struct CounterSettings {
    duration: Duration,
    qos: QosConfig,
    clock: StationClock,
}

/// Count samples of `M` on `topic` for the settings' duration; returns their arrivals.
fn spawn_counter<M: RosMessage + HeaderStamp + Send + Sync + 'static>(
    node: &mut RosNode,
    topic: &str,
    settings: CounterSettings,
    mut shutdown: watch::Receiver<bool>,
) -> Result<JoinHandle<Vec<Arrival>>, RosError> {
    let subscription = node.subscription::<M>(topic, settings.qos)?;
    let CounterSettings {
        duration, clock, ..
    } = settings;
    Ok(tokio::spawn(async move {
        let mut stream = Box::pin(subscription.async_stream());
        let deadline = tokio::time::sleep(duration);
        tokio::pin!(deadline);
        let mut times = Vec::new();
        loop {
            tokio::select! {
                _ = &mut deadline => break,
                _ = shutdown.changed() => if *shutdown.borrow() { break },
                item = stream.next() => match item {
                    Some(Ok((message, _))) => times.push(Arrival {
                        received_ns: clock.now_ns(),
                        stamp_ns: message.header_stamp_ns(),
                    }),
                    Some(Err(_)) => {}
                    None => break,
                },
            }
        }
        times
    }))
}

/// Subscribe to `topic` as the type its publisher announced.
fn counter_for(
    node: &mut RosNode,
    topic: &str,
    type_name: &str,
    settings: CounterSettings,
    shutdown: &watch::Receiver<bool>,
) -> Result<Option<JoinHandle<Vec<Arrival>>>, RosError> {
    let shutdown = shutdown.clone();
    let handle = if type_name == dds_type::<JointState>() {
        spawn_counter::<JointState>(node, topic, settings, shutdown)?
    } else if type_name == dds_type::<PoseStamped>() {
        spawn_counter::<PoseStamped>(node, topic, settings, shutdown)?
    } else if type_name == dds_type::<Float32MultiArray>() {
        spawn_counter::<Float32MultiArray>(node, topic, settings, shutdown)?
    } else if type_name == dds_type::<PoseArray>() {
        spawn_counter::<PoseArray>(node, topic, settings, shutdown)?
    } else if type_name == dds_type::<StringMsg>() {
        spawn_counter::<StringMsg>(node, topic, settings, shutdown)?
    } else {
        return Ok(None);
    };
    Ok(Some(handle))
}

/// Run the probe until every topic has been counted for `duration` (or was not discovered
/// within `discovery_timeout`), or until `shutdown`.
pub async fn probe(
    network: &NetworkConfig,
    options: &ProbeOptions,
    shutdown: watch::Receiver<bool>,
) -> Result<ProbeReport, RosError> {
    let domain_id = crate::ros::domain_id(network.domain_id)?;
    let mut node = RosNode::join(network, "/", "pomdar_probe")?;
    let settings = CounterSettings {
        duration: options.duration,
        // Best effort matches reliable and best-effort publishers alike.
        qos: match options.reliable {
            true => QosConfig::reliable(1000),
            false => QosConfig::best_effort(1000),
        },
        clock: StationClock::new(),
    };
    let start = Instant::now();
    let mut topics: Vec<TopicProbe> = options
        .topics
        .iter()
        .map(|topic| TopicProbe {
            topic: topic.clone(),
            type_name: None,
            discovered_after_s: None,
            samples: 0,
            window_s: 0.0,
            rate_hz: None,
            timing: None,
            problem: None,
        })
        .collect();
    let mut counters: Vec<Option<JoinHandle<Vec<Arrival>>>> = topics.iter().map(|_| None).collect();
    loop {
        let publishers = discovered_publishers(&node);
        for (probe, counter) in topics.iter_mut().zip(counters.iter_mut()) {
            if probe.type_name.is_some() {
                continue;
            }
            let Some(publisher) = publishers.iter().find(|p| p.topic == probe.topic) else {
                continue;
            };
            probe.type_name = Some(publisher.type_name.clone());
            probe.discovered_after_s = Some(start.elapsed().as_secs_f64());
            *counter = counter_for(
                &mut node,
                &probe.topic,
                &publisher.type_name,
                settings,
                &shutdown,
            )?;
            if counter.is_none() {
                probe.problem = Some(format!(
                    "type {} is not one the probe decodes",
                    publisher.type_name
                ));
            }
        }
        let waiting = topics.iter().any(|t| t.type_name.is_none());
        if !waiting || start.elapsed() >= options.discovery_timeout || *shutdown.borrow() {
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    for (probe, counter) in topics.iter_mut().zip(counters) {
        if probe.type_name.is_none() {
            probe.problem = Some(format!(
                "no publisher discovered within {:.0} s",
                options.discovery_timeout.as_secs_f64()
            ));
        }
        let Some(counter) = counter else { continue };
        let times = counter.await?;
        probe.samples = times.len() as u64;
        if let (Some(first), Some(last)) = (times.first(), times.last()) {
            probe.window_s = (last.received_ns - first.received_ns) as f64 * 1e-9;
            probe.timing = Some(TopicTiming::of(&times, options.age_limit_ms));
            if times.len() >= 2 && probe.window_s > 0.0 {
                probe.rate_hz = Some((times.len() - 1) as f64 / probe.window_s);
            }
        }
        if probe.samples == 0 && probe.problem.is_none() {
            probe.problem = Some(
                "publisher discovered but no sample received (QoS mismatch, or data blocked between the hosts)"
                    .to_string(),
            );
        }
    }
    Ok(ProbeReport {
        domain_id,
        publishers: discovered_publishers(&node),
        topics,
    })
}

impl std::fmt::Display for ProbeReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "domain {}: publishers discovered", self.domain_id)?;
        for p in &self.publishers {
            let addresses: Vec<String> = p.addresses.iter().map(ToString::to_string).collect();
            writeln!(
                f,
                "  {:<36} {:<44} {}",
                p.topic,
                p.type_name,
                addresses.join(" ")
            )?;
        }
        writeln!(f, "topics")?;
        for t in &self.topics {
            match (&t.problem, t.rate_hz) {
                (Some(problem), _) => writeln!(f, "  {:<36} {problem}", t.topic)?,
                (None, Some(rate)) => writeln!(
                    f,
                    "  {:<36} {:.1} Hz ({} samples over {:.1} s; discovered after {:.1} s)",
                    t.topic,
                    rate,
                    t.samples,
                    t.window_s,
                    t.discovered_after_s.unwrap_or(0.0)
                )?,
                (None, None) => writeln!(f, "  {:<36} {} samples", t.topic, t.samples)?,
            }
            if let Some(timing) = &t.timing {
                write_timing(f, timing)?;
            }
        }
        Ok(())
    }
}

/// A topic's ages and longest silence, under its rate line.
fn write_timing(f: &mut std::fmt::Formatter<'_>, timing: &TopicTiming) -> std::fmt::Result {
    let mut parts = Vec::new();
    if let (Some(p50), Some(max)) = (timing.age_p50_ms, timing.age_max_ms) {
        parts.push(format!(
            "age on arrival p50 {p50:.1} ms, max {max:.1} ms, {} older than {} ms",
            timing.older_than_limit, timing.age_limit_ms
        ));
    }
    if let Some(silence) = timing.longest_silence() {
        parts.push(format!(
            "longest silence {:.2} s ({} silences)",
            silence.seconds,
            timing.silences.len()
        ));
    }
    match parts.is_empty() {
        true => Ok(()),
        false => writeln!(f, "  {:<36} {}", "", parts.join("; ")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ros_names_come_back_from_dds_names() {
        assert_eq!(ros_topic("rt/ingress/mano"), "/ingress/mano");
        assert_eq!(ros_topic("ros_discovery_info"), "ros_discovery_info");
    }

    #[test]
    fn dds_type_names_follow_ros2_naming() {
        assert_eq!(
            dds_type::<JointState>(),
            "sensor_msgs::msg::dds_::JointState_"
        );
        assert_eq!(dds_type::<StringMsg>(), "std_msgs::msg::dds_::String_");
    }
}
