//! What a benchmark run leaves in its directory, and how shards' directories are merged:
//!
//! - `items/EMBODIMENT__TASK.json`: one per item (practice, chosen strategy, recorded trials),
//!   written as each item finishes, so a shard's directory is its whole result;
//! - the POMDAR report `pomdar score` writes (report.md, scores.csv, overall.csv, trials.csv,
//!   scores.json, the radar and score-vs-DoF figures), from the recorded trials of every item;
//! - `strategies.md` / `.json`: the strategy chosen per task and embodiment;
//! - `findings.md` / `.json`: the paper's findings, each held or not, and why.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use practice::{Evidence, Finding, Grip, check_findings};
use scoring::{ScoreReport, TrialScore};

use super::error::BenchError;
use super::item::{ItemOutcome, score};
use crate::atomic_file::write_atomically;
use crate::score::report_files::write_report_files;
use crate::score::score_inputs::ScoringInputs;

/// The folder of the item files.
pub const ITEMS_DIR: &str = "items";

/// Writes `outcome` to `out/items/`.
pub fn write_item(out: &Path, outcome: &ItemOutcome) -> Result<(), BenchError> {
    let path = out.join(ITEMS_DIR).join(format!(
        "{}__{}.json",
        outcome.item.embodiment, outcome.item.task
    ));
    let text = serde_json::to_string_pretty(outcome).unwrap_or_default();
    write(&path, text.as_bytes())
}

/// Writes `bytes` to `path` atomically, its folder created first.
pub fn write(path: &Path, bytes: &[u8]) -> Result<(), BenchError> {
    let failed = |reason: String| BenchError::Write {
        path: path.to_path_buf(),
        reason,
    };
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| failed(e.to_string()))?;
    }
    write_atomically(path, bytes).map_err(|e| failed(e.to_string()))
}

/// Reads a JSON file this command wrote.
pub fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, BenchError> {
    let text = std::fs::read_to_string(path).map_err(|source| BenchError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|e| BenchError::Item {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })
}

/// Every item file in `dirs` (shards' output directories), sorted by embodiment and task;
/// an item found twice is an error naming both files.
pub fn read_items(dirs: &[PathBuf]) -> Result<Vec<ItemOutcome>, BenchError> {
    let mut found: Vec<(PathBuf, ItemOutcome)> = Vec::new();
    for dir in dirs {
        let items = dir.join(ITEMS_DIR);
        let entries = std::fs::read_dir(&items).map_err(|source| BenchError::Read {
            path: items.clone(),
            source,
        })?;
        let mut paths: Vec<PathBuf> = entries
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "json"))
            .collect();
        paths.sort();
        for path in paths {
            let outcome: ItemOutcome = read_json(&path)?;
            if let Some((other, _)) = found.iter().find(|(_, o)| same_item(o, &outcome)) {
                return Err(BenchError::Item {
                    path,
                    reason: format!("the same item is also in {}", other.display()),
                });
            }
            found.push((path, outcome));
        }
    }
    let mut items: Vec<ItemOutcome> = found.into_iter().map(|(_, o)| o).collect();
    items.sort_by_key(|o| o.item.index);
    Ok(items)
}

fn same_item(a: &ItemOutcome, b: &ItemOutcome) -> bool {
    a.item.embodiment == b.item.embodiment && a.item.task == b.item.task
}

/// Every recorded run of `items`, scored.
pub fn recorded_scores(
    items: &[ItemOutcome],
    scoring: &ScoringInputs,
) -> Result<Vec<TrialScore>, BenchError> {
    let mut scores = Vec::new();
    for outcome in items {
        for (k, run) in outcome.recorded.iter().enumerate() {
            let name = match &run.log {
                Some(path) => path.display().to_string(),
                None => format!("run_{:02}", k + 1),
            };
            let mut scored = score(scoring, &run.trial, &outcome.item, &name)?;
            if let Some(path) = &run.log {
                scored.file = path.display().to_string();
            }
            scores.push(scored);
        }
    }
    Ok(scores)
}

