//! From a control tick to the messages the station sends: hand joint targets, the lab's
//! `/hand/policy_output`, and the arm target (with the arm clutch following the drive state).
//! Pure: the ROS node publishes these messages, the re-simulation writes them to a log.

use anyhow::Context as _;
use msgs::{Float32MultiArray, JointState, MultiArrayDimension, MultiArrayLayout, PoseStamped};
use nalgebra::Isometry3;
use retarget::HandModel;

use crate::arm::ArmMapper;
use crate::ros::convert::{header, isometry_to_pose};
use crate::station::policy_output::PolicyOutput;
use crate::station::station_config::{ControlMode, StationConfig};
use crate::station::station_core::Tick;
use crate::station::watchdog::DriveState;

/// The messages of one tick (each `None` when nothing is to be sent).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Outputs {
    /// Hand joint targets (URDF names and zeros, radians).
    pub joint_state: Option<JointState>,
    /// The same command for orca_core (17 values, wrist first).
    pub policy: Option<Float32MultiArray>,
    /// The arm end-effector target.
    pub arm: Option<PoseStamped>,
    /// Whether the hand command was computed from a new frame (not a repeat or hold).
    pub fresh_hand: bool,
}

/// The output stage's state across ticks.
#[derive(Debug)]
pub struct OutputStage {
    arm: ArmMapper,
    arm_enabled: bool,
    arm_frame_id: String,
    policy: Option<PolicyOutput>,
    joint_names: Vec<String>,
    mode: ControlMode,
    previous_state: DriveState,
    /// Engaged, but the arm clutch still waits for the first glove wrist pose.
    arm_engage_pending: bool,
    last_published_frame_ns: i64,
    /// Warnings for the operator, taken by [`OutputStage::take_warnings`].
    warnings: Vec<String>,
}

impl OutputStage {
    /// Warnings since the last call (the caller shows them: stderr or the operator console).
    pub fn take_warnings(&mut self) -> Vec<String> {
        std::mem::take(&mut self.warnings)
    }

    /// The stage for a configuration and hand model.
    pub fn new(config: &StationConfig, model: &HandModel) -> anyhow::Result<OutputStage> {
        let policy = if config.policy_output.topic.is_empty() {
            None
        } else {
            Some(PolicyOutput::new(model, &config.policy_output)?)
        };
        Ok(OutputStage {
            arm: ArmMapper::new(config.arm.clone())
                .map_err(|e| anyhow::anyhow!("arm: {e}"))
                .context("output stage")?,
            arm_enabled: !config.output.arm_target_topic.is_empty(),
            arm_frame_id: config.output.arm_frame_id.clone(),
            policy,
            joint_names: model.dof_names().map(str::to_string).collect(),
            mode: config.control.mode,
            previous_state: DriveState::Disengaged,
            arm_engage_pending: false,
            warnings: Vec::new(),
            last_published_frame_ns: i64::MIN,
        })
    }

    /// The arm mapper (for status).
    pub fn arm(&self) -> &ArmMapper {
        &self.arm
    }

    /// The messages for `tick` at `now_ns`. `frame_source_ns` stamps fresh hand commands (the
    /// glove frame's publish time); `glove_wrist` and `robot_pose` are the latest wrist pose
    /// and arm feedback; `arm_blocked` withholds arm targets (a second publisher drives the
    /// arm command topic).
    pub fn outputs(
        &mut self,
        tick: &Tick,
        now_ns: i64,
        frame_source_ns: i64,
        glove_wrist: Option<Isometry3<f64>>,
        robot_pose: Option<Isometry3<f64>>,
        arm_blocked: bool,
    ) -> Outputs {
        self.follow_state(tick.state, glove_wrist, robot_pose);
        let mut outputs = Outputs::default();
        // On every-frame control a timer tick only keeps a held command alive; fresh commands
        // go out once per new frame.
        let repeat = tick
            .hand
            .as_ref()
            .is_some_and(|h| !h.held && h.frame_received_ns == self.last_published_frame_ns);
        if repeat && self.mode == ControlMode::EveryFrame {
            return outputs;
        }
        if let Some(hand) = &tick.hand {
            self.last_published_frame_ns = hand.frame_received_ns;
            let stamp = if hand.held { now_ns } else { frame_source_ns };
            outputs.joint_state = Some(JointState {
                header: header(stamp, ""),
                name: self.joint_names.clone(),
                position: hand.q.clone(),
                velocity: vec![],
                effort: vec![],
            });
            outputs.policy = self
                .policy
                .as_ref()
                .map(|p| policy_array(p.values(&hand.q)));
            outputs.fresh_hand = !hand.held && !repeat;
        }
        if let (true, Some(wrist)) = (self.arm_enabled && !arm_blocked, glove_wrist) {
            let target = match tick.state {
                DriveState::Engaged => self.arm.step(wrist).ok().flatten().map(|c| c.target),
                DriveState::Held => self.arm.last_command().map(|c| c.target),
                DriveState::Disengaged => None,
            };
            outputs.arm = target.map(|t| PoseStamped {
                header: header(now_ns, &self.arm_frame_id),
                pose: isometry_to_pose(&t),
            });
        }
        outputs
    }

