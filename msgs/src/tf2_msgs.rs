//! `tf2_msgs`: the `/tf` and `/tf_static` message.

use serde::{Deserialize, Serialize};

use crate::geometry_msgs::TransformStamped;
use crate::{MsgDefinition, RosMessage};

/// `tf2_msgs/msg/TFMessage`: edges of the transform tree.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct TFMessage {
    /// Parent → child transforms.
    pub transforms: Vec<TransformStamped>,
}

impl RosMessage for TFMessage {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "tf2_msgs",
        name: "TFMessage",
        text: "geometry_msgs/TransformStamped[] transforms\n",
        dependencies: &[&TransformStamped::DEFINITION],
    };
}
