//! From commands to the messages the station sends: hand joint targets, the lab's
//! `/hand/policy_output`, and the arm target (with the arm clutch following the drive state).

use msgs::{Float32MultiArray, JointState, MultiArrayDimension, MultiArrayLayout, PoseStamped};
use nalgebra::Isometry3;
use retarget::HandModel;

use crate::arm::{ArmMapper, ArmRefusal};
use crate::convert::{header, isometry_to_pose};
use crate::hand_control::HandCommand;
use crate::policy_output::PolicyOutput;
use crate::station_config::StationConfig;
use crate::station_error::StationError;
use crate::watchdog::DriveState;

/// The messages of one hand command.
#[derive(Debug, Clone, PartialEq)]
pub struct HandMessages {
    /// Hand joint targets (URDF names and zeros, radians).
    pub joint_state: JointState,
    /// The same command for orca_core (17 values, wrist first), when that output is on.
    pub policy: Option<Float32MultiArray>,
}

/// What the arm did on one tick.
#[derive(Debug, Clone, PartialEq)]
pub enum ArmStep {
    /// No target this tick: the arm is off, blocked, disengaged, or no wrist pose came yet.
    Idle,
    /// A target to send.
    Target(PoseStamped),
    /// The arm mapping refused this tick's input (the arm holds: nothing is sent).
    Refused(ArmRefusal),
}

/// Where the arm's inputs stand on a tick.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArmInputs {
    /// The latest valid glove wrist pose.
    pub glove_wrist: Option<Isometry3<f64>>,
    /// The latest robot end-effector pose (arm feedback).
    pub robot_pose: Option<Isometry3<f64>>,
    /// Another publisher drives the arm command topic: send nothing.
    pub blocked: bool,
}

/// The output stage's state across ticks.
#[derive(Debug)]
pub struct OutputStage {
    arm: ArmMapper,
    arm_enabled: bool,
    arm_frame_id: String,
    policy: Option<PolicyOutput>,
    joint_names: Vec<String>,
    previous_state: DriveState,
    /// Engaged, but the arm clutch still waits for the first glove wrist pose.
    arm_engage_pending: bool,
    /// The last target sent since the clutch last latched: what a hold repeats (never one
    /// of an earlier engagement).
    held_target: Option<Isometry3<f64>>,
}

impl OutputStage {
    /// The stage for a configuration and hand model.
    pub fn new(config: &StationConfig, model: &HandModel) -> Result<OutputStage, StationError> {
        let policy = if config.policy_output.topic.is_empty() {
            None
        } else {
            Some(PolicyOutput::new(model, &config.policy_output)?)
        };
        Ok(OutputStage {
            arm: ArmMapper::new(config.arm.clone())?,
            arm_enabled: !config.output.arm_target_topic.is_empty(),
            arm_frame_id: config.output.arm_frame_id.clone(),
            policy,
            joint_names: crate::joint_names::published_joint_names(
                model,
                config.output.joint_name_prefix.as_deref(),
            ),
            previous_state: DriveState::Disengaged,
            arm_engage_pending: false,
            held_target: None,
        })
    }

    /// The arm mapper (for status).
    pub fn arm(&self) -> &ArmMapper {
        &self.arm
    }

    /// Whether the station drives an arm at all.
    pub fn arm_enabled(&self) -> bool {
        self.arm_enabled
    }

    /// The messages for `command`, stamped with the glove frame's source time when fresh
    /// (end-to-end latency is measurable downstream) and with `now_ns` when held.
    pub fn hand_messages(&self, command: &HandCommand, now_ns: i64) -> HandMessages {
        let stamp = if command.held {
            now_ns
        } else {
            command.frame_source_ns
        };
        HandMessages {
            joint_state: JointState {
                header: header(stamp, ""),
                name: self.joint_names.clone(),
                position: command.q.clone(),
                velocity: vec![],
                effort: vec![],
            },
            policy: self
                .policy
                .as_ref()
                .map(|p| policy_array(p.values(&command.q))),
        }
    }

    /// The operator disengaged: release the arm clutch at once, not at the next tick, so an
    /// engage granted before that tick latches afresh from the robot's current pose.
    pub fn disengage(&mut self) {
        self.previous_state = DriveState::Disengaged;
        self.release_arm();
    }

    fn release_arm(&mut self) {
        self.arm_engage_pending = false;
        self.held_target = None;
        self.arm.disengage();
    }

