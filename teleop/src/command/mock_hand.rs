//! `pomdar mock-hand`: the mock ORCA hand node.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use anyhow::Context as _;
use clap::Args;
use retarget::HandModel;
use station::policy_output::PolicyOutput;

use super::shared_args::{NodeArgs, ctrl_c_shutdown};
use crate::clock::StationClock;
use crate::ros::NetworkConfig;
use crate::stand_ins::mock_hand::{MockHandConfig, MockHandReport, PolicyInput, run_mock_hand};
use crate::station_driver::setup::read_station_config;

/// A mock ORCA hand: follows joint targets with a first-order lag, publishes its state
/// (and with --policy-config, a policy output topic through the inverse of its table).
#[derive(Debug, Args)]
pub struct MockHandArgs {
    /// Joint target topic.
    #[arg(long, default_value = "/pomdar/hand/joint_targets")]
    pub targets_topic: String,
    /// Also follow this station configuration's policy output topic, decoded through the
    /// inverse of its [[policy_output.joints]] table (or its offsets_rad): what
    /// `pomdar hand-check` with the same --config sends moves the mock hand's joints.
    #[arg(long, value_name = "FILE")]
    pub policy_config: Option<PathBuf>,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
}

/// `pomdar mock-hand`.
pub async fn mock_hand(args: MockHandArgs) -> anyhow::Result<()> {
    let model = HandModel::orca_v1_right();
    let policy = match &args.policy_config {
        Some(path) => {
            let config = read_station_config(path)?;
            if config.policy_output.topic.is_empty() {
                anyhow::bail!("{}: policy_output.topic is empty", path.display());
            }
            let table = PolicyOutput::new(&model, &config.policy_output)
                .with_context(|| format!("{}: policy_output", path.display()))?;
            eprintln!(
                "mock hand: following {} ({})",
                config.policy_output.topic,
                config.policy_output.verification().line()
            );
            Some(PolicyInput {
                topic: config.policy_output.topic,
                table,
            })
        }
        None => None,
    };
    let report = Arc::new(Mutex::new(MockHandReport::default()));
    let config = MockHandConfig {
        targets_topic: args.targets_topic,
        policy,
        ..MockHandConfig::default()
    };
    run_mock_hand(
        model,
        config,
        args.node.network(&NetworkConfig::default()),
        StationClock::new(),
        report.clone(),
        ctrl_c_shutdown(),
    )
    .await?;
    if let Ok(r) = report.lock() {
        eprintln!(
            "received {} targets, latency p50 {:?} ms; {} policy outputs ({} rejected)",
            r.targets,
            r.latency.percentile(0.5),
            r.policy_targets,
            r.policy_rejected
        );
    }
    Ok(())
}
