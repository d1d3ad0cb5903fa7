//! `pomdar tracking`: commanded against measured joint angles of a trial log, per joint (the
//! reading is in [`crate::eval::tracking`], the comparison in [`scoring::tracking_report`],
//! the figure in [`scoring::plot::tracking_grid`]).

use std::path::PathBuf;

use anyhow::Context as _;
use clap::Args;
use retarget::HandModel;
use scoring::{JointTracking, TrackingReport, TrackingSettings, track_joint, tracking_chart};

use crate::atomic_file::write_atomically;
use crate::eval::tracking::{TrackingOutput, TrackingTopics, read_tracking, tracking_table};
use crate::mcap_log::TrialReader;
use crate::progress_bar::{ProgressBar, ProgressStyle};
use crate::station_driver::setup::load_station_config;

/// Measured samples over all joints above which the comparison shows its progress.
const PROGRESS_SAMPLES: usize = 200_000;

/// How closely the hand followed its commands in a trial log: commanded vs measured, per
/// joint.
///
/// Reads the station's joint targets ([output] joint_targets_topic) and the hand's
/// measured state ([input] hand_state_topic), both sensor_msgs/JointState as the station
/// recorded them, with their names mapped onto the model's joints. Per joint: commands and
/// measured samples, the RMS and largest |command in force − measured| (degrees; the
/// command in force is the last one sent at or before the measurement), the lag that best
/// aligns the measured angle with the command (the highest correlation over 0–300 ms, in
/// whole milliseconds) and the share of time the error exceeds --threshold-deg (5°).
/// Prints a table (or JSON with --json); --out DIR writes tracking.svg and tracking.png
/// (one panel per joint: commanded and measured angle over time, titled with the joint
/// and its RMS error) and tracking.json, each atomically. A log without measured states
/// is an error naming the file and the topic looked at.
///
/// Examples:
///   pomdar tracking sessions/alice/orca_full/V1/V1-t03.mcap
///   pomdar tracking run.mcap --out report/tracking --json > tracking.json
///   pomdar tracking run.mcap --config launch_configs/station/eth_lab.toml --threshold-deg 3
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct TrackingArgs {
    /// The trial log (MCAP) the station recorded, with the hand's measured state.
    #[arg(value_name = "TRIAL")]
    pub trial: PathBuf,
    /// Write tracking.svg, tracking.png and tracking.json here (created if needed; each file
    /// written atomically, replacing an earlier one).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Print the report as JSON on stdout instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Station configuration the log was recorded with: the topics and the joint name prefix
    /// (default: the built-in ETH lab preset).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// The commands' topic (default: the configuration's `[output] joint_targets_topic`).
    #[arg(long, value_name = "TOPIC")]
    pub commanded: Option<String>,
    /// The measured state's topic (default: the configuration's `[input] hand_state_topic`).
    #[arg(long, value_name = "TOPIC")]
    pub measured: Option<String>,
    /// The error counted in the share of time over it, degrees.
    #[arg(long, value_name = "DEG", default_value_t = TrackingSettings::default().threshold_deg)]
    pub threshold_deg: f64,
    /// The largest lag tried, milliseconds (every whole millisecond from 0).
    #[arg(long, value_name = "MS", default_value_t = TrackingSettings::default().max_lag_ms)]
    pub max_lag_ms: u32,
}

/// `pomdar tracking`.
pub fn tracking(args: TrackingArgs) -> anyhow::Result<()> {
    if !(args.threshold_deg.is_finite() && args.threshold_deg > 0.0) {
        anyhow::bail!("--threshold-deg {} must be above 0", args.threshold_deg);
    }
    if args.max_lag_ms > 10_000 {
        anyhow::bail!("--max-lag-ms {} must be at most 10000", args.max_lag_ms);
    }
    let config = load_station_config(args.config.as_deref(), None)?;
    let topics = TrackingTopics {
        commanded: (args.commanded.clone()).unwrap_or(config.output.joint_targets_topic.clone()),
        measured: (args.measured.clone()).unwrap_or(config.input.hand_state_topic.clone()),
        joint_name_prefix: config.output.joint_name_prefix.clone(),
    };
    let model = HandModel::orca_v1_right();
    let reader = TrialReader::open(&args.trial)?;
    let input = read_tracking(&reader, &model, &topics)?;
    let settings = TrackingSettings {
        max_lag_ms: args.max_lag_ms,
        threshold_deg: args.threshold_deg,
    };
    let report = compare(&input.tracks, settings);
    let output = TrackingOutput::new(&input, report);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&output)?);
    } else {
        print!("{}", tracking_table(&output));
    }
    if let Some(dir) = &args.out {
        let name = args.trial.file_name().map_or_else(
            || args.trial.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        let chart = tracking_chart(
            &input.tracks,
            &output.report,
            "Commanded vs measured joint angle (deg)",
            Some(format!(
                "{name}: {} on {}, {} on {}",
                output.commands, output.commanded_topic, output.states, output.measured_topic
            )),
        );
        let figure = scoring::plot::tracking_grid(&chart)
            .with_context(|| format!("the tracking figure of {}", args.trial.display()))?;
        let json = serde_json::to_string_pretty(&output)? + "\n";
        for (file, bytes) in [
            ("tracking.svg", figure.svg.as_bytes()),
            ("tracking.png", figure.png.as_slice()),
            ("tracking.json", json.as_bytes()),
        ] {
            let path = dir.join(file);
            write_atomically(&path, bytes)?;
            eprintln!("wrote {}", path.display());
        }
    }
    Ok(())
}

/// Every joint compared, with progress on stderr for a long log.
fn compare(tracks: &[scoring::JointTrack], settings: TrackingSettings) -> TrackingReport {
    let samples: usize = tracks.iter().map(|t| t.measured.len()).sum();
    let style = if samples > PROGRESS_SAMPLES {
        ProgressStyle::redraw_on_terminal(ProgressStyle::Lines { every: 4 })
    } else {
        ProgressStyle::Silent
    };
    let mut progress = ProgressBar::new(style);
    let mut joints: Vec<JointTracking> = Vec::with_capacity(tracks.len());
    for (done, track) in tracks.iter().enumerate() {
        progress.update(done, tracks.len(), &track.joint);
        joints.push(track_joint(track, settings));
    }
    progress.update(tracks.len(), tracks.len(), "joints compared");
    progress.finish();
    TrackingReport { settings, joints }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use clap::Parser;

    use super::*;

    #[derive(Debug, Parser)]
    struct Cli {
        #[command(flatten)]
        args: TrackingArgs,
    }

    #[test]
    fn the_defaults_are_the_analysis_defaults_and_bad_settings_are_refused() {
        use clap::CommandFactory as _;
        Cli::command().debug_assert();
        let args = Cli::try_parse_from(["pomdar", "run.mcap"]).unwrap().args;
        assert_eq!(args.threshold_deg, 5.0);
        assert_eq!(args.max_lag_ms, 300);
        assert_eq!((args.out, args.json), (None, false));
        for bad in [["--threshold-deg", "0"], ["--max-lag-ms", "20000"]] {
            let argv = ["pomdar", "run.mcap"].into_iter().chain(bad);
            let args = Cli::try_parse_from(argv).unwrap().args;
            let error = tracking(args).unwrap_err().to_string();
            assert!(error.contains(bad[0]), "{error}");
        }
    }
}
