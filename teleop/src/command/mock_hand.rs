//! `pomdar mock-hand`: the mock ORCA hand node.

use std::sync::{Arc, Mutex};

use clap::Args;
use retarget::HandModel;

use super::common::{NodeArgs, ctrl_c_shutdown};
use crate::clock::StationClock;
use crate::ros::NetworkConfig;
use crate::sim::mock_hand::{MockHandConfig, MockHandReport, run_mock_hand};

/// `pomdar mock-hand` options.
#[derive(Debug, Args)]
pub struct MockHandArgs {
    /// Joint target topic.
    #[arg(long, default_value = "/pomdar/hand/joint_targets")]
    pub targets_topic: String,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
}

/// `pomdar mock-hand`.
pub async fn mock_hand(args: MockHandArgs) -> anyhow::Result<()> {
    let report = Arc::new(Mutex::new(MockHandReport::default()));
    let config = MockHandConfig {
        targets_topic: args.targets_topic,
        ..MockHandConfig::default()
    };
    run_mock_hand(
        HandModel::orca_v1_right(),
        config,
        args.node.network(&NetworkConfig::default()),
        StationClock::new(),
        report.clone(),
        ctrl_c_shutdown(),
    )
    .await?;
    if let Ok(r) = report.lock() {
        eprintln!(
            "received {} targets, latency p50 {:?} ms",
            r.targets,
            r.latency.percentile(0.5)
        );
    }
    Ok(())
}
