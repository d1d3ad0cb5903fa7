//! `std_srvs`: the `Trigger` service the station offers (engage, disengage, trial start, stop,
//! abort). Service types are named `pkg/srv/Type` in ROS and `pkg::srv::dds_::Type_Request_` /
//! `_Response_` on DDS.

use serde::{Deserialize, Serialize};

/// `std_srvs/srv/Trigger` request: empty. DDS cannot carry an empty structure, so ROS 2 gives
/// it one `uint8` member, which this type keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct TriggerRequest {
    /// Always 0 (ROS 2's placeholder member).
    pub structure_needs_at_least_one_member: u8,
}

/// `std_srvs/srv/Trigger` response.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct TriggerResponse {
    /// Whether the request was carried out.
    pub success: bool,
    /// What happened, or why not.
    pub message: String,
}

/// `std_srvs/srv/Trigger`, the ROS type name.
pub const TRIGGER_TYPE: &str = "std_srvs/srv/Trigger";
/// The request's DDS type name.
pub const TRIGGER_REQUEST_DDS_TYPE: &str = "std_srvs::srv::dds_::Trigger_Request_";
/// The response's DDS type name.
pub const TRIGGER_RESPONSE_DDS_TYPE: &str = "std_srvs::srv::dds_::Trigger_Response_";
