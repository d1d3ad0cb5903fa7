//! The simulated robot's settings: its topics (the real robot's), the arm's start and speed
//! limits, its rates, and how the task's progress is read.

use nalgebra::Isometry3;
use scoring::CorrectnessKind;
use simulation::progress::PhysicsMapping;

use super::setup::SimulatedTask;

/// The simulated robot's settings.
#[derive(Debug, Clone, PartialEq)]
pub struct PhysicsRobotConfig {
    /// Hand target topic (`sensor_msgs/JointState`).
    pub hand_targets_topic: String,
    /// Hand state topic (`sensor_msgs/JointState`).
    pub hand_state_topic: String,
    /// Arm target topic (`PoseStamped`).
    pub arm_target_topic: String,
    /// Arm pose feedback topic (`PoseStamped`).
    pub arm_feedback_topic: String,
    /// Progress events (`std_msgs/String`, JSON).
    pub progress_topic: String,
    /// The task object's pose (`PoseStamped`), when the scene has one.
    pub object_topic: String,
    /// The frame of arm poses and object poses (the arm's base).
    pub frame_id: String,
    /// The arm's start pose, base frame.
    pub arm_start: Isometry3<f64>,
    /// Arm translation speed limit, m/s.
    pub arm_max_speed_m_s: f64,
    /// Arm rotation speed limit, rad/s.
    pub arm_max_rate_rad_s: f64,
    /// Physics tick, seconds (each advances by the wall time since the last).
    pub tick_s: f64,
    /// State publishing rate, Hz.
    pub state_rate_hz: f64,
    /// The task's id (in progress messages).
    pub task_id: String,
    /// How the task's progress counts, and where it is read; `None`: no progress published.
    pub progress: Option<(CorrectnessKind, PhysicsMapping)>,
    /// The task object's body, for its pose.
    pub object_body: Option<String>,
}

impl PhysicsRobotConfig {
    /// Topics and rates as the mock robot's, for `task_id` and no progress.
    pub fn new(task_id: &str, arm_start: Isometry3<f64>) -> Self {
        PhysicsRobotConfig {
            hand_targets_topic: "/pomdar/hand/joint_targets".into(),
            hand_state_topic: "/pomdar/hand/joint_states".into(),
            arm_target_topic: "/franka/end_effector_pose_cmd".into(),
            arm_feedback_topic: "/franka/end_effector_pose".into(),
            progress_topic: "/pomdar/sim/progress".into(),
            object_topic: "/pomdar/sim/object_pose".into(),
            frame_id: "world".into(),
            arm_start,
            arm_max_speed_m_s: 0.5,
            arm_max_rate_rad_s: 1.0,
            tick_s: 0.005,
            state_rate_hz: 100.0,
            task_id: task_id.to_string(),
            progress: None,
            object_body: None,
        }
    }
}

impl PhysicsRobotConfig {
    /// The simulated robot on `station`'s topics for the task `loaded`, its arm starting at
    /// `arm_start`.
    pub fn for_station(
        station: &station::StationConfig,
        loaded: &SimulatedTask,
        arm_start: Isometry3<f64>,
    ) -> PhysicsRobotConfig {
        PhysicsRobotConfig {
            hand_targets_topic: station.output.joint_targets_topic.clone(),
            hand_state_topic: station.input.hand_state_topic.clone(),
            arm_target_topic: station.output.arm_target_topic.clone(),
            arm_feedback_topic: station.input.arm_feedback_topic.clone(),
            frame_id: station.output.arm_frame_id.clone(),
            progress: Some((loaded.task.correctness, loaded.progress.clone())),
            object_body: loaded.object_body.clone(),
            ..PhysicsRobotConfig::new(&loaded.task.id, arm_start)
        }
    }
}