/// What the report's writing produced.
pub struct BenchReport {
    /// The POMDAR report.
    pub report: ScoreReport,
    /// The findings.
    pub findings: Vec<Finding>,
    /// The figures that could not be drawn.
    pub figure_errors: Vec<String>,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// Writes the report, the strategies and the findings of `items` into `out`; `abduction`
/// names the embodiments with abduction.
pub fn write_bench_report(
    out: &Path,
    items: &[ItemOutcome],
    scoring: &ScoringInputs,
    abduction: &BTreeSet<String>,
    header: &str,
) -> Result<BenchReport, BenchError> {
    let scores = recorded_scores(items, scoring)?;
    let evidence = Evidence::new(&scores, &scoring.catalog, abduction);
    let findings = check_findings(&evidence);
    let mut report = scoring.report(scores, Vec::new(), Vec::new());
    let written = write_report_files(out, &mut report)
        .map_err(|e| BenchError::Setup(format!("the report in {}: {e}", out.display())))?;
    let mut files = written.files;
    for (name, text) in [
        ("strategies.md", strategies_markdown(header, items)),
        ("findings.md", findings_markdown(header, &findings)),
    ] {
        let path = out.join(name);
        write(&path, text.as_bytes())?;
        files.push(path);
    }
    for (name, json) in [
        ("strategies.json", strategies_json(items)),
        (
            "findings.json",
            serde_json::to_value(&findings).unwrap_or_default(),
        ),
    ] {
        let path = out.join(name);
        let text = serde_json::to_string_pretty(&json).unwrap_or_default();
        write(&path, text.as_bytes())?;
        files.push(path);
    }
    Ok(BenchReport {
        report,
        findings,
        figure_errors: written.figure_errors,
        files,
    })
}

fn grip_name(grip: Grip) -> String {
    match grip {
        Grip::AsScripted => "as scripted".into(),
        Grip::Pose(pose) => serde_json::to_value(pose)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default(),
    }
}

fn strategies_markdown(header: &str, items: &[ItemOutcome]) -> String {
    let mut text = format!(
        "# Strategies chosen by programmed practice\n\n{header}\n\n\
         | embodiment | task | grip | closure × | time × | reach × | approach turn | start offset (mm) | practice trials | best mean practice score |\n\
         |---|---|---|---|---|---|---|---|---|---|\n"
    );
    for o in items {
        let s = &o.strategy;
        text.push_str(&format!(
            "| {} | {} | {} | {:.2} | {:.2} | {:.2} | {:+.1}° | {:+.1}, {:+.1}, {:+.1} | {} | {:.3} |\n",
            o.item.embodiment,
            o.item.task,
            grip_name(s.grip),
            s.closure_scale,
            s.time_scale,
            s.reach_scale,
            s.approach_yaw_deg,
            s.start_offset_mm[0],
            s.start_offset_mm[1],
            s.start_offset_mm[2],
            o.practice.len(),
            o.practice_score
        ));
    }
    text
}

fn strategies_json(items: &[ItemOutcome]) -> serde_json::Value {
    let list: Vec<serde_json::Value> = items
        .iter()
        .map(|o| {
            serde_json::json!({
                "embodiment": o.item.embodiment,
                "task": o.item.task,
                "strategy": o.strategy,
                "practice_trials": o.practice.len(),
                "practice_score": o.practice_score,
            })
        })
        .collect();
    serde_json::Value::Array(list)
}

fn findings_markdown(header: &str, findings: &[Finding]) -> String {
    let mut text = format!(
        "# The paper's findings, checked in simulation\n\n{header}\n\n| finding | the paper | here | why |\n|---|---|---|---|\n"
    );
    for f in findings {
        text.push_str(&format!(
            "| {} | {} | **{}** | {} |\n",
            f.id,
            f.claim,
            f.verdict.word(),
            f.why
        ));
    }
    text
}
