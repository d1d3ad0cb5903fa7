//! `pomdar resim`: re-simulate a log through the station.

use std::path::PathBuf;

use anyhow::Context as _;
use clap::Args;
use retarget::HandModel;

use crate::station_driver::setup::load_station_config;

/// Re-simulate a recorded log's glove input through the station, deterministically.
///
/// The station's processing is fed from the log with the log's clock, in process; the
/// outputs (joint targets, policy output, arm targets) are written to a new MCAP. Use it to
/// re-retarget recorded glove data with a new configuration. A log the station recorded
/// carries its timer ticks and the operator's engage/disengage (/pomdar/station_control):
/// with the run's configuration it reproduces the run's commands byte for byte. A plain
/// glove recording gets ticks on the log's clock and engages on its first fresh frame.
/// Accepts the lab's 22- and 21-point layouts. Same log + same config = byte-identical
/// output.
///
/// Example:
///   pomdar resim trial.mcap --config launch_configs/station/eth_lab.toml --out resim.mcap --stats-json stats.json
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct ResimArgs {
    /// The recorded log (MCAP) whose glove input is re-simulated.
    pub input: PathBuf,
    /// Station configuration (default: the built-in ETH lab preset).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Output log (MCAP) for the station's outputs.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Write the statistics as JSON to this file.
    #[arg(long, value_name = "FILE")]
    pub stats_json: Option<PathBuf>,
    /// Replace an existing output file.
    #[arg(long)]
    pub overwrite: bool,
    /// The user's calibration profile (TOML written by `pomdar calibrate`); overrides the
    /// configuration's `calibration_profile`. Default: the configuration's, else none
    /// (identity: scale 1, no rotation).
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
}

/// `pomdar resim`.
pub fn resim(args: ResimArgs) -> anyhow::Result<()> {
    use crate::mcap_log::{TrialReader, TrialWriter, TrialWriterOptions};
    let config = load_station_config(args.config.as_deref(), args.profile.as_deref())?;
    let reader = TrialReader::open(&args.input)?;
    let options = TrialWriterOptions {
        overwrite: args.overwrite,
        ..TrialWriterOptions::default()
    };
    let mut writer = TrialWriter::create(&args.out, options)?;
    let stats = crate::resim::resim(&reader, &config, HandModel::orca_v1_right(), &mut writer)?;
    writer.finish()?;
    let json = serde_json::to_string_pretty(&stats)?;
    if let Some(path) = &args.stats_json {
        std::fs::write(path, &json).with_context(|| format!("cannot write {}", path.display()))?;
    }
    let ms = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.3}"));
    if let Some(profile) = &stats.profile {
        eprintln!("{profile}");
    }
    eprintln!(
        "re-simulated {}: {} frames ({} new of which {} with an outlier put back, {} repeated, rejected {:?}), {} joint targets, layout {}, control step p50 {} ms, p99 {} ms → {}",
        args.input.display(),
        stats.frames_read,
        stats.frames_new,
        stats.frames_repaired,
        stats.frames_repeated,
        stats.rejected,
        stats.joint_targets,
        stats.layout,
        ms(stats.step_ms_p50),
        ms(stats.step_ms_p99),
        args.out.display()
    );
    Ok(())
}
