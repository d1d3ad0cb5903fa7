//! Typed publishers and subscriptions for the `msgs` types on one ROS 2 node.
//!
//! Topic types come from [`msgs::RosMessage`] (ROS 2 naming on the wire: topic `rt/<name>`,
//! type `pkg::msg::dds_::Type_`), so peers such as Cyclone DDS or rclpy match by type name.

use futures::FutureExt as _;
use msgs::RosMessage;
use ros2_client::dds::rustdds::Topic;
use ros2_client::qos::Durability;
use ros2_client::{
    Client, Context, MessageTypeName, Name, Node, NodeName, NodeOptions, Publisher, QosProfile,
    Server, ServiceMapping, ServiceTypeName, Subscription,
};
use serde::{Deserialize, Serialize};

use crate::ros::teardown::{SpinnerTask, TeardownScope};
use crate::ros::{NetworkConfig, NetworkContext as _, QosConfig, QosProfileOf as _, RosError};

/// A `std_srvs/srv/Trigger` request as ros2-client carries it (its `Message` marker on the
/// `msgs` type, which knows nothing of ros2-client).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(transparent)]
pub struct TriggerRequest(pub msgs::TriggerRequest);

impl ros2_client::Message for TriggerRequest {}

/// A `std_srvs/srv/Trigger` response as ros2-client carries it.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(transparent)]
pub struct TriggerResponse(pub msgs::TriggerResponse);

impl ros2_client::Message for TriggerResponse {}

/// A message with the times the station knows about it.
#[derive(Debug, Clone, PartialEq)]
pub struct Stamped<M> {
    /// The message.
    pub message: M,
    /// When the station received it, nanoseconds on the station's clock.
    pub received_ns: i64,
    /// When the sender published it (DDS source timestamp), nanoseconds since the epoch.
    pub source_ns: Option<i64>,
}

/// A ROS 2 node with typed endpoint helpers. The spinner runs on the tokio runtime.
///
/// Shutdown order (`ros::teardown`): drop the endpoints made from a node before the node; the
/// node holds its context, and its spinner task holds a clone until the spinner's own
/// endpoints are gone, so the DDS participant is always the last to go.
pub struct RosNode {
    node: Node,
    context: Context,
    /// Dropped last: spans the drops of the node and the context (possibly the participant's
    /// last handle), entered by `Drop for RosNode`.
    teardown: TeardownScope,
}

impl Drop for RosNode {
    fn drop(&mut self) {
        self.teardown.enter();
    }
}

impl std::fmt::Debug for RosNode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RosNode").finish_non_exhaustive()
    }
}

fn topic_name(name: &str) -> Result<Name, RosError> {
    let trimmed = name.trim_start_matches('/');
    let (namespace, base) = match trimmed.rsplit_once('/') {
        Some((ns, base)) => (format!("/{ns}"), base),
        None => ("/".to_string(), trimmed),
    };
    Name::new(&namespace, base).map_err(|source| RosError::TopicName {
        topic: name.to_string(),
        source,
    })
}

impl RosNode {
    /// Join the DDS domain `network` describes with a participant of its own, and create node
    /// `name` in `namespace` on it (see [`RosNode::new`]). The node owns the participant: it
    /// goes when the node and its spinner are gone.
    pub fn join(network: &NetworkConfig, namespace: &str, name: &str) -> Result<RosNode, RosError> {
        RosNode::new(&network.context()?, namespace, name)
    }

    /// Create node `name` in `namespace` and spawn its spinner on the current tokio runtime.
    pub fn new(context: &Context, namespace: &str, name: &str) -> Result<RosNode, RosError> {
        let node_name = NodeName::new(namespace, name).map_err(|source| RosError::NodeName {
            namespace: namespace.to_string(),
            name: name.to_string(),
            source,
        })?;
        let mut node = context
            .new_node(node_name, NodeOptions::new().enable_rosout(false))
            .map_err(|source| RosError::Node { source })?;
        let spinner = node
            .spinner()
            .map_err(|source| RosError::Spinner { source })?;
        tokio::spawn(SpinnerTask::new(spinner.spin(), context.clone()));
        Ok(RosNode {
            node,
            context: context.clone(),
            teardown: TeardownScope::default(),
        })
    }

    /// The ROS 2 context (participant) of this node.
    pub fn context(&self) -> &Context {
        &self.context
    }

    /// The underlying ros2-client node (graph queries).
    pub fn node(&self) -> &Node {
        &self.node
    }

    /// How many subscriptions `publisher` (made by this node) is matched with.
    ///
    /// ros2-client's `Publisher::get_subscription_count` logs an ERROR for a publisher it has
    /// no match record of, which is every publisher before its first match: asked first,
    /// the match future says without logging whether there is one.
    pub fn matched_subscriptions<M: Serialize>(&self, publisher: &Publisher<M>) -> usize {
        match publisher.wait_for_subscription(&self.node).now_or_never() {
            Some(()) => publisher.get_subscription_count(&self.node),
            None => 0,
        }
    }

