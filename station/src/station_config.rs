//! The station's configuration (TOML; `launch_configs/station/*.toml` are presets). Every
//! table is optional and defaults to the ETH lab's topics; unknown keys are rejected; errors
//! name the key and its allowed range (the application adds the file).

use std::path::PathBuf;

use retarget::RetargetConfig;
use serde::{Deserialize, Serialize};

use crate::arm::ArmConfig;
use crate::config_error::ConfigError;
use crate::frame_gate::GateConfig;
use crate::network_config::{NetworkConfig, QosConfig};
use crate::policy_output::PolicyOutputConfig;
use crate::robot_link::RobotLinkConfig;
use crate::ros_tools_config::RosToolsConfig;
use crate::simulated_physics_config::SimulatedPhysicsConfig;
use crate::watchdog::WatchdogConfig;

/// The whole station configuration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct StationConfig {
    /// DDS domain and interfaces.
    pub network: NetworkConfig,
    /// Where glove keypoints and the wrist pose come from.
    pub input: InputConfig,
    /// Where commands and status go.
    pub output: OutputConfig,
    /// When the retargeter runs.
    pub control: ControlConfig,
    /// Plausibility limits of keypoint frames.
    pub gate: GateConfig,
    /// Stale-input timeouts.
    pub watchdog: WatchdogConfig,
    /// How commands reach the robot's computer (straight, or through `pomdar relay`).
    pub robot_link: RobotLinkConfig,
    /// The lab's `/hand/policy_output` (orca_core convention).
    pub policy_output: PolicyOutputConfig,
    /// Retargeting (layout, embodiment, weights, solver).
    pub retarget: RetargetConfig,
    /// Arm target mapping (task constraint, workspace, step caps).
    pub arm: ArmConfig,
    /// What the lab's ROS tools see: `/tf`, markers, `/diagnostics`, services.
    pub ros_tools: RosToolsConfig,
    /// The user's calibration profile (`pomdar calibrate` writes it). In a file, a relative
    /// path is relative to the configuration file's directory; unset: no calibration
    /// (identity transform).
    pub calibration_profile: Option<PathBuf>,
    /// The simulated benchmark's hand: a lab's MuJoCo model of the robot hand (the
    /// manufacturer's MJCF, its meshes beside it) instead of the hand the project writes from
    /// the URDF. In a file, a relative path is relative to the configuration file's directory;
    /// unset: the project's hand. Only the simulator reads it.
    pub simulated_hand_mjcf: Option<PathBuf>,
    /// The simulated benchmark's contact, actuator and mount settings (unset: the twin's
    /// defaults). Only the simulator reads them.
    pub simulated_physics: SimulatedPhysicsConfig,
}

/// How keypoints arrive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum KeypointFormat {
    /// The lab's `std_msgs/Float32MultiArray`, N × 3 metres, no stamp.
    Float32MultiArray,
    /// `geometry_msgs/PoseArray`: the positions of its poses, stamped.
    PoseArray,
}

/// Input topics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct InputConfig {
    /// Keypoint topic.
    pub keypoints_topic: String,
    /// Keypoint message type.
    pub keypoints_format: KeypointFormat,
    /// Glove wrist pose topic (`geometry_msgs/PoseStamped`).
    pub wrist_topic: String,
    /// Arm end-effector pose feedback (`geometry_msgs/PoseStamped`); latched at engage.
    pub arm_feedback_topic: String,
    /// The hand's measured joint state (`sensor_msgs/JointState`), recorded and compared
    /// with the commands where the hand publishes one (the mock hand does; the ETH stack
    /// publishes none today); empty: not read.
    pub hand_state_topic: String,
    /// The ingress's status (`std_msgs/String` carrying JSON, as `pomdar ingress` and the
    /// simulated glove publish it): its `source` (kind and device) goes into every trial log's
    /// metadata as `keypoint_source` and `keypoint_device`; empty: not read (`unknown`).
    pub ingress_status_topic: String,
    /// QoS of the glove topics: deep enough for the lab's 200 Hz republishing.
    pub qos: QosConfig,
}

