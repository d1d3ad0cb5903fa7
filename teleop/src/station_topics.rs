//! The topics a station sends to a live viewer and records into its logs, each with its ROS
//! type and `ros2msg` schema: what a viewer such as Foxglove can bind a panel to (the shipped
//! layouts in `launch_configs/foxglove/` are checked against this list).
//!
//! It follows the station node for a configuration:
//!
//! - **live** (`--view`, the station's tap): every message the node publishes — joint targets,
//!   `/hand/policy_output`, the arm target, `/tf`, the keypoint markers, `/diagnostics`, the
//!   status — and the latched ones (`/tf_static`, the hand's drawing, `/robot_description`);
//! - **recorded** (`pomdar station --record`, `pomdar demo --out`, `pomdar trial`): the same,
//!   plus the inputs as received (glove keypoints and wrist, the arm's pose feedback, the
//!   hand's measured joint state), the control inputs on
//!   [`STATION_CONTROL_TOPIC`] and the trial events on [`TRIAL_EVENTS_TOPIC`].
//!
//! The names are the configuration's: with a relay (`[robot_link]`) the commands cross the
//! network on the relay's topics, but the view and the log carry them under these names. An
//! empty topic name (turned off) is left out, and so is everything about the robot for a human
//! study's station (it drives none).

use msgs::{
    DiagnosticArray, Float32MultiArray, JointState, MarkerArray, PoseArray, PoseStamped,
    RosMessage, StringMsg, TFMessage,
};
use station::{KeypointFormat, StationConfig};

use crate::mcap_log::TRIAL_EVENTS_TOPIC;
use crate::station_node::control_input_log::STATION_CONTROL_TOPIC;

/// One topic the station sends to a live viewer or records.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StationTopic {
    /// The topic, e.g. `/pomdar/hand/joint_targets`.
    pub topic: String,
    /// `pkg/msg/Type`, e.g. `sensor_msgs/msg/JointState` (the schema name of its MCAP channel
    /// and of its live-view channel).
    pub ros_type: String,
    /// The complete `ros2msg` schema text, dependencies included (as in the log).
    pub schema_text: String,
    /// Served by the live view (`--view`).
    pub live: bool,
    /// Written into the station's logs.
    pub recorded: bool,
    /// Only when the station was given the robot's URDF (`pomdar station --urdf`):
    /// `/robot_description`.
    pub needs_urdf: bool,
}

impl StationTopic {
    fn of<M: RosMessage>(topic: &str, live: bool) -> StationTopic {
        StationTopic {
            topic: topic.to_string(),
            ros_type: M::ros_type_name(),
            schema_text: M::schema_text(),
            live,
            recorded: true,
            needs_urdf: false,
        }
    }
}

