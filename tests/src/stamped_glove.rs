//! A glove for fault injection: a keypoint publisher that sets each frame's DDS source
//! timestamp itself, so a test can send frames out of order, duplicate a sample exactly, or
//! make the sender's clock jump. ros2-client's publisher always stamps "now", so this one is
//! a RustDDS data writer on the same ROS 2 topic and type, in its own participant (as a
//! separate glove process would be). [`StampedWriter`] is the same for any message type.

use std::time::{Duration, Instant};

use msgs::{Float32MultiArray, RosMessage};
use ros2_client::dds::rustdds::no_key::DataWriterCdr;
use ros2_client::dds::rustdds::{DataWriterStatus, QosPolicies, StatusEvented as _, Timestamp};
use ros2_client::{MessageTypeName, Name};
use teleop::ros::NetworkContext as _;
use teleop::ros::QosProfileOf as _;
use teleop::ros::{NetworkConfig, QosConfig, RosNode};

/// Nanoseconds since the Unix epoch as a DDS timestamp (seconds and 2^-32 fractions).
/// Negative times are not representable on the wire: they clamp to the epoch.
pub fn dds_timestamp(unix_ns: i64) -> Timestamp {
    let ns = u64::try_from(unix_ns).unwrap_or(0);
    let seconds = ns / 1_000_000_000;
    let fraction = ((ns % 1_000_000_000) << 32) / 1_000_000_000;
    Timestamp::from_ticks((seconds << 32) | fraction)
}

/// A writer of `M` that sets each sample's DDS source timestamp, and the node that keeps its
/// participant alive.
pub struct StampedWriter<M: RosMessage> {
    writer: DataWriterCdr<M>,
    _node: RosNode,
}

impl<M: RosMessage + std::fmt::Debug> StampedWriter<M> {
    /// A writer of `M` on `topic` (absolute, e.g. `/ingress/mano`) with `qos`, in a new
    /// participant on `network`.
    pub fn new(network: &NetworkConfig, topic: &str, qos: QosConfig) -> anyhow::Result<Self> {
        let context = network.context()?;
        let node = RosNode::new(&context, "/", "stamped_glove")?;
        let (namespace, base) = topic
            .rsplit_once('/')
            .ok_or_else(|| anyhow::anyhow!("topic {topic} has no '/'"))?;
        let namespace = if namespace.is_empty() { "/" } else { namespace };
        let definition = M::DEFINITION;
        let profile = qos.profile();
        let dds_topic = node
            .node()
            .create_topic(
                &Name::new(namespace, base)?,
                MessageTypeName::new(definition.package, definition.name),
                &profile,
            )
            .map_err(|e| anyhow::anyhow!("topic {topic}: {e:?}"))?;
        let policies = QosPolicies::from(profile);
        let publisher = context
            .domain_participant()
            .create_publisher(&policies)
            .map_err(|e| anyhow::anyhow!("publisher: {e:?}"))?;
        let writer = publisher
            .create_datawriter_no_key_cdr::<M>(&dds_topic, Some(policies))
            .map_err(|e| anyhow::anyhow!("writer on {topic}: {e:?}"))?;
        Ok(StampedWriter {
            writer,
            _node: node,
        })
    }

    /// Wait until at least one reader matched, at most `timeout` (from the
    /// writer's publication-matched status events).
    pub async fn wait_for_reader(&self, timeout: Duration) -> anyhow::Result<()> {
        let start = Instant::now();
        let mut matched = 0;
        loop {
            while let Some(status) = self.writer.try_recv_status() {
                if let DataWriterStatus::PublicationMatched { current, .. } = status {
                    matched = current.count();
                }
            }
            if matched > 0 {
                return Ok(());
            }
            anyhow::ensure!(
                start.elapsed() < timeout,
                "no reader matched the stamped writer within {timeout:?}"
            );
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
    }

    /// Publish `message` with the DDS source timestamp `source_ns` (ns since the epoch).
    pub async fn write(&self, message: M, source_ns: i64) -> anyhow::Result<()> {
        self.writer
            .async_write(message, Some(dds_timestamp(source_ns)))
            .await
            .map_err(|e| anyhow::anyhow!("write: {e:?}"))
    }
}

/// The keypoint writer of a glove whose stamps the test chooses.
pub struct StampedGlove(StampedWriter<Float32MultiArray>);

impl StampedGlove {
    /// A writer of `std_msgs/Float32MultiArray` on `topic` (e.g. `/ingress/mano`) with `qos`,
    /// in a new participant on `network`.
    pub fn new(network: &NetworkConfig, topic: &str, qos: QosConfig) -> anyhow::Result<Self> {
        Ok(StampedGlove(StampedWriter::new(network, topic, qos)?))
    }

    /// Wait until at least one reader (the station) matched, at most `timeout`.
    pub async fn wait_for_reader(&self, timeout: Duration) -> anyhow::Result<()> {
        self.0.wait_for_reader(timeout).await
    }

    /// Publish keypoint rows with the DDS source timestamp `source_ns` (ns since the epoch).
    pub async fn publish(&self, rows: &[[f32; 3]], source_ns: i64) -> anyhow::Result<()> {
        self.0
            .write(Float32MultiArray::from_points(rows)?, source_ns)
            .await
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timestamps_keep_nanoseconds_to_the_fraction_resolution() {
        let ns: i64 = 1_732_100_000_123_456_789;
        let t = dds_timestamp(ns).to_ticks();
        let back =
            (t >> 32) as i64 * 1_000_000_000 + (((t & 0xffff_ffff) * 1_000_000_000) >> 32) as i64;
        assert!((back - ns).abs() <= 1, "{back} vs {ns}");
        assert_eq!(dds_timestamp(-5).to_ticks(), 0);
    }
}
