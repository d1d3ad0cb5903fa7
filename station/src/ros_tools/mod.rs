//! What the station offers the lab's ROS tools besides its commands, as pure functions of its
//! model, configuration and status: `/tf` and `/tf_static` from its own kinematics
//! ([`hand_tf`]), markers of the glove keypoints and a drawing of the hand ([`markers`]),
//! `/diagnostics` ([`diagnostics()`]); the `[ros_tools]` configuration with the service names is
//! `ros_tools_config.rs`, the published joint names [`crate::joint_names`]. The application publishes and records them.

pub mod diagnostics;
pub mod hand_tf;
pub mod markers;

pub use crate::joint_names::{dof_of_published_name, published_joint_names};
pub use crate::ros_tools_config::{RosToolsConfig, ServiceAction, ServiceMapping, ServicesConfig};
pub use diagnostics::diagnostics;
pub use hand_tf::HandTf;
