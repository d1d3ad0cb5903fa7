//! What the station is driven by, and what one step gives back.

use msgs::{Pose, PoseStamped};
use serde::{Deserialize, Serialize};

use crate::arm::ArmRefusal;
use crate::frame_gate::GateDecision;
use crate::hand_control::KeypointFrame;
use crate::output_stage::HandMessages;

/// One input to [`Station::step`](crate::Station::step), which takes its receive time beside
/// it.
#[derive(Debug, Clone, PartialEq)]
pub enum StationInput {
    /// A glove keypoint frame.
    Keypoints(KeypointFrame),
    /// The glove wrist pose (tracker frame).
    Wrist(Pose),
    /// The arm's end-effector pose (robot base frame), latched when the arm clutch engages.
    ArmFeedback(Pose),
    /// The station's timer, the operator, or the application's watch on the arm topic.
    Control(ControlInput),
}

/// The inputs that are not ROS messages. A recording keeps them on their own channel
/// (`/pomdar/station_control`, JSON), so a run re-simulates to itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "input", rename_all = "snake_case")]
pub enum ControlInput {
    /// A tick of the station's timer (`control.rate_hz`).
    Tick,
    /// The operator engages (granted with fresh input).
    Engage,
    /// The operator disengages: the arm stops, the hand holds.
    Disengage,
    /// Another publisher appeared on (`true`) or left (`false`) the arm command topic: while
    /// one drives it the station sends no arm target.
    ArmBlocked {
        /// Whether another publisher drives the arm topic.
        blocked: bool,
    },
}

/// A message for the operator.
#[derive(Debug, Clone, PartialEq)]
pub enum Notice {
    /// The arm clutch could not engage (the hand is driven, the arm is not).
    ArmNotEngaged(ArmRefusal),
    /// Another publisher drives the arm command topic: no arm targets until it stops.
    ArmBlocked,
}

impl std::fmt::Display for Notice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Notice::ArmNotEngaged(e) => write!(f, "warning: arm not engaged: {e}"),
            Notice::ArmBlocked => write!(
                f,
                "warning: another publisher drives the arm command topic: refusing to drive the arm until it stops"
            ),
        }
    }
}

/// What one step gives back: the messages to send, in this order, and what became of the
/// input.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StationOutputs {
    /// The hand command's messages, when one is due.
    pub hand: Option<HandMessages>,
    /// Receive time of the glove frame behind a freshly computed hand command (for the
    /// application's latency figure); `None` for a held or repeated one.
    pub fresh_frame_received_ns: Option<i64>,
    /// The arm target, when one is due.
    pub arm: Option<PoseStamped>,
    /// What the frame gate said of a keypoint frame.
    pub verdict: Option<GateDecision>,
    /// Messages for the operator.
    pub notices: Vec<Notice>,
}
