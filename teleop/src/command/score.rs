//! `pomdar score`: score trial logs, print the table, write the reports.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::Args;
use scoring::{FileProblem, TrialScore};

use crate::score::parallel_files::{process_files, progress_style};
use crate::score::report_files::write_report_files;
use crate::score::score_inputs::ScoringFileArgs;
use crate::score::trial_files::collect_trial_files;

/// Exit status when the run finished but some trial files were rejected.
pub const EXIT_SOME_REJECTED: u8 = 3;

/// `pomdar score` options.
#[derive(Debug, Args)]
pub struct ScoreArgs {
    /// Trial logs (.mcap), or directories searched recursively for them.
    #[arg(required = true, value_name = "PATHS")]
    pub paths: Vec<PathBuf>,
    /// The baseline, catalog and rules.
    #[command(flatten)]
    pub files: ScoringFileArgs,
    /// Write report.md, scores.csv, overall.csv, trials.csv, scores.json and the figures
    /// (radar_manipulation, radar_grasp, overall_vs_dof, overall_vs_dof_all_tasks; .svg and
    /// .png) into this directory.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Print the report as JSON on stdout instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// `pomdar score`.
pub fn score(args: ScoreArgs) -> anyhow::Result<ExitCode> {
    let started = Instant::now();
    let inputs = args.files.load()?;
    let found = collect_trial_files(&args.paths);
    if found.files.is_empty() && found.problems.is_empty() {
        for s in &found.skipped {
            eprintln!("note: skipped {}: {}", s.file, s.reason);
        }
        anyhow::bail!(
            "no .mcap trial files in {}",
            args.paths
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    let results = process_files(
        &found.files,
        |path| inputs.score_file(path),
        progress_style(found.files.len()),
        "trial files scored",
    );
    let mut scores: Vec<TrialScore> = Vec::new();
    let mut rejected = found.problems.clone();
    for (path, result) in found.files.iter().zip(results) {
        match result {
            Ok(s) => scores.push(s),
            Err(reason) => rejected.push(FileProblem {
                file: path.display().to_string(),
                reason: reason.to_string(),
            }),
        }
    }
    let scored = scores.len();
    let mut report = inputs.report(scores, rejected, found.skipped);

    let mut figure_errors = Vec::new();
    if let Some(dir) = &args.out {
        let written = write_report_files(dir, &mut report)?;
        figure_errors = written.figure_errors;
        eprintln!("wrote {} files to {}", written.files.len(), dir.display());
    }
    if args.json {
        println!("{}", report.to_json());
    } else {
        print!("{}", scoring::render_terminal(&report));
    }
    for s in &report.skipped {
        eprintln!("note: skipped {}: {}", s.file, s.reason);
    }
    for r in &report.rejected {
        eprintln!("error: {}: {}", r.file, r.reason);
    }
    for e in &figure_errors {
        eprintln!("error: {e}");
    }
    eprintln!(
        "scored {scored} of {} trial files ({} rejected, {} skipped) in {:.2} s",
        scored + report.rejected.len(),
        report.rejected.len(),
        report.skipped.len(),
        started.elapsed().as_secs_f64()
    );
    Ok(if !figure_errors.is_empty() {
        ExitCode::FAILURE
    } else if !report.rejected.is_empty() {
        ExitCode::from(EXIT_SOME_REJECTED)
    } else {
        ExitCode::SUCCESS
    })
}
