//! `pomdar score`: score trial logs, print the table, write the reports; with `--compare
//! FIELD` the trials' groups by a metadata entry side by side instead (the source ablation).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::Args;
use scoring::{FileProblem, ScoreReport, TrialScore, compare_by, render_compare_terminal};

use crate::score::compare_files::write_compare_files;
use crate::score::parallel_files::{process_files, progress_style};
use crate::score::report_files::write_report_files;
use crate::score::score_inputs::ScoringFileArgs;
use crate::score::trial_files::{EXIT_SOME_REJECTED, collect_trial_files};

/// Score trial logs the POMDAR way: 0.8 · correctness + 0.2 · speed, per trial, task and
/// embodiment.
///
/// Reads each trial's pomdar_trial metadata (task, embodiment, practice, user, ...) and its
/// events on /pomdar/trial_events, through the MCAP summary (only the chunks holding events
/// are decompressed). Per trial: time = stop − start (aborted: abort − start); correctness
/// from the progress events per the task's kind (notches or curves passed / total,
/// degrees / 360, millimetres / 200 for H4 and H5, grasp level 0 / 0.5 / 1, a drop = 0.5);
/// speed = baseline time / trial time (unbounded above). Aborted or timed-out trials follow
/// the rules file (default: correctness reached, speed term 0). Practice trials are shown
/// but never averaged. Per task × embodiment: mean ± sample std over recorded trials; per
/// embodiment: the overall score as the mean over attempted tasks and as the mean over all
/// 18 with missing tasks = 0, with the embodiment's DoF.
///
/// Without --baseline, or for a task the baseline lacks, there is no score, only
/// correctness, and every report says so; a baseline marked example = true is flagged in
/// every report. A file that cannot be scored (not MCAP, truncated, no pomdar_trial record,
/// missing start or stop, events out of order, unknown task, a progress value the task does
/// not allow, ...) is named with its reason on stderr and in the reports; the other files
/// are still scored. Interrupted recordings (*.mcap.part) are skipped with a note.
///
/// Prints the table on stdout (or the JSON report with --json); progress on stderr for
/// large sets. Exit status: 0 every file scored; 3 some files rejected (reports still
/// written); 1 the run failed (bad catalog, rules or baseline file, no trial files, a
/// report or figure could not be written).
///
/// --compare FIELD puts groups of trials side by side instead (the source ablation: the
/// same station, controller and robot with keypoints from Rokoko gloves or from Apple
/// Vision Pro): the groups are the values of the trials' pomdar_trial metadata entry FIELD
/// (keypoint_source, user, station_version, ...; trials without it form "(missing)", and
/// the report says how many). Per task × embodiment × group: n and mean ± sample std of
/// correctness, time and score (score only with a baseline), over the same recorded
/// trials and scores as the report; per group the difference from the reference group
/// (the first value in sorted order, or --compare-reference VALUE) with Welch's 95 %
/// interval (none when a group has fewer than 2 trials there). With --out it writes
/// compare.md, compare.csv, compare.json and the grouped-bar figures compare_score and
/// compare_correctness (.svg, .png) instead of the report's files. Fewer than two groups,
/// or a reference that is not a group, stops the run (status 1).
///
/// Examples:
///   pomdar score trials/ --baseline baselines/eth_2026.toml
///   pomdar score trials/orca_full trials/orca_5 --baseline baselines/eth_2026.toml --out report/
///   pomdar score trials/ --rules launch_configs/scoring/default_rules.toml --json > scores.json
///   pomdar score trials/ --baseline baselines/eth_2026.toml --compare keypoint_source --out reports/ablation/
///   pomdar score trials/ --baseline baselines/eth_2026.toml --compare keypoint_source --compare-reference rokoko --json
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct ScoreArgs {
    /// Trial logs (.mcap), or directories searched recursively for them.
    #[arg(required = true, value_name = "PATHS")]
    pub paths: Vec<PathBuf>,
    /// The baseline, catalog and rules.
    #[command(flatten)]
    pub files: ScoringFileArgs,
    /// Write report.md, scores.csv, overall.csv, trials.csv, scores.json and the figures
    /// (radar_manipulation, radar_grasp, overall_vs_dof, overall_vs_dof_all_tasks; .svg and
    /// .png) into this directory; with --compare instead compare.md, compare.csv,
    /// compare.json and compare_score, compare_correctness (.svg and .png).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Print the report (or the comparison) as JSON on stdout instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Compare groups of trials side by side per task and embodiment, the groups being the
    /// values of this entry of the trials' pomdar_trial metadata (keypoint_source, user,
    /// station_version, ...; trials without it form the group "(missing)"). Per group: n and
    /// mean ± std of correctness, time and score; per group against the reference: the
    /// difference with Welch's 95 % interval. Example: --compare keypoint_source
    #[arg(long, value_name = "FIELD", value_parser = non_blank)]
    pub compare: Option<String>,
    /// The group the others are compared against (default: the first value in sorted order).
    #[arg(long, value_name = "VALUE", requires = "compare")]
    pub compare_reference: Option<String>,
}

