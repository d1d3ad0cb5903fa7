//! The mock robot of a station configuration: a mock ORCA hand on its joint-target topic and a
//! mock Franka on its arm topics, started at the arm's configured start pose; for `pomdar demo`
//! and `pomdar trial --simulate`.

use std::sync::{Arc, Mutex};

use retarget::HandModel;
use tokio::sync::watch;
use tokio::task::JoinHandle;

use crate::clock::StationClock;
use crate::stand_ins::error::SimError;
use crate::stand_ins::mock_franka::{MockFrankaConfig, MockFrankaReport, run_mock_franka};
use crate::stand_ins::mock_hand::{MockHandConfig, MockHandReport, run_mock_hand};
use station::StationConfig;

/// The running mock robot: its two nodes and what they saw (updated live).
#[derive(Debug)]
pub struct MockRobot {
    /// The mock hand's node.
    pub hand: JoinHandle<Result<(), SimError>>,
    /// The mock Franka's node.
    pub arm: JoinHandle<Result<(), SimError>>,
    /// What the hand saw.
    pub hand_report: Arc<Mutex<MockHandReport>>,
    /// What the arm saw.
    pub arm_report: Arc<Mutex<MockFrankaReport>>,
}

/// Starts the mock hand and arm on `station`'s network and topics, until `shutdown`.
pub fn spawn_mock_robot(
    station: &StationConfig,
    model: &HandModel,
    clock: StationClock,
    shutdown: &watch::Receiver<bool>,
) -> Result<MockRobot, SimError> {
    let hand_report = Arc::new(Mutex::new(MockHandReport::default()));
    let arm_report = Arc::new(Mutex::new(MockFrankaReport::default()));
    let start = station
        .arm
        .start_pose_isometry()
        .map_err(|source| SimError::ArmStartPose { source })?;
    let hand = tokio::spawn(run_mock_hand(
        model.clone(),
        MockHandConfig {
            targets_topic: station.output.joint_targets_topic.clone(),
            ..MockHandConfig::default()
        },
        station.network.clone(),
        clock,
        hand_report.clone(),
        shutdown.clone(),
    ));
    let arm = tokio::spawn(run_mock_franka(
        MockFrankaConfig {
            command_topic: station.output.arm_target_topic.clone(),
            pose_topic: station.input.arm_feedback_topic.clone(),
            start,
            max_speed_m_s: 0.5,
            max_rate_rad_s: 1.0,
            rate_hz: 100.0,
        },
        station.network.clone(),
        clock,
        arm_report.clone(),
        shutdown.clone(),
    ));
    Ok(MockRobot {
        hand,
        arm,
        hand_report,
        arm_report,
    })
}
