//! `[ros_tools]`: what the station offers the lab's ROS tools (RViz, Foxglove,
//! rqt_robot_monitor) besides its commands: `/tf`, markers, `/diagnostics`,
//! `/robot_description`, and the services that drive it.

use serde::{Deserialize, Serialize};

use crate::config_error::ConfigError;

/// How ROS 2 services are carried on DDS (which RMW the lab's clients use).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ServiceMapping {
    /// rmw_fastrtps (the default RMW of Humble and Jazzy): the request's identity travels as
    /// DDS inline QoS.
    #[default]
    Enhanced,
    /// rmw_cyclonedds: a 16-byte request header in front of the payload.
    Cyclone,
}

/// `[ros_tools]` configuration. Every topic or service may be emptied to turn it off.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RosToolsConfig {
    /// Publish `/tf` (every moving link of the hand, and the arm target) and `/tf_static`
    /// (the fixed links).
    pub tf: bool,
    /// The `/tf` name of the hand model's root link; empty: its URDF name (ORCA: `world`).
    pub root_frame: String,
    /// The arm target as a `/tf` frame, child of `output.arm_frame_id`; empty: none.
    pub arm_target_frame: String,
    /// `visualization_msgs/MarkerArray`: the glove keypoints as the retargeter sees them
    /// (after calibration, placed on the robot's palm frame) and the robot's fingertips.
    pub keypoint_markers_topic: String,
    /// `visualization_msgs/MarkerArray`: the robot hand drawn from primitive shapes in its
    /// link frames (latched), for viewers without the hand's meshes.
    pub hand_model_markers_topic: String,
    /// `diagnostic_msgs/DiagnosticArray` at the status rate.
    pub diagnostics_topic: String,
    /// `std_msgs/String` with the URDF text (transient local), published only when the
    /// station was given a URDF (`--urdf`); the project ships none.
    pub robot_description_topic: String,
    /// The station's services (`std_srvs/srv/Trigger`).
    pub services: ServicesConfig,
}

/// Service names (`std_srvs/srv/Trigger` each); an empty name offers no such service.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ServicesConfig {
    /// How requests and replies are carried (the lab's RMW).
    pub mapping: ServiceMapping,
    /// Engage: drive hand and arm once the glove input is fresh.
    pub engage: String,
    /// Disengage: the hand holds, the arm stops.
    pub disengage: String,
    /// Start a trial (in the operator console: the countdown's start).
    pub trial_start: String,
    /// Stop the running trial (finished).
    pub trial_stop: String,
    /// Abort the running trial.
    pub trial_abort: String,
}

impl Default for RosToolsConfig {
    fn default() -> Self {
        RosToolsConfig {
            tf: true,
            root_frame: String::new(),
            arm_target_frame: "pomdar_arm_target".into(),
            keypoint_markers_topic: "/pomdar/markers/keypoints".into(),
            hand_model_markers_topic: "/pomdar/markers/hand_model".into(),
            diagnostics_topic: "/diagnostics".into(),
            robot_description_topic: "/robot_description".into(),
            services: ServicesConfig::default(),
        }
    }
}

impl Default for ServicesConfig {
    fn default() -> Self {
        ServicesConfig {
            mapping: ServiceMapping::Enhanced,
            engage: "/pomdar/engage".into(),
            disengage: "/pomdar/disengage".into(),
            trial_start: "/pomdar/trial/start".into(),
            trial_stop: "/pomdar/trial/stop".into(),
            trial_abort: "/pomdar/trial/abort".into(),
        }
    }
}

impl ServicesConfig {
    /// The offered services: (what it does, its name), empty names left out.
    pub fn offered(&self) -> Vec<(ServiceAction, &str)> {
        [
            (ServiceAction::Engage, &self.engage),
            (ServiceAction::Disengage, &self.disengage),
            (ServiceAction::TrialStart, &self.trial_start),
            (ServiceAction::TrialStop, &self.trial_stop),
            (ServiceAction::TrialAbort, &self.trial_abort),
        ]
        .into_iter()
        .filter(|(_, name)| !name.is_empty())
        .map(|(action, name)| (action, name.as_str()))
        .collect()
    }
}

/// What a service call asks of the station.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ServiceAction {
    /// Engage.
    Engage,
    /// Disengage.
    Disengage,
    /// Start a trial.
    TrialStart,
    /// Stop the running trial.
    TrialStop,
    /// Abort the running trial.
    TrialAbort,
}

impl RosToolsConfig {
    /// Check every topic and service name: empty (off) or absolute.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let s = &self.services;
        let names = [
            (
                "ros_tools.keypoint_markers_topic",
                &self.keypoint_markers_topic,
            ),
            (
                "ros_tools.hand_model_markers_topic",
                &self.hand_model_markers_topic,
            ),
            ("ros_tools.diagnostics_topic", &self.diagnostics_topic),
            (
                "ros_tools.robot_description_topic",
                &self.robot_description_topic,
            ),
            ("ros_tools.services.engage", &s.engage),
            ("ros_tools.services.disengage", &s.disengage),
            ("ros_tools.services.trial_start", &s.trial_start),
            ("ros_tools.services.trial_stop", &s.trial_stop),
            ("ros_tools.services.trial_abort", &s.trial_abort),
        ];
        for (key, name) in names {
            if !name.is_empty() && !name.starts_with('/') {
                return Err(ConfigError::out_of_range(
                    key,
                    format!("'{name}'"),
                    "empty (off) or an absolute name (start with '/')",
                ));
            }
        }
        for (key, frame) in [
            ("ros_tools.root_frame", &self.root_frame),
            ("ros_tools.arm_target_frame", &self.arm_target_frame),
        ] {
            if frame.starts_with('/') || frame.contains(char::is_whitespace) {
                return Err(ConfigError::out_of_range(
                    key,
                    format!("'{frame}'"),
                    "a tf frame name: no leading '/', no spaces",
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_validate_and_offer_five_services() {
        let config = RosToolsConfig::default();
        config.validate().unwrap();
        assert_eq!(config.services.offered().len(), 5);
    }

    #[test]
    fn a_relative_service_name_is_named_with_its_key() {
        let mut config = RosToolsConfig::default();
        config.services.trial_abort = "abort".into();
        let error = config.validate().unwrap_err().to_string();
        assert!(error.contains("ros_tools.services.trial_abort"), "{error}");
        config.services.trial_abort = String::new();
        config.validate().unwrap();
        assert_eq!(config.services.offered().len(), 4);
    }
}
