//! `pomdar eval`: retargeting quality on a recording's glove frames (the work is in
//! [`crate::eval`]).

use std::path::PathBuf;

use clap::Args;
use retarget::HandModel;

use crate::eval::{evaluate, table};
use crate::mcap_log::TrialReader;
use crate::station_setup::load_station_config;

/// `pomdar eval` options.
#[derive(Debug, Args)]
pub struct EvalArgs {
    /// The recording (MCAP) whose glove keypoints are retargeted.
    pub input: PathBuf,
    /// Station configuration: keypoint topic and format, retargeting settings (default: the
    /// built-in ETH lab preset, whose retargeting is the shipped default).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// The user's calibration profile (TOML written by `pomdar calibrate`); overrides the
    /// configuration's `calibration_profile`. Default: the configuration's, else none
    /// (identity: scale 1, no rotation).
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// Print the report as JSON on stdout instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// `pomdar eval`.
pub fn eval(args: EvalArgs) -> anyhow::Result<()> {
    let config = load_station_config(args.config.as_deref(), args.profile.as_deref())?;
    let reader = TrialReader::open(&args.input)?;
    let output = evaluate(&reader, &config, HandModel::orca_v1_right())?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&output)?);
    } else {
        print!("{}", table(&output));
    }
    Ok(())
}
