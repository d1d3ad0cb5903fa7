//! `pomdar eval`: retargeting quality on recordings' glove frames (the work is in
//! [`crate::eval`]): one recording, or an evaluation set (several files, or directories of
//! them) with a table per recording and a summary.

use std::path::PathBuf;

use clap::Args;
use retarget::HandModel;
use retarget::quality::REACH_GRID_MAX_CONFIGURATIONS;

use super::shared_args::readable_mcap_files;
use crate::eval::summary::{SetOutput, summary_table};
use crate::eval::{EvalOptions, evaluate, table};
use crate::eval_modes::{eval_commands, eval_outlier_study, eval_profile_scales, in_file};
use crate::mcap_log::TrialReader;
use crate::progress_bar::{ProgressBar, ProgressStyle};
use crate::station_driver::setup::load_station_config;

/// Retargeting quality on recordings' glove keypoints: how closely the hand follows.
///
/// Several recordings (files, or directories searched for .mcap files: an evaluation
/// set) give a report per recording, then a summary table (live path and retargeter alone,
/// one row per recording, the worst of each column).
///
/// Each distinct keypoint frame (repeats of the ingress's re-publishing are dropped) goes
/// through the station's retargeter, configured by --config and calibrated by --profile,
/// with the recording's time between frames as the time step (the station's input gate
/// and control loop are left out: every glove frame is scored, comparable with other
/// retargeters). Then the live path: the recording re-simulated through the station as
/// `pomdar resim` runs it, and the command in force at each distinct frame scored the same
/// way, with its difference from the retargeter alone. Prints, overall and per finger: fingertip error after one global scale s* of the human hand (mean, p95;
/// fingertip-to-palm-centre vectors in each hand's palm frame), pinches (human thumb tip
/// within 2 cm of a fingertip) and the share the robot closes under 15 mm, jerk (mean
/// absolute third difference per joint and frame), the largest per-frame joint step,
/// frames outside the joint limits, and the time per frame. Any layout the station
/// accepts. Then the metrics without the global scale (a smaller-looking hand does not
/// score better): per finger the tip error after that finger's own scale, the correlation
/// of human and robot flexion (palm-centre-to-tip distance), pinches closed with their
/// frame counts, and the lag (the shift that best aligns robot to human flexion).
/// --commands TOPIC scores another retargeter's recorded JointState commands instead.
///
/// Examples:
///   pomdar eval recordings/glove_session.mcap
///   pomdar eval trial.mcap --config launch_configs/station/eth_lab.toml --profile profiles/alice.toml --json
///   pomdar eval recordings/ eval_set/
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct EvalArgs {
    /// The recordings (MCAP) whose glove keypoints are retargeted, or directories searched
    /// for them (an evaluation set, e.g. from `pomdar eval-set`).
    #[arg(required = true, value_name = "RECORDING")]
    pub inputs: Vec<PathBuf>,
    /// Station configuration: keypoint topic and format, retargeting settings (default: the
    /// built-in ETH lab preset, whose retargeting is the shipped default).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// The user's calibration profile (TOML written by `pomdar calibrate`); overrides the
    /// configuration's `calibration_profile`. Default: the configuration's, else none
    /// (identity: scale 1, no rotation).
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// Score the `sensor_msgs/JointState` commands another retargeter recorded on this topic
    /// (the command in force at each distinct keypoint frame) instead of the station's own
    /// retargeting; joint names as the model's, a `right_`/`left_` prefix dropped.
    #[arg(long, value_name = "TOPIC")]
    pub commands: Option<String>,
    /// Print the report as JSON on stdout instead of the tables (one recording: its report;
    /// several: `{"recordings": [...], "summary": [...]}`).
    #[arg(long)]
    pub json: bool,
    /// Also report, per digit, the own scale Σ robot·human / Σ |human|² (fingertip to palm
    /// centre vectors in each hand's palm frame), the global s*, and the reachability bound:
    /// the mean over frames of the distance from the human tip target (scaled by s*) to the
    /// nearest fingertip the robot reaches on a grid over that digit's joints within the
    /// URDF limits (at most --reach-grid configurations per digit; a second or so).
    #[arg(long)]
    pub reach: bool,
    /// Most grid configurations per digit for --reach: the default gives 58 steps per joint
    /// for a three-joint finger and 21 for the four-joint thumb (ORCA v1).
    #[arg(long, value_name = "N", default_value_t = REACH_GRID_MAX_CONFIGURATIONS, requires = "reach")]
    pub reach_grid: usize,
    /// Instead of the full report: the retargeter alone under a calibration profile of each
    /// of these scales with no rotation (replacing any profile), tip error (after s* and after
    /// each digit's own scale) and jerk per scale; e.g. 1.0,0.9,0.8. No live path.
    #[arg(long, value_name = "SCALES", value_delimiter = ',', conflicts_with_all = ["commands", "reach"])]
    pub profile_scales: Vec<f64>,
    /// Instead of the full report: a camera tracker's one-frame outliers injected into each
    /// recording (one point of a digit leaping 3-6 cm for one frame, 20 times, drawn from
    /// --outlier-seed) and the station re-simulated with the frame gate's outlier check and
    /// without it: the largest joint change toward the outliers, the extra frames before the
    /// robot closes each sustained pinch, and the clean frames the check caught (a point put back).
    #[arg(long, conflicts_with_all = ["commands", "reach", "profile_scales"])]
    pub outlier_study: bool,
    /// Seed of the outliers of --outlier-study.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 1,
        requires = "outlier_study"
    )]
    pub outlier_seed: u64,
}

