//! `pomdar study-report`: do the study's participants adopt the same strategy per task? The
//! hand motion of every recorded human trial, in 1.5 s segments, through a PCA; figures of the
//! segments on the first principal components coloured by task, the variance explained and
//! the per-task separation (silhouette), with a sentence saying what it means.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use study::{StrategyAnalysis, StrategySettings, TrialMotion, analyse, strategy_figure};

use super::shared_args::mcap_files_under;
use crate::atomic_file::write_atomically;
use crate::score::ScoreFileError;
use crate::score::parallel_files::{process_files, progress_style};
use crate::score::score_inputs::ScoringInputs;
use crate::score::trial_files::EXIT_SOME_REJECTED;
use crate::study_logs::{StudyTrial, read_study_trial};

/// The human study's strategy check: do participants do each task the same way?
///
/// Reads the recorded human trials (embodiment "human"; practice and aborted trials left
/// out) and cuts each trial's glove keypoints into 1.5 s segments. Each frame's keypoints
/// are expressed in the palm frame and divided by the participant's hand length (so hand
/// size, glove placement and where the hand is in the room do not count); a segment's
/// features are the mean and the standard deviation of those coordinates (the posture and
/// the movement). A PCA of the standardised features gives the first 3 principal
/// components. Writes to --out: strategy_pc1_pc2 and strategy_pc1_pc3 (.svg and .png: one
/// point per segment, coloured by task), report.md (variance explained, per-task
/// separation, the trial files used and left out) and strategy.json. The separation is
/// the silhouette of the segments' task labels on the kept components, read with Kaufman
/// & Rousseeuw's bands: > 0.70 strong, > 0.50 reasonable, > 0.25 weak, otherwise no
/// substantial structure. Exit status: 0 every file read; 3 some files could not be read
/// (the report is still written from the rest); 1 nothing to analyse (fewer than 2 tasks,
/// too few segments), or a file could not be written.
///
/// Example:
///   pomdar study-report sessions/ --out reports/study_strategy
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct StudyReportArgs {
    /// Human trial logs (.mcap, embodiment "human"), or directories searched recursively
    /// (e.g. the sessions directory of `pomdar study`).
    #[arg(required = true, value_name = "TRIALS")]
    pub paths: Vec<PathBuf>,
    /// The report's directory (created if needed): report.md, strategy.json and the figures.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Segment length, seconds (the POMDAR paper: 1.5).
    #[arg(long, value_name = "S", default_value_t = StrategySettings::default().segment_s)]
    pub segment: f64,
    /// Principal components kept (the figures show PC1–PC2 and PC1–PC3).
    #[arg(long, value_name = "N", default_value_t = StrategySettings::default().components)]
    pub components: usize,
    /// Task catalog (TOML; default: the built-in 18 POMDAR tasks).
    #[arg(long, value_name = "FILE")]
    pub catalog: Option<PathBuf>,
}

/// The trials read: motions to analyse, and what was left out or could not be read.
#[derive(Default)]
struct ReadTrials {
    motions: Vec<TrialMotion>,
    dropped_frames: usize,
    left_out: Vec<(PathBuf, String)>,
    rejected: Vec<(PathBuf, String)>,
}

fn read_trials(args: &StudyReportArgs, inputs: &ScoringInputs) -> anyhow::Result<ReadTrials> {
    let found = mcap_files_under(&args.paths)?;
    let results = process_files(
        &found.files,
        |path| read_study_trial(path, &inputs.catalog).map_err(|e| e.to_string()),
        progress_style(found.files.len()),
        "trial files read",
    );
    let mut read = ReadTrials {
        rejected: found
            .problems
            .iter()
            .map(|p| (PathBuf::from(&p.file), p.reason.clone()))
            .collect(),
        ..ReadTrials::default()
    };
    for (path, result) in found.files.iter().zip(results) {
        match result {
            Ok(StudyTrial::Used {
                motion,
                dropped_frames,
            }) => {
                read.dropped_frames += dropped_frames;
                read.motions.push(motion);
            }
            Ok(StudyTrial::LeftOut(reason)) => read.left_out.push((path.clone(), reason)),
            Err(reason) => read.rejected.push((path.clone(), reason)),
        }
    }
    Ok(read)
}

