//! `pomdar replay`: republish a log over ROS 2 with its timing.

use std::path::PathBuf;

use clap::Args;

use super::shared_args::{NodeArgs, ctrl_c_shutdown};
use crate::ros::NetworkConfig;

/// Republish a log's recorded topics over ROS 2 with their original timing.
///
/// Example:
///   pomdar replay rokoko_orca_2024-11-20.mcap --topics /ingress/mano,/ingress/wrist --rate 1
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct ReplayArgs {
    /// The log (MCAP) to republish.
    pub input: PathBuf,
    /// Speed factor (1 = original timing).
    #[arg(long, default_value_t = 1.0)]
    pub rate: f64,
    /// Topics to republish (default: every topic of a supported type).
    #[arg(long, value_delimiter = ',')]
    pub topics: Vec<String>,
    /// Start again at the end.
    #[arg(long = "loop")]
    pub looped: bool,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
}

/// `pomdar replay`.
pub async fn replay(args: ReplayArgs) -> anyhow::Result<()> {
    let reader = crate::mcap_log::TrialReader::open(&args.input)?;
    let options = crate::replay::ReplayOptions {
        rate: args.rate,
        topics: args.topics,
        looped: args.looped,
        ..crate::replay::ReplayOptions::default()
    };
    let report = crate::replay::replay(
        &reader,
        &args.node.network(&NetworkConfig::default()),
        &options,
        ctrl_c_shutdown(),
    )
    .await?;
    eprintln!(
        "replayed {:?} ({} passes); skipped {:?}",
        report.published, report.passes, report.skipped
    );
    Ok(())
}
