//! `pomdar mock-franka`: the mock Franka node.

use std::sync::{Arc, Mutex};

use clap::Args;

use super::shared_args::{NodeArgs, ctrl_c_shutdown};
use crate::clock::StationClock;
use crate::ros::NetworkConfig;
use crate::stand_ins::mock_franka::{MockFrankaConfig, MockFrankaReport, run_mock_franka};

/// A mock Franka: follows pose commands at limited speed, publishes its pose.
#[derive(Debug, Args)]
pub struct MockFrankaArgs {
    /// Pose command topic.
    #[arg(long, default_value = "/franka/end_effector_pose_cmd")]
    pub command_topic: String,
    /// Pose feedback topic.
    #[arg(long, default_value = "/franka/end_effector_pose")]
    pub pose_topic: String,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
}

/// `pomdar mock-franka`.
pub async fn mock_franka(args: MockFrankaArgs) -> anyhow::Result<()> {
    let report = Arc::new(Mutex::new(MockFrankaReport::default()));
    let start = ::station::StationConfig::default()
        .arm
        .start_pose_isometry()?;
    let config = MockFrankaConfig {
        command_topic: args.command_topic,
        pose_topic: args.pose_topic,
        start,
        max_speed_m_s: 0.5,
        max_rate_rad_s: 1.0,
        rate_hz: 100.0,
    };
    run_mock_franka(
        config,
        args.node.network(&NetworkConfig::default()),
        StationClock::new(),
        report.clone(),
        ctrl_c_shutdown(),
    )
    .await?;
    if let Ok(r) = report.lock() {
        eprintln!("received {} commands ({} rejected)", r.commands, r.rejected);
    }
    Ok(())
}
