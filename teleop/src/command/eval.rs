//! `pomdar eval`: retargeting quality on recordings' glove frames (the work is in
//! [`crate::eval`]): one recording, or an evaluation set (several files, or directories of
//! them) with a table per recording and a summary.

use std::path::PathBuf;

use clap::Args;
use retarget::HandModel;
use retarget::quality::REACH_GRID_MAX_CONFIGURATIONS;

use super::common::readable_mcap_files;
use crate::eval::external::{evaluate_commands, external_table};
use crate::eval::outlier_study::outlier_study;
use crate::eval::profile_scales::{profile_scales, profile_scales_table};
use crate::eval::summary::{SetOutput, summary_table};
use crate::eval::{EvalOptions, evaluate, table};
use crate::mcap_log::TrialReader;
use crate::progress_bar::{ProgressBar, ProgressStyle};
use crate::station_driver::setup::load_station_config;

/// `pomdar eval` options.
#[derive(Debug, Args)]
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
        return eval_commands(&args, &config, topic);
    }
    if !args.profile_scales.is_empty() {
        return eval_profile_scales(&args, &config);
    }
    if args.outlier_study {
        return eval_outlier_study(&args, &config);
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

/// `pomdar eval --outlier-study`: per recording, what one-frame outliers do with the outlier
/// check and without it.
fn eval_outlier_study(args: &EvalArgs, config: &station::StationConfig) -> anyhow::Result<()> {
    let files = readable_mcap_files(&args.inputs)?;
    let mut outputs = Vec::new();
    for path in &files {
        let reader = TrialReader::open(path)?;
        let study = outlier_study(
            &reader,
            config,
            &HandModel::orca_v1_right(),
            args.outlier_seed,
        )
        .map_err(|e| in_file(path, &e))?;
        if !args.json {
            println!(
                "{}: {} one-frame outliers, {} caught; largest joint move toward them {:.3} rad \
                 with the outlier check, {:.3} rad without; {} sustained pinches compared, closed \
                 at most {} frame(s) later with the check; {} clean frame(s) caught",
                path.display(),
                study.outliers,
                study.outlier_frames_caught,
                study.toward_outliers_rad,
                study.toward_outliers_unchecked_rad,
                study.pinches_compared,
                study.closure_delay_max_frames,
                study.clean_frames_caught,
            );
        }
        outputs.push(serde_json::json!({ "input": path.display().to_string(), "study": study }));
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&outputs)?);
    }
    Ok(())
}

/// `pomdar eval --commands TOPIC`: another retargeter's recorded commands, per recording.
fn eval_commands(
    args: &EvalArgs,
    config: &station::StationConfig,
    topic: &str,
) -> anyhow::Result<()> {
    let files = readable_mcap_files(&args.inputs)?;
    let mut outputs = Vec::new();
    for path in &files {
        let reader = TrialReader::open(path)?;
        let output = evaluate_commands(&reader, config, HandModel::orca_v1_right(), topic)
            .map_err(|e| in_file(path, &e))?;
        if !args.json {
            println!("{}", external_table(&output));
        }
        outputs.push(output);
    }
    if args.json {
        let json = match &outputs[..] {
            [one] => serde_json::to_string_pretty(one)?,
            all => serde_json::to_string_pretty(all)?,
        };
        println!("{json}");
    }
    Ok(())
}

/// `pomdar eval --profile-scales S,…`: the retargeter alone under each scale, per recording.
fn eval_profile_scales(args: &EvalArgs, config: &station::StationConfig) -> anyhow::Result<()> {
    if let Some(bad) = args
        .profile_scales
        .iter()
        .find(|s| !(s.is_finite() && **s > 0.0))
    {
        anyhow::bail!("--profile-scales: {bad} is not a positive scale");
    }
    let model = HandModel::orca_v1_right();
    let mut outputs = Vec::new();
    for path in &readable_mcap_files(&args.inputs)? {
        let reader = TrialReader::open(path)?;
        let rows = profile_scales(&reader, config, &model, &args.profile_scales)
            .map_err(|e| in_file(path, &e))?;
        let input = path.display().to_string();
        if !args.json {
            println!("{}", profile_scales_table(&input, &rows));
        }
        outputs.push(serde_json::json!({ "input": input, "profile_scales": rows }));
    }
    if args.json {
        let json = match &outputs[..] {
            [one] => serde_json::to_string_pretty(one)?,
            all => serde_json::to_string_pretty(all)?,
        };
        println!("{json}");
    }
    Ok(())
}

/// An evaluation error naming its recording (once: some errors name it already).
fn in_file(path: &std::path::Path, error: &crate::eval::EvalError) -> anyhow::Error {
    let text = error.to_string();
    let name = path.display().to_string();
    if text.starts_with(&name) {
        anyhow::anyhow!("{text}")
    } else {
        anyhow::anyhow!("{name}: {text}")
    }
}
