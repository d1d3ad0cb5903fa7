//! `pomdar review`: one figure and a short JSON per trial log, and the feedback sentences
//! (the review is in the `review` crate, the files in [`crate::trial_review`]).

use std::path::PathBuf;

use anyhow::Context as _;
use clap::Args;
use review::FeedbackSettings;

use crate::station_driver::setup::load_station_config;
use crate::trial_review::review_trial_file;

/// What happened in a trial, for the operator: one figure and a short JSON per log, and
/// feedback sentences.
///
/// The figure (NAME.review.png and .svg, beside the log or in --out) shows on one time
/// axis from the trial's start to its stop: the station's drive state (engaged, held on a
/// stalled glove with the glove's gap, disengaged), the arm's clutch and refused steps,
/// the human's pinches (green: the robot closed it, under 15 mm; red: it did not); the
/// progress marks and drops; the glove's rate; the input age with the hold timeout and
/// the rejected frames; the thumb–finger distances, human (dashed) and robot; and, when
/// the hand's measured state was logged, the tracking error per digit. NAME.review.json
/// holds the same facts and the feedback: short sentences said only past a threshold
/// ("held 2× (glove gaps 180–420 ms)", "index pinch did not close in 4 of 6 attempts
/// (robot 18 mm apart)", "wrist at its limit 22 % of the time", "2.4 s without progress
/// before the drop at 9.1 s"), none for a clean trial; the thresholds are README's table
/// (--feedback FILE overrides them). The operator console does the same after each trial.
///
/// Examples:
///   pomdar review sessions/alice/orca_full/G4/G4-t03.mcap
///   pomdar review sessions/alice/orca_full/G4/*.mcap --out review/
///   pomdar review run.mcap --json | jq .feedback
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct ReviewArgs {
    /// Trial logs (MCAP) the station recorded.
    #[arg(value_name = "TRIAL", required = true)]
    pub trials: Vec<PathBuf>,
    /// Write each NAME.review.png, .svg and .json here (created if needed) instead of beside
    /// its log.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Station configuration the logs were recorded with: the topics, the hold timeout and
    /// the arm's workspace box (default: the built-in ETH lab preset).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// The feedback's thresholds (TOML with any of the keys in README, "Reviewing a trial";
    /// default: the built-in values).
    #[arg(long, value_name = "FILE")]
    pub feedback: Option<PathBuf>,
    /// Print each review's JSON on stdout instead of its feedback lines.
    #[arg(long)]
    pub json: bool,
}

/// `pomdar review`.
pub fn review(args: ReviewArgs) -> anyhow::Result<()> {
    let config = load_station_config(args.config.as_deref(), None)?;
    let settings = match &args.feedback {
        Some(path) => {
            let text = std::fs::read_to_string(path)
                .with_context(|| format!("cannot read {}", path.display()))?;
            toml::from_str::<FeedbackSettings>(&text)
                .with_context(|| format!("{}: invalid feedback settings", path.display()))?
        }
        None => FeedbackSettings::default(),
    };
    if let Some(dir) = &args.out {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    let mut failed = 0;
    for trial in &args.trials {
        match review_trial_file(trial, &config, &settings, args.out.as_deref()) {
            Ok(files) if args.json => {
                println!("{}", serde_json::to_string(&files.review)?);
            }
            Ok(files) => {
                println!("{}: {}", trial.display(), headline(&files.review));
                for feedback in &files.review.feedback {
                    println!("  - {}", feedback.text);
                }
                for note in &files.review.notes {
                    println!("  note: {note}");
                }
                eprintln!("wrote {}", files.png.display());
            }
            Err(e) => {
                failed += 1;
                eprintln!("error: {e}");
            }
        }
    }
    if failed > 0 {
        anyhow::bail!(
            "{failed} of {} trials could not be reviewed",
            args.trials.len()
        );
    }
    Ok(())
}

/// `12.4 s, stopped, progress 6, 2 feedback` / `…, nothing to say`.
fn headline(review: &review::TrialReview) -> String {
    let progress = review
        .progress
        .iter()
        .rev()
        .find_map(|m| m.value)
        .map_or("no progress".to_string(), |v| format!("progress {v}"));
    let said = match review.feedback.len() {
        0 => "nothing to say".to_string(),
        n => format!("{n} feedback"),
    };
    format!(
        "{:.1} s, {}, {progress}, {said}",
        review.duration_s, review.ending
    )
}
