//! `pomdar model`: load a hand model, validate it and print it.

use clap::Args;

use super::shared_args::HandSourceArgs;
use crate::model_report;

/// Load a hand model, validate it and print its joints, limits, frames and embodiments.
///
/// Without options it shows the built-in ORCA v1 right hand. Use it to check a new hand's
/// URDF before running the station with it: errors name the file, element and problem.
///
/// Examples:
///   pomdar model
///   pomdar model --urdf orcahand_v1_right.urdf --import launch_configs/hands/orca_v1_right_urdf.toml
///   pomdar model --pose index_mcp=0.8,thumb_mcp=0.3 --json
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct ModelArgs {
    /// The hand to load.
    #[command(flatten)]
    pub hand: HandSourceArgs,
    /// Joint values (radians) for the frame positions, as NAME=VALUE[,NAME=VALUE...];
    /// unnamed joints stay at zero.
    #[arg(long, value_name = "JOINTS", value_delimiter = ',')]
    pub pose: Vec<String>,
    /// Print JSON instead of tables.
    #[arg(long)]
    pub json: bool,
}

/// `pomdar model`.
pub fn model(args: ModelArgs) -> anyhow::Result<()> {
    Ok(model_report::run(
        &args.hand.source(),
        &args.pose,
        args.json,
    )?)
}
