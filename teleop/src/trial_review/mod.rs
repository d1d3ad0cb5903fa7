//! A trial's review from its log: the log read into [`review::TrialInput`] (`read`), the pure
//! review, and its files (`TRIAL.review.png`, `.svg`, `.json`) written beside the log or into
//! a directory. `pomdar review` and the operator console (after each trial) both go through
//! [`review_trial_file`].

mod read;

use std::path::{Path, PathBuf};

use retarget::{HandModel, KeypointLayout};
use review::{FeedbackSettings, ReviewContext, ReviewError, TrialReview, WorkspaceLimits};
use station::StationConfig;

use crate::atomic_file::{AtomicWriteError, write_atomically};
use crate::mcap_log::{LogError, TrialReader};

pub use read::read_trial_input;

/// A trial that could not be reviewed, or its files not written.
#[derive(Debug, thiserror::Error)]
pub enum TrialReviewError {
    /// The log could not be read.
    #[error(transparent)]
    Log(#[from] LogError),
    /// The trial could not be reviewed.
    #[error(transparent)]
    Review(#[from] ReviewError),
    /// A file could not be written.
    #[error(transparent)]
    Write(#[from] AtomicWriteError),
}

/// What a review wrote.
#[derive(Debug, Clone)]
pub struct ReviewFiles {
    /// The facts and feedback.
    pub review: TrialReview,
    /// The figure, PNG.
    pub png: PathBuf,
    /// The figure, SVG.
    pub svg: PathBuf,
    /// The facts, JSON.
    pub json: PathBuf,
}

/// [`review_trial_file`] on a thread of its own at the lowest CPU priority (nice 19 where the
/// system allows it), waited for: the operator console reviews each finished trial while its
/// station, glove and robot nodes keep running beside it, and they must not wait for the CPU.
pub fn review_trial_file_in_background(
    path: &Path,
    config: &StationConfig,
    settings: &FeedbackSettings,
    out: Option<&Path>,
) -> Result<ReviewFiles, TrialReviewError> {
    std::thread::scope(|scope| {
        let worker = scope.spawn(|| {
            lowest_cpu_priority();
            review_trial_file(path, config, settings, out)
        });
        match worker.join() {
            Ok(result) => result,
            Err(panic) => std::panic::resume_unwind(panic),
        }
    })
}

/// This thread at nice 19 (Linux: a thread's own priority); left as it is where refused.
fn lowest_cpu_priority() {
    let me = rustix::thread::gettid();
    rustix::process::setpriority_process(Some(me), 19).ok();
}

/// Review the trial log at `path` recorded with `config`, and write `NAME.review.png`, `.svg`
/// and `.json` into `out` (default: beside the log), each atomically.
pub fn review_trial_file(
    path: &Path,
    config: &StationConfig,
    settings: &FeedbackSettings,
    out: Option<&Path>,
) -> Result<ReviewFiles, TrialReviewError> {
    let reader = TrialReader::open(path)?;
    let input = read_trial_input(&reader, config)?;
    let model = HandModel::orca_v1_right();
    let layout = input
        .metadata
        .get("layout")
        .and_then(|l| serde_json::from_value::<KeypointLayout>(serde_json::json!(l)).ok())
        .unwrap_or(config.retarget.layout);
    let arm = &config.arm;
    let context = ReviewContext {
        model: &model,
        joint_name_prefix: config.output.joint_name_prefix.clone(),
        layout,
        workspace: config.drives_robot().then_some(WorkspaceLimits {
            min_m: arm.workspace_min_m,
            max_m: arm.workspace_max_m,
        }),
        hold_timeout_ms: Some(config.watchdog.hold_timeout_ms as f64),
        settings,
    };
    let (facts, series) = review::review(&input, &context)?;
    let figure =
        scoring::plot::review_figure(&review::review_chart(&facts, &series)).map_err(|e| {
            ReviewError::Figure {
                file: path.display().to_string(),
                reason: e.to_string(),
            }
        })?;
    let stem = path
        .file_stem()
        .map_or_else(|| "trial".into(), |s| s.to_string_lossy().into_owned());
    let dir = out.map_or_else(
        || {
            path.parent()
                .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
        },
        Path::to_path_buf,
    );
    let file = |ext: &str| dir.join(format!("{stem}.review.{ext}"));
    let (png, svg, json) = (file("png"), file("svg"), file("json"));
    write_atomically(&png, &figure.png)?;
    write_atomically(&svg, figure.svg.as_bytes())?;
    let text = serde_json::to_string_pretty(&facts).unwrap_or_default() + "\n";
    write_atomically(&json, text.as_bytes())?;
    Ok(ReviewFiles {
        review: facts,
        png,
        svg,
        json,
    })
}