/// Writes the report's files into `--out`; their paths.
fn write_files(
    args: &StudyReportArgs,
    analysis: &StrategyAnalysis,
    read: &ReadTrials,
) -> anyhow::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    let mut write = |name: &str, bytes: &[u8]| -> Result<(), ScoreFileError> {
        let path = args.out.join(name);
        write_atomically(&path, bytes)?;
        written.push(path);
        Ok(())
    };
    let mut figures = Vec::new();
    for y_pc in 2..=analysis.components_kept.min(3) {
        let figure = strategy_figure(analysis, 1, y_pc)?;
        let stem = format!("strategy_pc1_pc{y_pc}");
        write(&format!("{stem}.svg"), figure.svg.as_bytes())?;
        write(&format!("{stem}.png"), &figure.png)?;
        figures.push(stem);
    }
    let mut markdown = study::report_markdown(analysis);
    for stem in &figures {
        markdown.push_str(&format!("\n![{stem}]({stem}.svg)\n"));
    }
    markdown.push_str(&files_section(read));
    write("report.md", markdown.as_bytes())?;
    write(
        "strategy.json",
        serde_json::to_string_pretty(analysis)?.as_bytes(),
    )?;
    Ok(written)
}

/// The report's list of the trial files left out or not read.
fn files_section(read: &ReadTrials) -> String {
    let mut out = format!(
        "\n## Trial files\n\n{} trials analysed; {} keypoint frames dropped (wrong size, non-finite, out of order).\n",
        read.motions.len(),
        read.dropped_frames
    );
    for (label, list) in [("Left out", &read.left_out), ("Not read", &read.rejected)] {
        if !list.is_empty() {
            out.push_str(&format!("\n{label}:\n\n"));
            for (path, reason) in list {
                out.push_str(&format!("- `{}`: {reason}\n", path.display()));
            }
        }
    }
    out
}

/// `pomdar study-report`.
pub fn study_report(args: StudyReportArgs) -> anyhow::Result<ExitCode> {
    let settings = StrategySettings {
        segment_s: args.segment,
        components: args.components,
        ..StrategySettings::default()
    };
    settings.validate()?;
    let inputs = ScoringInputs::load(args.catalog.as_deref(), None, None)?;
    let read = read_trials(&args, &inputs)?;
    for (path, reason) in &read.left_out {
        eprintln!("note: left out {}: {reason}", path.display());
    }
    for (path, reason) in &read.rejected {
        eprintln!("error: {}: {reason}", path.display());
    }
    let analysis = analyse(&read.motions, &settings)?;
    for skipped in &analysis.skipped {
        eprintln!("note: not analysed {skipped}");
    }
    let written = write_files(&args, &analysis, &read)?;
    println!("{}", analysis.sentence());
    let variance: Vec<String> = analysis
        .variance_explained
        .iter()
        .enumerate()
        .map(|(i, v)| format!("PC{} {:.1} %", i + 1, v * 100.0))
        .collect();
    println!(
        "{} segments of {} trials ({} participants); variance explained: {}",
        analysis.segments.len(),
        analysis.trials_used,
        analysis.participants,
        variance.join(", ")
    );
    for task in &analysis.per_task {
        println!(
            "  {:<5} {:>4} segments  {:>2} participants  silhouette {:>6.3}",
            task.task, task.segments, task.participants, task.mean_silhouette
        );
    }
    eprintln!("wrote {} files to {}", written.len(), args.out.display());
    Ok(if read.rejected.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_SOME_REJECTED)
    })
}