    /// The arm on a tick at `now_ns` in drive `state`. The clutch engages at the first engaged
    /// tick with a glove wrist pose after the station left the disengaged state (the wrist
    /// topic may deliver after the keypoints that engaged it, and the first tick may find the
    /// input already stale, held) and releases on disengage; while held the last target of
    /// this engagement is repeated. `Err` says why the clutch could not engage (the station
    /// warns the operator).
    pub fn arm_step(
        &mut self,
        state: DriveState,
        inputs: ArmInputs,
        now_ns: i64,
    ) -> (ArmStep, Option<ArmRefusal>) {
        let engage_error = self.follow_state(state, inputs);
        let Some(wrist) = inputs
            .glove_wrist
            .filter(|_| self.arm_enabled && !inputs.blocked)
        else {
            return (ArmStep::Idle, engage_error);
        };
        let target = match state {
            DriveState::Engaged => match self.arm.step(wrist) {
                Ok(command) => {
                    self.held_target = command.map(|c| c.target);
                    self.held_target
                }
                Err(e) => return (ArmStep::Refused(e), engage_error),
            },
            DriveState::Held => self.held_target,
            DriveState::Disengaged => None,
        };
        let step = match target {
            Some(t) => ArmStep::Target(PoseStamped {
                header: header(now_ns, &self.arm_frame_id),
                pose: isometry_to_pose(&t),
            }),
            None => ArmStep::Idle,
        };
        (step, engage_error)
    }

    fn follow_state(&mut self, state: DriveState, inputs: ArmInputs) -> Option<ArmRefusal> {
        let was = self.previous_state;
        self.previous_state = state;
        match (was, state) {
            (DriveState::Disengaged, DriveState::Engaged | DriveState::Held) => {
                self.arm_engage_pending = true;
            }
            (_, DriveState::Disengaged) => self.release_arm(),
            _ => {}
        }
        let (true, DriveState::Engaged, Some(wrist)) =
            (self.arm_engage_pending, state, inputs.glove_wrist)
        else {
            return None;
        };
        self.arm_engage_pending = false;
        self.held_target = None;
        let engaged = match inputs.robot_pose {
            Some(robot) => self.arm.engage(wrist, robot),
            None => self.arm.engage_at_start_pose(wrist),
        };
        engaged.err()
    }
}

/// A policy output array of `values` (one dimension, `joints`).
pub fn policy_array(values: Vec<f32>) -> Float32MultiArray {
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
    use nalgebra::{Translation3, UnitQuaternion};

    use super::*;

    fn wrist(z: f64) -> Option<Isometry3<f64>> {
        Some(Isometry3::from_parts(
            Translation3::new(0.0, 0.0, z),
            UnitQuaternion::identity(),
        ))
    }

    fn step(
        stage: &mut OutputStage,
        state: DriveState,
        glove_wrist: Option<Isometry3<f64>>,
    ) -> bool {
        let inputs = ArmInputs {
            glove_wrist,
            robot_pose: None,
            blocked: false,
        };
        matches!(stage.arm_step(state, inputs, 0).0, ArmStep::Target(_))
    }

    #[test]
    fn the_arm_engages_at_the_first_wrist_pose_after_engage_even_when_it_comes_late() {
        let config = StationConfig::default();
        let mut stage = OutputStage::new(&config, &HandModel::orca_v1_right()).unwrap();
        // Engaged by the first keypoints, before any wrist pose arrived.
        assert!(!step(&mut stage, DriveState::Engaged, None));
        assert!(step(&mut stage, DriveState::Engaged, wrist(0.0)));
        assert!(step(&mut stage, DriveState::Engaged, wrist(0.001)));
        // Disengage releases the clutch; engaging again latches afresh.
        assert!(!step(&mut stage, DriveState::Disengaged, wrist(0.001)));
        assert!(!step(&mut stage, DriveState::Disengaged, wrist(0.001)));
        assert!(step(&mut stage, DriveState::Engaged, wrist(0.002)));
        assert!(stage.arm().is_engaged());
    }

    #[test]
    fn held_input_waits_for_engaged_before_latching_a_late_wrist() {
        let config = StationConfig::default();
        let mut stage = OutputStage::new(&config, &HandModel::orca_v1_right()).unwrap();
        assert!(!step(&mut stage, DriveState::Engaged, None));
        assert!(!step(&mut stage, DriveState::Held, wrist(0.0)));
        assert!(!stage.arm().is_engaged());
        assert!(step(&mut stage, DriveState::Engaged, wrist(0.0)));
    }
}