/// Output topics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputConfig {
    /// Hand joint targets (`sensor_msgs/JointState`, URDF names and zeros, radians).
    pub joint_targets_topic: String,
    /// Prefix of the published joint names; unset: the names the robot's URDF uses (the
    /// model's import prefix, `right_` for the built-in ORCA v1 right), `""`: the model's bare
    /// names (`thumb_mcp`).
    pub joint_name_prefix: Option<String>,
    /// Arm target (`geometry_msgs/PoseStamped`); empty disables the arm.
    pub arm_target_topic: String,
    /// `frame_id` of the arm target.
    pub arm_frame_id: String,
    /// Station status (`std_msgs/String` carrying JSON).
    pub status_topic: String,
    /// Status publishing rate, Hz.
    pub status_rate_hz: f64,
    /// QoS of the command topics.
    pub qos: QosConfig,
}

/// When the retargeter runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ControlMode {
    /// A hand command as each new (changed, accepted) glove frame arrives, at most
    /// `max_command_rate_hz` by the frames' own stamps (the default; `every_frame` is the old
    /// name).
    #[serde(alias = "every_frame")]
    OnArrival,
    /// A hand command on every tick of the `rate_hz` timer, from the newest frame.
    Rate,
}

/// Control loop settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ControlConfig {
    /// On frame arrival, or on the timer.
    pub mode: ControlMode,
    /// The station's timer, Hz. Every tick advances the watchdog, steps the arm target (its
    /// step caps are per tick) and repeats a held hand command; with `mode = "rate"` it also
    /// computes the hand command.
    pub rate_hz: f64,
    /// Ceiling on hand commands with `mode = "on_arrival"`, Hz: a frame stamped less than
    /// `1 / max_command_rate_hz` after the last commanded one waits for the next frame or tick.
    pub max_command_rate_hz: f64,
    /// Engage automatically once input is fresh, once (demo, tests); the console engages
    /// explicitly.
    pub auto_engage: bool,
}

impl Default for StationConfig {
    fn default() -> Self {
        StationConfig {
            network: NetworkConfig::default(),
            input: InputConfig::default(),
            output: OutputConfig::default(),
            control: ControlConfig::default(),
            gate: GateConfig::default(),
            watchdog: WatchdogConfig::default(),
            robot_link: RobotLinkConfig::default(),
            policy_output: PolicyOutputConfig {
                topic: "/hand/policy_output".into(),
                ..PolicyOutputConfig::default()
            },
            retarget: RetargetConfig::default(),
            arm: ArmConfig::default(),
            ros_tools: RosToolsConfig::default(),
            calibration_profile: None,
            simulated_hand_mjcf: None,
            simulated_physics: SimulatedPhysicsConfig::default(),
        }
    }
}

impl Default for InputConfig {
    fn default() -> Self {
        InputConfig {
            keypoints_topic: "/ingress/mano".into(),
            keypoints_format: KeypointFormat::Float32MultiArray,
            wrist_topic: "/ingress/wrist".into(),
            arm_feedback_topic: "/franka/end_effector_pose".into(),
            hand_state_topic: "/pomdar/hand/joint_states".into(),
            ingress_status_topic: "/ingress/status".into(),
            qos: QosConfig::best_effort(400),
        }
    }
}

impl Default for OutputConfig {
    fn default() -> Self {
        OutputConfig {
            joint_targets_topic: "/pomdar/hand/joint_targets".into(),
            joint_name_prefix: None,
            arm_target_topic: "/franka/end_effector_pose_cmd".into(),
            arm_frame_id: "world".into(),
            status_topic: "/pomdar/status".into(),
            status_rate_hz: 5.0,
            qos: QosConfig::reliable(50),
        }
    }
}

impl Default for ControlConfig {
    fn default() -> Self {
        ControlConfig {
            mode: ControlMode::OnArrival,
            rate_hz: 25.0,
            max_command_rate_hz: 200.0,
            auto_engage: false,
        }
    }
}

/// The embodiment of a human study: the participant's own hand, no robot.
pub const HUMAN_EMBODIMENT: &str = "human";

impl StationConfig {
    /// Whether this configuration drives a robot: false for embodiment
    /// [`HUMAN_EMBODIMENT`] (a human study records the glove only).
    pub fn drives_robot(&self) -> bool {
        self.retarget.embodiment != HUMAN_EMBODIMENT
    }