/// `pomdar eval`.
pub fn eval(args: EvalArgs) -> anyhow::Result<()> {
    let config = load_station_config(args.config.as_deref(), args.profile.as_deref())?;
    if let Some(topic) = &args.commands {
        let files = readable_mcap_files(&args.inputs)?;
        return Ok(eval_commands(&files, &config, topic, args.json)?);
    }
    if !args.profile_scales.is_empty() {
        if let Some(bad) = args
            .profile_scales
            .iter()
            .find(|s| !(s.is_finite() && **s > 0.0))
        {
            anyhow::bail!("--profile-scales: {bad} is not a positive scale");
        }
        let files = readable_mcap_files(&args.inputs)?;
        return Ok(eval_profile_scales(
            &files,
            &config,
            &args.profile_scales,
            args.json,
        )?);
    }
    if args.outlier_study {
        let files = readable_mcap_files(&args.inputs)?;
        return Ok(eval_outlier_study(
            &files,
            &config,
            args.outlier_seed,
            args.json,
        )?);
    }
    let options = EvalOptions {
        reach_max_configurations: args.reach.then_some(args.reach_grid),
    };
    let single = args.inputs.len() == 1 && args.inputs[0].is_file();
    let files = if single {
        args.inputs.clone()
    } else {
        readable_mcap_files(&args.inputs)?
    };
    let mut outputs = Vec::new();
    let style = match single {
        true => ProgressStyle::Silent,
        false => ProgressStyle::redraw_on_terminal(ProgressStyle::Lines { every: 1 }),
    };
    let mut progress = ProgressBar::new(style);
    for (done, path) in files.iter().enumerate() {
        progress.update(done, files.len(), &path.display().to_string());
        let reader = TrialReader::open(path)?;
        let output = evaluate(&reader, &config, HandModel::orca_v1_right(), options)
            .map_err(|e| in_file(path, &e))?;
        if !args.json {
            println!("{}", table(&output));
        }
        outputs.push(output);
    }
    progress.update(files.len(), files.len(), "recordings evaluated");
    progress.finish();
    if single && args.json {
        println!("{}", serde_json::to_string_pretty(&outputs[0])?);
        return Ok(());
    }
    let set = SetOutput::of(outputs);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&set)?);
    } else if !single {
        print!("{}", summary_table(&set));
    }
    Ok(())
}