    /// Engage the arm clutch when the station becomes engaged (at the first tick with a glove
    /// wrist pose: the wrist topic may deliver after the keypoints that engaged the station),
    /// release it on disengage.
    fn follow_state(
        &mut self,
        state: DriveState,
        glove_wrist: Option<Isometry3<f64>>,
        robot_pose: Option<Isometry3<f64>>,
    ) {
        let was = self.previous_state;
        self.previous_state = state;
        match (was, state) {
            (DriveState::Disengaged, DriveState::Engaged) => self.arm_engage_pending = true,
            (_, DriveState::Disengaged) => {
                self.arm_engage_pending = false;
                self.arm.disengage();
            }
            _ => {}
        }
        if let (true, DriveState::Engaged, Some(wrist)) =
            (self.arm_engage_pending, state, glove_wrist)
        {
            self.arm_engage_pending = false;
            let engaged = match robot_pose {
                Some(robot) => self.arm.engage(wrist, robot),
                None => self.arm.engage_at_start_pose(wrist),
            };
            if let Err(e) = engaged {
                self.warnings.push(format!("warning: arm not engaged: {e}"));
            }
        }
    }
}

fn policy_array(values: Vec<f32>) -> Float32MultiArray {
    Float32MultiArray {
        layout: MultiArrayLayout {
            dim: vec![MultiArrayDimension {
                label: "joints".into(),
                size: values.len() as u32,
                stride: values.len() as u32,
            }],
            data_offset: 0,
        },
        data: values,
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use nalgebra::{Translation3, UnitQuaternion};

    use super::*;

    fn tick(state: DriveState) -> Tick {
        Tick { state, hand: None }
    }

    fn wrist(z: f64) -> Option<Isometry3<f64>> {
        Some(Isometry3::from_parts(
            Translation3::new(0.0, 0.0, z),
            UnitQuaternion::identity(),
        ))
    }

    #[test]
    fn the_arm_engages_at_the_first_wrist_pose_after_engage_even_when_it_comes_late() {
        let config = StationConfig::default();
        let mut stage = OutputStage::new(&config, &HandModel::orca_v1_right()).unwrap();
        let mut outputs = |state, wrist| stage.outputs(&tick(state), 0, 0, wrist, None, false);
        // Engaged by the first keypoints, before any wrist pose arrived.
        assert!(outputs(DriveState::Engaged, None).arm.is_none());
        assert!(outputs(DriveState::Engaged, wrist(0.0)).arm.is_some());
        assert!(outputs(DriveState::Engaged, wrist(0.001)).arm.is_some());
        // Disengage releases the clutch; engaging again latches afresh.
        assert!(outputs(DriveState::Disengaged, wrist(0.001)).arm.is_none());
        assert!(outputs(DriveState::Disengaged, wrist(0.001)).arm.is_none());
        assert!(outputs(DriveState::Engaged, wrist(0.002)).arm.is_some());
        assert!(stage.arm().is_engaged());
    }

    #[test]
    fn held_input_waits_for_engaged_before_latching_a_late_wrist() {
        let config = StationConfig::default();
        let mut stage = OutputStage::new(&config, &HandModel::orca_v1_right()).unwrap();
        let mut outputs = |state, wrist| stage.outputs(&tick(state), 0, 0, wrist, None, false);
        assert!(outputs(DriveState::Engaged, None).arm.is_none());
        assert!(outputs(DriveState::Held, wrist(0.0)).arm.is_none());
        assert!(!stage.arm().is_engaged());
        let mut outputs = |state, wrist| stage.outputs(&tick(state), 0, 0, wrist, None, false);
        assert!(outputs(DriveState::Engaged, wrist(0.0)).arm.is_some());
    }
}