    /// How many publishers `subscription` (made by this node) is matched with (as
    /// [`RosNode::matched_subscriptions`], without ros2-client's ERROR before a first match).
    pub fn matched_publishers<M: 'static>(&self, subscription: &Subscription<M>) -> usize {
        match subscription.wait_for_publisher(&self.node).now_or_never() {
            Some(()) => subscription.get_publisher_count(&self.node),
            None => 0,
        }
    }

    /// The DDS topic of `M` named `topic`, with its QoS profile.
    fn topic<M: RosMessage>(
        &self,
        topic: &str,
        qos: QosConfig,
    ) -> Result<(Topic, QosProfile), RosError> {
        let profile = qos.profile();
        let definition = M::DEFINITION;
        let handle = self
            .node
            .create_topic(
                &topic_name(topic)?,
                MessageTypeName::new(definition.package, definition.name),
                &profile,
            )
            .map_err(|source| RosError::Topic {
                topic: topic.to_string(),
                source,
            })?;
        Ok((handle, profile))
    }

    /// A reliable, transient-local publisher of `M` on `topic` keeping its last `depth`
    /// messages for late subscribers (`/tf_static`, `/robot_description`: ROS's latched
    /// topics).
    pub fn latched_publisher<M: RosMessage>(
        &mut self,
        topic: &str,
        depth: u32,
    ) -> Result<Publisher<M>, RosError> {
        let (handle, profile) = self.topic::<M>(topic, QosConfig::reliable(depth))?;
        let profile = profile.durability(Durability::TransientLocal);
        self.node
            .create_publisher(&handle, Some(profile))
            .map_err(|source| RosError::Publisher {
                topic: topic.to_string(),
                source,
            })
    }

    /// A `std_srvs/srv/Trigger` server named `service` (topics `rq/<service>Request` and
    /// `rr/<service>Reply`), carried as `mapping` says (the clients' RMW).
    pub fn trigger_server(
        &mut self,
        service: &str,
        mapping: ServiceMapping,
    ) -> Result<Server<TriggerRequest, TriggerResponse>, RosError> {
        let profile = QosConfig::reliable(10).profile();
        self.node
            .create_server(
                mapping,
                &topic_name(service)?,
                &ServiceTypeName::new("std_srvs", "Trigger"),
                profile.clone(),
                profile,
            )
            .map_err(|source| RosError::Service {
                service: service.to_string(),
                source,
            })
    }

    /// A `std_srvs/srv/Trigger` client of `service`, carried as `mapping` says (the server's
    /// side of [`RosNode::trigger_server`]).
    pub fn trigger_client(
        &mut self,
        service: &str,
        mapping: ServiceMapping,
    ) -> Result<Client<TriggerRequest, TriggerResponse>, RosError> {
        let profile = QosConfig::reliable(10).profile();
        self.node
            .create_client(
                mapping,
                &topic_name(service)?,
                &ServiceTypeName::new("std_srvs", "Trigger"),
                profile.clone(),
                profile,
            )
            .map_err(|source| RosError::Service {
                service: service.to_string(),
                source,
            })
    }

    /// A publisher of `M` on `topic`.
    pub fn publisher<M: RosMessage>(
        &mut self,
        topic: &str,
        qos: QosConfig,
    ) -> Result<Publisher<M>, RosError> {
        let (handle, profile) = self.topic::<M>(topic, qos)?;
        self.node
            .create_publisher(&handle, Some(profile))
            .map_err(|source| RosError::Publisher {
                topic: topic.to_string(),
                source,
            })
    }

    /// A subscription to `M` on `topic`.
    pub fn subscription<M: RosMessage + 'static>(
        &mut self,
        topic: &str,
        qos: QosConfig,
    ) -> Result<Subscription<M>, RosError> {
        let (handle, profile) = self.topic::<M>(topic, qos)?;
        self.node
            .create_subscription(&handle, Some(profile))
            .map_err(|source| RosError::Subscription {
                topic: topic.to_string(),
                source,
            })
    }

    /// A reliable, transient-local subscription to `M` on `topic` that also receives what a
    /// [`RosNode::latched_publisher`] sent before it joined (the last `depth` messages).
    pub fn latched_subscription<M: RosMessage + 'static>(
        &mut self,
        topic: &str,
        depth: u32,
    ) -> Result<Subscription<M>, RosError> {
        let (handle, profile) = self.topic::<M>(topic, QosConfig::reliable(depth))?;
        let profile = profile.durability(Durability::TransientLocal);
        self.node
            .create_subscription(&handle, Some(profile))
            .map_err(|source| RosError::Subscription {
                topic: topic.to_string(),
                source,
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn topic_names_split_into_namespace_and_base() {
        assert_eq!(
            topic_name("/ingress/mano").unwrap().to_string(),
            "/ingress/mano"
        );
        assert_eq!(
            topic_name("/target_pose").unwrap().to_string(),
            "/target_pose"
        );
        assert_eq!(
            topic_name("/fr3/arm/end_effector_pose_cmd")
                .unwrap()
                .to_string(),
            "/fr3/arm/end_effector_pose_cmd"
        );
        let err = topic_name("/bad name").unwrap_err().to_string();
        assert!(
            err.starts_with("'/bad name' is not a valid ROS 2 topic name: "),
            "{err}"
        );
    }
}
