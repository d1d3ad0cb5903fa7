//! `diagnostic_msgs`: health for rqt_robot_monitor and Foxglove's diagnostics panels
//! (`/diagnostics`).

use serde::{Deserialize, Serialize};

use crate::{Header, MsgDefinition, RosMessage};

/// `diagnostic_msgs/msg/KeyValue`: one named value of a status.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct KeyValue {
    /// What is measured.
    pub key: String,
    /// Its value, as text.
    pub value: String,
}

impl RosMessage for KeyValue {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "diagnostic_msgs",
        name: "KeyValue",
        text: "string key\nstring value\n",
        dependencies: &[],
    };
}

/// `diagnostic_msgs/msg/DiagnosticStatus`: the state of one component.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct DiagnosticStatus {
    /// [`DiagnosticStatus::OK`], [`DiagnosticStatus::WARN`], [`DiagnosticStatus::ERROR`] or
    /// [`DiagnosticStatus::STALE`].
    pub level: u8,
    /// The component, e.g. `pomdar_station: glove`.
    pub name: String,
    /// A one-line summary.
    pub message: String,
    /// The hardware it concerns (may be empty).
    pub hardware_id: String,
    /// Measured values.
    pub values: Vec<KeyValue>,
}

impl DiagnosticStatus {
    /// Level: working.
    pub const OK: u8 = 0;
    /// Level: degraded.
    pub const WARN: u8 = 1;
    /// Level: failed.
    pub const ERROR: u8 = 2;
    /// Level: no recent information.
    pub const STALE: u8 = 3;
}

impl RosMessage for DiagnosticStatus {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "diagnostic_msgs",
        name: "DiagnosticStatus",
        text: "byte OK=0\n\
               byte WARN=1\n\
               byte ERROR=2\n\
               byte STALE=3\n\
               byte level\n\
               string name\n\
               string message\n\
               string hardware_id\n\
               KeyValue[] values\n",
        dependencies: &[&KeyValue::DEFINITION],
    };
}

/// `diagnostic_msgs/msg/DiagnosticArray`: the statuses of a node's components.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct DiagnosticArray {
    /// Stamp.
    pub header: Header,
    /// One status per component.
    pub status: Vec<DiagnosticStatus>,
}

impl RosMessage for DiagnosticArray {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "diagnostic_msgs",
        name: "DiagnosticArray",
        text: "std_msgs/Header header\nDiagnosticStatus[] status\n",
        dependencies: &[&Header::DEFINITION, &DiagnosticStatus::DEFINITION],
    };
}
