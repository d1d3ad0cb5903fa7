//! The station's configuration file (TOML; `launch_configs/station/*.toml` are presets).
//! Every table is optional and defaults to the ETH lab's topics; unknown keys are rejected;
//! errors name the file and the key.

use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use retarget::RetargetConfig;
use serde::{Deserialize, Serialize};

use crate::arm::ArmConfig;
use crate::ros::{NetworkConfig, QosConfig};
use crate::station::frame_gate::GateConfig;
use crate::station::policy_output::PolicyOutputConfig;
use crate::station::watchdog::WatchdogConfig;

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
    /// The lab's `/hand/policy_output` (orca_core convention).
    pub policy_output: PolicyOutputConfig,
    /// Retargeting (layout, embodiment, weights, solver).
    pub retarget: RetargetConfig,
    /// Arm target mapping (task constraint, workspace, step caps).
    pub arm: ArmConfig,
    /// The user's calibration profile (`pomdar calibrate` writes it). In a file, a relative
    /// path is relative to the configuration file's directory; unset: no calibration
    /// (identity transform).
    pub calibration_profile: Option<PathBuf>,
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
    /// QoS of the glove topics: deep enough for the lab's 200 Hz republishing.
    pub qos: QosConfig,
}

/// Output topics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputConfig {
    /// Hand joint targets (`sensor_msgs/JointState`, URDF names and zeros, radians).
    pub joint_targets_topic: String,
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
    /// On a fixed-rate timer (`rate_hz`), using the newest frame.
    Rate,
    /// On every new (changed) frame.
    EveryFrame,
}

/// Control loop settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ControlConfig {
    /// Timer or every frame.
    pub mode: ControlMode,
    /// Timer rate, Hz (`mode = "rate"`); commands are republished at this rate while held.
    pub rate_hz: f64,
    /// Engage automatically once input is fresh (demo, tests); the console engages explicitly.
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
            policy_output: PolicyOutputConfig {
                topic: "/hand/policy_output".into(),
                ..PolicyOutputConfig::default()
            },
            retarget: RetargetConfig::default(),
            arm: ArmConfig::default(),
            calibration_profile: None,
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
            qos: QosConfig::best_effort(400),
        }
    }
}

impl Default for OutputConfig {
    fn default() -> Self {
        OutputConfig {
            joint_targets_topic: "/pomdar/hand/joint_targets".into(),
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
            mode: ControlMode::Rate,
            rate_hz: 25.0,
            auto_engage: false,
        }
    }
}

impl StationConfig {
    /// Parse and validate.
    pub fn from_toml_str(text: &str) -> anyhow::Result<StationConfig> {
        let config: StationConfig =
            toml::from_str(text).map_err(|e| anyhow::anyhow!("{}", e.to_string().trim_end()))?;
        config.validate()?;
        Ok(config)
    }

    /// Read, parse and validate a file; errors name it. A relative `calibration_profile` is
    /// resolved against the file's directory.
    pub fn from_file(path: &Path) -> anyhow::Result<StationConfig> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let mut config =
            StationConfig::from_toml_str(&text).with_context(|| format!("{}", path.display()))?;
        if let Some(profile) = &config.calibration_profile
            && profile.is_relative()
        {
            let dir = path.parent().unwrap_or(Path::new(""));
            config.calibration_profile = Some(dir.join(profile));
        }
        Ok(config)
    }

    /// Check every value.
    pub fn validate(&self) -> anyhow::Result<()> {
        if !(self.control.rate_hz >= 1.0 && self.control.rate_hz <= 2000.0) {
            bail!(
                "control.rate_hz = {} must be in [1, 2000]",
                self.control.rate_hz
            );
        }
        if !(self.output.status_rate_hz > 0.0 && self.output.status_rate_hz <= 100.0) {
            bail!(
                "output.status_rate_hz = {} must be in (0, 100]",
                self.output.status_rate_hz
            );
        }
        for (key, topic) in [
            ("input.keypoints_topic", &self.input.keypoints_topic),
            (
                "output.joint_targets_topic",
                &self.output.joint_targets_topic,
            ),
            ("output.status_topic", &self.output.status_topic),
        ] {
            if !topic.starts_with('/') {
                bail!("{key} = '{topic}' must be an absolute topic name (start with '/')");
            }
        }
        self.input.qos.validate("input.qos")?;
        self.output.qos.validate("output.qos")?;
        self.gate.validate()?;
        self.watchdog.validate()?;
        if self.gate.reorder_window_ms >= self.watchdog.disengage_timeout_ms {
            bail!(
                "gate.reorder_window_ms = {} must be less than watchdog.disengage_timeout_ms ({}): a sender's clock stepping back must not disengage the station",
                self.gate.reorder_window_ms,
                self.watchdog.disengage_timeout_ms
            );
        }
        self.retarget
            .validate()
            .map_err(|e| anyhow::anyhow!("retarget: {e}"))?;
        self.arm
            .validate()
            .map_err(|e| anyhow::anyhow!("arm: {e}"))?;
        crate::ros::domain_id(self.network.domain_id).context("network.domain_id")?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
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
    }

    #[test]
    fn a_relative_profile_is_relative_to_the_config_file() {
        let dir = std::env::temp_dir().join(format!("pomdar-station-cfg-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("station.toml");
        std::fs::write(&path, "calibration_profile = \"profiles/alice.toml\"\n").unwrap();
        let config = StationConfig::from_file(&path).unwrap();
        std::fs::remove_dir_all(&dir).ok();
        assert_eq!(
            config.calibration_profile,
            Some(dir.join("profiles/alice.toml"))
        );
    }
}