/// Every topic a station with `config` sends live or records, in a fixed order (outputs, then
/// the ROS tools' topics, then the inputs and the log's own channels).
pub fn station_topics(config: &StationConfig) -> Vec<StationTopic> {
    let robot = config.drives_robot();
    let on = |topic: &str| robot && !topic.is_empty();
    let tools = &config.ros_tools;
    let (live, log_only) = (true, false);
    let mut topics = vec![StationTopic::of::<StringMsg>(
        &config.output.status_topic,
        live,
    )];
    if robot {
        topics.push(StationTopic::of::<JointState>(
            &config.output.joint_targets_topic,
            live,
        ));
    }
    if on(&config.policy_output.topic) {
        topics.push(StationTopic::of::<Float32MultiArray>(
            &config.policy_output.topic,
            live,
        ));
    }
    if on(&config.output.arm_target_topic) {
        topics.push(StationTopic::of::<PoseStamped>(
            &config.output.arm_target_topic,
            live,
        ));
    }
    if robot && tools.tf {
        topics.push(StationTopic::of::<TFMessage>("/tf", live));
        topics.push(StationTopic::of::<TFMessage>("/tf_static", live));
    }
    if on(&tools.keypoint_markers_topic) {
        topics.push(StationTopic::of::<MarkerArray>(
            &tools.keypoint_markers_topic,
            live,
        ));
    }
    if on(&tools.hand_model_markers_topic) {
        topics.push(StationTopic::of::<MarkerArray>(
            &tools.hand_model_markers_topic,
            live,
        ));
    }
    if !tools.diagnostics_topic.is_empty() {
        topics.push(StationTopic::of::<DiagnosticArray>(
            &tools.diagnostics_topic,
            live,
        ));
    }
    if on(&tools.robot_description_topic) {
        topics.push(StationTopic {
            needs_urdf: true,
            ..StationTopic::of::<StringMsg>(&tools.robot_description_topic, live)
        });
    }
    let keypoints = &config.input.keypoints_topic;
    topics.push(match config.input.keypoints_format {
        KeypointFormat::Float32MultiArray => {
            StationTopic::of::<Float32MultiArray>(keypoints, log_only)
        }
        KeypointFormat::PoseArray => StationTopic::of::<PoseArray>(keypoints, log_only),
    });
    topics.push(StationTopic::of::<PoseStamped>(
        &config.input.wrist_topic,
        log_only,
    ));
    topics.push(StationTopic::of::<PoseStamped>(
        &config.input.arm_feedback_topic,
        log_only,
    ));
    if on(&config.input.hand_state_topic) {
        topics.push(StationTopic::of::<JointState>(
            &config.input.hand_state_topic,
            log_only,
        ));
    }
    topics.push(StationTopic::of::<StringMsg>(
        STATION_CONTROL_TOPIC,
        log_only,
    ));
    topics.push(StationTopic::of::<StringMsg>(TRIAL_EVENTS_TOPIC, log_only));
    topics
}

/// The topics the live view (`--view`) serves.
pub fn live_topics(config: &StationConfig) -> Vec<StationTopic> {
    station_topics(config)
        .into_iter()
        .filter(|t| t.live)
        .collect()
}

/// The topics the station's logs hold.
pub fn recorded_topics(config: &StationConfig) -> Vec<StationTopic> {
    station_topics(config)
        .into_iter()
        .filter(|t| t.recorded)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(topics: &[StationTopic]) -> Vec<&str> {
        topics.iter().map(|t| t.topic.as_str()).collect()
    }

    #[test]
    fn the_default_station_serves_its_outputs_live_and_records_its_inputs_too() {
        let config = StationConfig::default();
        let live = live_topics(&config);
        assert!(names(&live).contains(&"/pomdar/hand/joint_targets"));
        assert!(!names(&live).contains(&"/pomdar/hand/joint_states"));
        assert!(!names(&live).contains(&TRIAL_EVENTS_TOPIC));
        let recorded = recorded_topics(&config);
        assert_eq!(recorded.len(), station_topics(&config).len());
        let state = recorded
            .iter()
            .find(|t| t.topic == "/pomdar/hand/joint_states")
            .unwrap();
        assert_eq!(state.ros_type, "sensor_msgs/msg/JointState");
        assert!(state.schema_text.contains("float64[] position"));
        let description: Vec<_> = recorded.iter().filter(|t| t.needs_urdf).collect();
        assert_eq!(names(&live).iter().filter(|n| **n == "/tf").count(), 1);
        assert_eq!(description.len(), 1);
        assert_eq!(description[0].topic, "/robot_description");
    }

    #[test]
    fn topics_turned_off_and_a_human_study_leave_their_entries_out() {
        let mut config = StationConfig::default();
        config.ros_tools.keypoint_markers_topic = String::new();
        config.ros_tools.tf = false;
        let topics = station_topics(&config);
        assert!(!names(&topics).contains(&"/pomdar/markers/keypoints"));
        assert!(!names(&topics).contains(&"/tf"));
        config.retarget.embodiment = station::HUMAN_EMBODIMENT.to_string();
        let topics = station_topics(&config);
        assert!(!names(&topics).contains(&"/pomdar/hand/joint_targets"));
        assert!(!names(&topics).contains(&"/pomdar/markers/hand_model"));
        assert!(names(&topics).contains(&"/diagnostics"));
        assert!(names(&topics).contains(&"/ingress/mano"));
    }
}
