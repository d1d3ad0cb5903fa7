//! `pomdar baseline`: the human baseline table from recorded human trials.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use scoring::{
    FileProblem, HUMAN_EMBODIMENT, POMDAR_STUDY_TRIALS_PER_TASK, TrialRecord, baseline_study,
    compute_baseline, render_study_markdown, render_study_text,
};

use super::shared_args::mcap_files_under;
use crate::atomic_file::write_atomically;
use crate::score::load_trial::load_trial_log;
use crate::score::parallel_files::{process_files, progress_style};
use crate::score::score_inputs::ScoringInputs;
use crate::score::score_inputs::reason;
use crate::score::trial_files::EXIT_SOME_REJECTED;

/// Compute the human baseline table from recorded human trials (embodiment "human").
///
/// Per task: the mean and sample standard deviation of the trial time (start → stop) over
/// recorded trials that were stopped, not aborted, and within the rules' time limit;
/// practice, aborted and timed-out trials are listed and left out. Trials of another
/// embodiment are refused by name. Writes the table atomically as TOML (example = false,
/// a source note with --source, the trial count and the users; per task the number of
/// participants when every trial names its user), for `pomdar score --baseline`.
///
/// Prints the study: per task the trials, mean, std, min–max and participants, then per
/// participant × task (the trials' user; "(unnamed)" without one) the trial times in
/// trial-index order. Tasks with fewer than --min-trials trials (default 18: the POMDAR
/// study's 6 participants × 3 trials) are flagged FEW and warned about on stderr; the
/// table is still written and the exit status is unchanged. --report FILE also writes the
/// study as Markdown (atomically; an existing file needs --overwrite, like --out).
///
/// Exit status: 0 every file used or left out for a stated reason; 3 some files were
/// rejected or refused (the table is still written from the rest); 1 nothing usable, or
/// a file could not be read or written.
///
/// Examples:
///   pomdar baseline trials/human/ --source "ETH lab, 6 participants, Nov 2026" --out baselines/eth_2026.toml
///   pomdar baseline trials/human/ --out baselines/pilot.toml --min-trials 6 --report baselines/pilot_study.md
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct BaselineArgs {
    /// Human trial logs (.mcap, embodiment "human"), or directories searched recursively.
    #[arg(required = true, value_name = "TRIALS")]
    pub paths: Vec<PathBuf>,
    /// The baseline table to write (TOML).
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Where the trials come from (lab, participants, dates), written into the table's
    /// source note before the counts the command adds.
    #[arg(long, value_name = "TEXT")]
    pub source: Option<String>,
    /// Task catalog (TOML; default: the built-in 18 POMDAR tasks).
    #[arg(long, value_name = "FILE")]
    pub catalog: Option<PathBuf>,
    /// Scoring rules (TOML): their time limit leaves timed-out trials out of the baseline.
    #[arg(long, value_name = "FILE")]
    pub rules: Option<PathBuf>,
    /// Trials per task below which a task is flagged (a warning; the table is still
    /// written). Default: the POMDAR study's 6 participants × 3 trials.
    #[arg(long, value_name = "N", default_value_t = POMDAR_STUDY_TRIALS_PER_TASK, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub min_trials: u32,
    /// Also write the study report (Markdown): per task mean, std, min–max, participants and
    /// trials; per participant × task the trial times; the trials not averaged.
    #[arg(long, value_name = "FILE")]
    pub report: Option<PathBuf>,
    /// Replace an existing --out or --report file.
    #[arg(long)]
    pub overwrite: bool,
}

/// Refuses to replace an existing `path` without `--overwrite`.
fn check_writable(path: &Path, overwrite: bool) -> anyhow::Result<()> {
    if path.exists() && !overwrite {
        anyhow::bail!("{} exists: give --overwrite to replace it", path.display());
    }
    Ok(())
}

/// Refuses an --out or --report file that exists (without --overwrite), or one path for both.
fn check_outputs(args: &BaselineArgs) -> anyhow::Result<()> {
    check_writable(&args.out, args.overwrite)?;
    if let Some(report) = &args.report {
        if report == &args.out {
            anyhow::bail!(
                "--report and --out are the same file ({}): give two paths",
                report.display()
            );
        }
        check_writable(report, args.overwrite)?;
    }
    Ok(())
}

