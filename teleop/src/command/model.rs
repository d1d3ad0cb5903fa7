//! `pomdar model`: load a hand model, validate it and print it.

use clap::Args;

use super::common::HandSourceArgs;
use crate::model_report;

/// `pomdar model` options.
#[derive(Debug, Args)]
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