    /// Parse and validate.
    pub fn from_toml_str(text: &str) -> Result<StationConfig, ConfigError> {
        let config: StationConfig = toml::from_str(text).map_err(|e| ConfigError::Syntax {
            reason: e.to_string().trim_end().to_string(),
        })?;
        config.validate()?;
        Ok(config)
    }

    /// Check every value.
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.control.validate()?;
        if !(self.output.status_rate_hz > 0.0 && self.output.status_rate_hz <= 100.0) {
            return Err(ConfigError::out_of_range(
                "output.status_rate_hz",
                self.output.status_rate_hz,
                "in (0, 100]",
            ));
        }
        for (key, topic) in [
            ("input.keypoints_topic", &self.input.keypoints_topic),
            (
                "output.joint_targets_topic",
                &self.output.joint_targets_topic,
            ),
            ("output.status_topic", &self.output.status_topic),
            // Optional: empty reads no ingress status.
            (
                "input.ingress_status_topic",
                &self.input.ingress_status_topic,
            ),
        ] {
            let optional_and_off = key == "input.ingress_status_topic" && topic.is_empty();
            if !optional_and_off && !topic.starts_with('/') {
                return Err(ConfigError::out_of_range(
                    key,
                    format!("'{topic}'"),
                    "an absolute topic name (start with '/')",
                ));
            }
        }
        self.input.qos.validate("input.qos")?;
        self.output.qos.validate("output.qos")?;
        self.gate.validate()?;
        self.watchdog.validate()?;
        self.robot_link.validate()?;
        if self.gate.reorder_window_ms >= self.watchdog.disengage_timeout_ms {
            return Err(ConfigError::out_of_range(
                "gate.reorder_window_ms",
                self.gate.reorder_window_ms,
                format!(
                    "less than watchdog.disengage_timeout_ms ({}): a sender's clock stepping back must not disengage the station",
                    self.watchdog.disengage_timeout_ms
                ),
            ));
        }
        self.policy_output.validate()?;
        self.ros_tools.validate()?;
        self.retarget.validate()?;
        self.arm.validate()?;
        self.simulated_physics.validate()?;
        self.network.validate()
    }
}

impl ControlConfig {
    /// Check the rates.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if !(self.rate_hz >= 1.0 && self.rate_hz <= 2000.0) {
            return Err(ConfigError::out_of_range(
                "control.rate_hz",
                self.rate_hz,
                "in [1, 2000]",
            ));
        }
        if !(self.max_command_rate_hz >= 1.0 && self.max_command_rate_hz <= 2000.0) {
            return Err(ConfigError::out_of_range(
                "control.max_command_rate_hz",
                self.max_command_rate_hz,
                "in [1, 2000]",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn an_empty_file_is_the_eth_lab_default() {
        let config = StationConfig::from_toml_str("").unwrap();
        assert_eq!(config, StationConfig::default());
        assert_eq!(config.input.keypoints_topic, "/ingress/mano");
    }

    #[test]
    fn errors_name_the_key() {
        let err = StationConfig::from_toml_str("[control]\nrate_hz = 0.1\n").unwrap_err();
        assert!(err.to_string().contains("control.rate_hz"), "{err}");
        let err =
            StationConfig::from_toml_str("[output]\nstatus_topic = \"status\"\n").unwrap_err();
        assert!(err.to_string().contains("output.status_topic"), "{err}");
        let err = StationConfig::from_toml_str("[input]\ntopic = \"/x\"\n").unwrap_err();
        assert!(err.to_string().contains("topic"), "{err}");
        let err = StationConfig::from_toml_str("[control]\nmax_command_rate_hz = 0\n").unwrap_err();
        assert!(
            err.to_string().contains("control.max_command_rate_hz"),
            "{err}"
        );
    }

    #[test]
    fn the_old_every_frame_mode_reads_as_on_arrival() {
        let config = StationConfig::from_toml_str("[control]\nmode = \"every_frame\"\n").unwrap();
        assert_eq!(config.control.mode, ControlMode::OnArrival);
        assert_eq!(
            StationConfig::default().control.mode,
            ControlMode::OnArrival
        );
    }
}