/// The trial files under `paths`, checked: the records and the files rejected.
fn read_records(
    paths: &[PathBuf],
    inputs: &ScoringInputs,
) -> anyhow::Result<(Vec<TrialRecord>, Vec<FileProblem>)> {
    let found = mcap_files_under(paths)?;
    let results = process_files(
        &found.files,
        |path| {
            let log = load_trial_log(path).map_err(|e| e.to_string())?;
            TrialRecord::from_log(&log, &inputs.catalog).map_err(reason)
        },
        progress_style(found.files.len()),
        "trial files read",
    );
    let mut rejected: Vec<FileProblem> = found.problems.clone();
    let mut records = Vec::new();
    for (path, result) in found.files.iter().zip(results) {
        match result {
            Ok(r) => records.push(r),
            Err(reason) => rejected.push(FileProblem {
                file: path.display().to_string(),
                reason,
            }),
        }
    }
    Ok((records, rejected))
}

/// `pomdar baseline`.
pub fn baseline(args: BaselineArgs) -> anyhow::Result<ExitCode> {
    let inputs = ScoringInputs::load(args.catalog.as_deref(), args.rules.as_deref(), None)?;
    check_outputs(&args)?;
    let (records, rejected) = read_records(&args.paths, &inputs)?;
    let mut result = compute_baseline(&records, &inputs.catalog, &inputs.rules, "");
    let used = result.used.len();
    result.table.header.source =
        crate::score::baseline_source::source_note(args.source.as_deref(), &records, used);
    let study = baseline_study(&result, &inputs.catalog, args.min_trials);

    print!("{}", render_study_text(&study));
    for l in &result.left_out {
        eprintln!("note: not averaged {}: {}", l.file, l.reason);
    }
    for r in &result.refused {
        eprintln!("error: refused {}: {}", r.file, r.reason);
    }
    for r in &rejected {
        eprintln!("error: {}: {}", r.file, r.reason);
    }
    for (task, summary) in study.below_minimum() {
        eprintln!(
            "warning: task {}: {} trials < --min-trials {}",
            task.id, summary.trials, args.min_trials
        );
    }
    if result.table.tasks.is_empty() {
        anyhow::bail!(
            "no usable human trial (embodiment \"{HUMAN_EMBODIMENT}\", recorded, stopped within the time limit): {} not written",
            args.out.display()
        );
    }
    write_atomically(&args.out, result.table.to_toml())?;
    eprintln!(
        "wrote {} ({} tasks from {used} trials; {} not averaged, {} refused, {} rejected)",
        args.out.display(),
        result.table.tasks.len(),
        result.left_out.len(),
        result.refused.len(),
        rejected.len()
    );
    if let Some(report) = &args.report {
        write_atomically(report, render_study_markdown(&study))?;
        eprintln!(
            "wrote {} (the study per participant × task)",
            report.display()
        );
    }
    Ok(if rejected.is_empty() && result.refused.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_SOME_REJECTED)
    })
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::*;

    #[derive(Debug, Parser)]
    struct Cli {
        #[command(flatten)]
        args: BaselineArgs,
    }

    fn parse(extra: &[&str]) -> Result<BaselineArgs, clap::Error> {
        let argv = ["pomdar", "trials/", "--out", "b.toml"];
        Cli::try_parse_from(argv.iter().chain(extra)).map(|c| c.args)
    }

    #[test]
    fn min_trials_defaults_to_the_pomdar_study_and_is_range_checked() {
        use clap::CommandFactory as _;
        Cli::command().debug_assert();
        let args = parse(&[]).unwrap();
        assert_eq!((args.min_trials, args.report), (18, None));
        let args = parse(&["--min-trials", "6", "--report", "study.md"]).unwrap();
        assert_eq!(args.min_trials, 6);
        assert_eq!(args.report, Some(PathBuf::from("study.md")));
        for bad in ["0", "1001", "-3", "six"] {
            assert!(parse(&["--min-trials", bad]).is_err(), "--min-trials {bad}");
        }
        assert!(parse(&["--min-trials", "1000"]).is_ok());
    }

    #[test]
    fn the_report_and_the_table_must_be_two_files_and_are_not_replaced_silently() {
        let dir = std::env::temp_dir().join(format!("pomdar-baseline-args-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("b.toml");
        let report = dir.join("study.md");
        let _ = std::fs::remove_file(&out);
        std::fs::write(&report, "old").unwrap();
        let mut args = parse(&["--report", report.to_str().unwrap()]).unwrap();
        args.out = out.clone();
        let refused = check_outputs(&args).unwrap_err().to_string();
        assert!(
            refused.contains("study.md exists: give --overwrite"),
            "{refused}"
        );
        args.overwrite = true;
        assert!(check_outputs(&args).is_ok());
        args.report = Some(out.clone());
        let same = check_outputs(&args).unwrap_err().to_string();
        assert!(
            same.contains("--report and --out are the same file"),
            "{same}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
