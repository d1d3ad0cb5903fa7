//! What a trial's log holds for its review, decoded by the caller (the application reads the
//! MCAP file): every series with its log time, nanoseconds on the station's clock.

use std::collections::BTreeMap;

use nalgebra::Point3;

/// One glove frame as the station received it.
#[derive(Debug, Clone, PartialEq)]
pub struct GloveFrame {
    /// Log time, nanoseconds.
    pub t_ns: i64,
    /// The keypoints, metres, in the configured layout.
    pub points: Vec<Point3<f64>>,
}

/// One `sensor_msgs/JointState`: a joint target the station sent, or a measured hand state.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct JointSample {
    /// Log time, nanoseconds.
    pub t_ns: i64,
    /// Header stamp, nanoseconds. A held hand command is stamped with the time it was sent
    /// (its log time); a fresh one with its glove frame's time.
    pub stamp_ns: i64,
    /// Joint names.
    pub names: Vec<String>,
    /// Positions, radians, in the order of `names`.
    pub position: Vec<f64>,
}

/// A trial's log, decoded.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TrialInput {
    /// The file, as the operator named it.
    pub source: String,
    /// The `pomdar_trial` metadata record.
    pub metadata: BTreeMap<String, String>,
    /// The trial events (`start`, `progress`, `drop`, `abort`, `note`, `stop`), in file order.
    pub events: Vec<(i64, serde_json::Value)>,
    /// The station's status messages (JSON), in time order.
    pub statuses: Vec<(i64, serde_json::Value)>,
    /// The glove frames, in time order.
    pub glove_frames: Vec<GloveFrame>,
    /// The hand commands the station sent, in time order.
    pub joint_targets: Vec<JointSample>,
    /// The hand's measured joint states, in time order (empty when the log has none).
    pub hand_states: Vec<JointSample>,
    /// The arm targets' positions, robot base frame, metres, in time order.
    pub arm_targets: Vec<(i64, [f64; 3])>,
}
