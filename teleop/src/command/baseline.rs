//! `pomdar baseline`: the human baseline table from recorded human trials.

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use scoring::{
    BaselineTable, FileProblem, HUMAN_EMBODIMENT, TaskCatalog, TrialRecord, compute_baseline,
};

use super::score::EXIT_SOME_REJECTED;
use crate::atomic_file::write_atomically;
use crate::score::load_trial::load_trial_log;
use crate::score::parallel_files::{process_files, progress_style};
use crate::score::score_inputs::ScoringInputs;
use crate::score::score_inputs::reason;
use crate::score::trial_files::collect_trial_files;

/// `pomdar baseline` options.
#[derive(Debug, Args)]
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
    /// Replace an existing --out file.
    #[arg(long)]
    pub overwrite: bool,
}

fn table_text(table: &BaselineTable, catalog: &TaskCatalog) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "task  name              trials   mean s    std s");
    for task in &catalog.tasks {
        match table.get(&task.id) {
            Some(b) => {
                let _ = writeln!(
                    out,
                    "{:<5} {:<16} {:>7} {:>8.3} {:>8}",
                    task.id,
                    task.name,
                    b.n,
                    b.mean_s,
                    b.std_s.map_or("–".to_string(), |s| format!("{s:.3}"))
                );
            }
            None => {
                let _ = writeln!(
                    out,
                    "{:<5} {:<16}       0   (no usable human trial)",
                    task.id, task.name
                );
            }
        }
    }
    out
}

/// `pomdar baseline`.
pub fn baseline(args: BaselineArgs) -> anyhow::Result<ExitCode> {
    let inputs = ScoringInputs::load(args.catalog.as_deref(), args.rules.as_deref(), None)?;
    if args.out.exists() && !args.overwrite {
        anyhow::bail!(
            "{} exists: give --overwrite to replace it",
            args.out.display()
        );
    }
    let found = collect_trial_files(&args.paths);
    for s in &found.skipped {
        eprintln!("note: skipped {}: {}", s.file, s.reason);
    }
    if found.files.is_empty() && found.problems.is_empty() {
        anyhow::bail!("no .mcap trial files found");
    }
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
    let users: BTreeSet<&str> = records
        .iter()
        .filter(|r| r.embodiment == HUMAN_EMBODIMENT && !r.practice)
        .filter_map(|r| r.user.as_deref())
        .collect();
    let provisional = compute_baseline(&records, &inputs.catalog, &inputs.rules, "");
    let used: u32 = provisional.table.tasks.iter().map(|t| t.n).sum();
    let mut source = args
        .source
        .clone()
        .map_or(String::new(), |s| format!("{s}; "));
    let _ = write!(
        source,
        "pomdar baseline over {used} recorded human trials (users: {})",
        if users.is_empty() {
            "not recorded".to_string()
        } else {
            users.into_iter().collect::<Vec<_>>().join(", ")
        }
    );
    let result = compute_baseline(&records, &inputs.catalog, &inputs.rules, &source);

    print!("{}", table_text(&result.table, &inputs.catalog));
    for l in &result.left_out {
        eprintln!("note: not averaged {}: {}", l.file, l.reason);
    }
    for r in &result.refused {
        eprintln!("error: refused {}: {}", r.file, r.reason);
    }
    for r in &rejected {
        eprintln!("error: {}: {}", r.file, r.reason);
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
    Ok(if rejected.is_empty() && result.refused.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_SOME_REJECTED)
    })
}
