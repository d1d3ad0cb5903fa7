//! `pomdar eval`'s other modes, per recording: one-frame outliers with the frame gate's
//! outlier check and without it (`--outlier-study`), another retargeter's recorded commands
//! (`--commands TOPIC`), and the retargeter alone under several profile scales
//! (`--profile-scales`); and an evaluation error named by its recording.

use std::path::{Path, PathBuf};

use retarget::HandModel;
use station::StationConfig;

use crate::eval::external::{evaluate_commands, external_table};
use crate::eval::outlier_study::outlier_study;
use crate::eval::profile_scales::{profile_scales, profile_scales_table};
use crate::mcap_log::TrialReader;

/// An evaluation mode failed.
#[derive(Debug, thiserror::Error)]
pub enum EvalModeError {
    /// A recording cannot be read.
    #[error(transparent)]
    Read(#[from] crate::mcap_log::LogError),
    /// A recording could not be evaluated (the message names it).
    #[error("{text}")]
    InFile {
        /// What went wrong, with the recording's name.
        text: String,
    },
    /// The JSON output could not be written.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
}

/// `pomdar eval --outlier-study`: per recording, what one-frame outliers do with the outlier
/// check and without it.
pub fn eval_outlier_study(
    files: &[PathBuf],
    config: &StationConfig,
    seed: u64,
    json: bool,
) -> Result<(), EvalModeError> {
    let mut outputs = Vec::new();
    for path in files {
        let reader = TrialReader::open(path)?;
        let study = outlier_study(&reader, config, &HandModel::orca_v1_right(), seed)
            .map_err(|e| in_file(path, &e))?;
        if !json {
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
    if json {
        println!("{}", serde_json::to_string_pretty(&outputs)?);
    }
    Ok(())
}

/// `pomdar eval --commands TOPIC`: another retargeter's recorded commands, per recording.
pub fn eval_commands(
    files: &[PathBuf],
    config: &StationConfig,
    topic: &str,
    json: bool,
) -> Result<(), EvalModeError> {
    let mut outputs = Vec::new();
    for path in files {
        let reader = TrialReader::open(path)?;
        let output = evaluate_commands(&reader, config, HandModel::orca_v1_right(), topic)
            .map_err(|e| in_file(path, &e))?;
        if !json {
            println!("{}", external_table(&output));
        }
        outputs.push(output);
    }
    if json {
        print_json(&outputs)?;
    }
    Ok(())
}

/// `pomdar eval --profile-scales S,…`: the retargeter alone under each scale, per recording.
pub fn eval_profile_scales(
    inputs: &[PathBuf],
    config: &StationConfig,
    scales: &[f64],
    json: bool,
) -> Result<(), EvalModeError> {
    let model = HandModel::orca_v1_right();
    let mut outputs = Vec::new();
    for path in inputs {
        let reader = TrialReader::open(path)?;
        let rows =
            profile_scales(&reader, config, &model, scales).map_err(|e| in_file(path, &e))?;
        let input = path.display().to_string();
        if !json {
            println!("{}", profile_scales_table(&input, &rows));
        }
        outputs.push(serde_json::json!({ "input": input, "profile_scales": rows }));
    }
    if json {
        print_json(&outputs)?;
    }
    Ok(())
}

/// One recording's output as itself, several as a list: what `--json` prints.
fn print_json<T: serde::Serialize>(outputs: &[T]) -> Result<(), serde_json::Error> {
    let json = match outputs {
        [one] => serde_json::to_string_pretty(one)?,
        all => serde_json::to_string_pretty(all)?,
    };
    println!("{json}");
    Ok(())
}

/// An evaluation error naming its recording (once: some errors name it already).
pub fn in_file(path: &Path, error: &crate::eval::EvalError) -> EvalModeError {
    let text = error.to_string();
    let name = path.display().to_string();
    EvalModeError::InFile {
        text: if text.starts_with(&name) {
            text
        } else {
            format!("{name}: {text}")
        },
    }
}