/// A metadata entry name: not blank.
fn non_blank(text: &str) -> Result<String, String> {
    if text.trim().is_empty() {
        Err("a metadata entry name, e.g. keypoint_source".to_string())
    } else {
        Ok(text.trim().to_string())
    }
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
    print_file_problems(&report);
    let figure_errors = match &args.compare {
        Some(field) => output_comparison(&args, field, &report)?,
        None => output_report(&args, &mut report)?,
    };
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

/// The report's files (with --out) and the table or JSON; returns the figures not drawn.
fn output_report(args: &ScoreArgs, report: &mut ScoreReport) -> anyhow::Result<Vec<String>> {
    let mut figure_errors = Vec::new();
    if let Some(dir) = &args.out {
        let written = write_report_files(dir, report)?;
        figure_errors = written.figure_errors;
        eprintln!("wrote {} files to {}", written.files.len(), dir.display());
    }
    if args.json {
        println!("{}", report.to_json());
    } else {
        print!("{}", scoring::render_terminal(report));
    }
    Ok(figure_errors)
}

/// `--compare FIELD`: the comparison's files (with --out) and its table or JSON; returns the
/// figures not drawn.
fn output_comparison(
    args: &ScoreArgs,
    field: &str,
    report: &ScoreReport,
) -> anyhow::Result<Vec<String>> {
    let mut comparison = compare_by(report, field, args.compare_reference.as_deref())?;
    let mut figure_errors = Vec::new();
    if let Some(dir) = &args.out {
        let written = write_compare_files(dir, &mut comparison)?;
        figure_errors = written.figure_errors;
        eprintln!("wrote {} files to {}", written.files.len(), dir.display());
    }
    if args.json {
        println!("{}", comparison.to_json());
    } else {
        print!("{}", render_compare_terminal(&comparison));
    }
    Ok(figure_errors)
}

/// Skipped and rejected files, on stderr.
fn print_file_problems(report: &ScoreReport) {
    for s in &report.skipped {
        eprintln!("note: skipped {}: {}", s.file, s.reason);
    }
    for r in &report.rejected {
        eprintln!("error: {}: {}", r.file, r.reason);
    }
}

#[cfg(test)]
mod tests {
    use clap::{CommandFactory as _, Parser};

    use super::*;

    #[derive(Debug, Parser)]
    struct Cli {
        #[command(flatten)]
        args: ScoreArgs,
    }

    fn parse(extra: &[&str]) -> Result<ScoreArgs, clap::Error> {
        let argv = ["pomdar", "trials/"];
        Cli::try_parse_from(argv.iter().chain(extra)).map(|c| c.args)
    }

    #[test]
    fn compare_takes_a_field_and_an_optional_reference() {
        Cli::command().debug_assert();
        let args = parse(&[]).unwrap();
        assert_eq!((args.compare, args.compare_reference), (None, None));
        let args = parse(&["--compare", "keypoint_source", "--out", "cmp/"]).unwrap();
        assert_eq!(args.compare.as_deref(), Some("keypoint_source"));
        let args = parse(&["--compare", "user", "--compare-reference", "ann"]).unwrap();
        assert_eq!(args.compare_reference.as_deref(), Some("ann"));
        assert!(
            parse(&["--compare-reference", "ann"]).is_err(),
            "needs --compare"
        );
        assert!(parse(&["--compare", " "]).is_err(), "a blank field");
    }
}
