//! The trial console's report files: each trial's review written into the session's
//! `review/` directory (and its feedback said), and the session's report with an index of its
//! trials, worst first, once the plan is complete.

use std::path::{Path, PathBuf};

use station::StationConfig;

use super::manifest::TrialStatus;
use super::session_error::SessionError;
use super::trial_flow::TrialFlow;
use crate::atomic_file::write_atomically;
use crate::score::report_files::write_report_files;
use crate::score::score_inputs::ScoringInputs;
use crate::trial_review::review_trial_file_in_background;

/// Where the console writes each trial's review, in the session directory.
const REVIEW_DIR: &str = "review";

/// The session index appended to the report: every scored trial, worst first (lowest score,
/// or correctness without a baseline; then more feedback), with its feedback (count and
/// sentences) and a link to its review figure.
fn review_index(dir: &Path, scores: &[scoring::TrialScore]) -> String {
    let mut rows: Vec<(f64, usize, String)> = scores
        .iter()
        .map(|score| {
            let stem = Path::new(&score.file)
                .file_stem()
                .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
            let json = dir.join(REVIEW_DIR).join(format!("{stem}.review.json"));
            let said: Option<Vec<String>> = std::fs::read_to_string(&json)
                .ok()
                .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
                .and_then(|v| {
                    let list = v["feedback"].as_array()?;
                    Some(list.iter().filter_map(|f| f["text"].as_str()).map(str::to_string).collect())
                });
            let value = score.score.unwrap_or(score.correctness);
            let feedback = match &said {
                None => "no review".to_string(),
                Some(s) if s.is_empty() => "0".to_string(),
                Some(s) => format!("{}: {}", s.len(), s.join("; ")),
            };
            let row = format!(
                "| {stem} | {value:.3} | {feedback} | [figure](../{REVIEW_DIR}/{stem}.review.png) |\n"
            );
            (value, said.map_or(0, |s| s.len()), row)
        })
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
    let mut text = String::from(
        "\n## Trials, worst first\n\n| trial | score | feedback | review |\n|---|---|---|---|\n",
    );
    for (_, _, row) in rows {
        text.push_str(&row);
    }
    text
}

/// Scores the session's counted trials and writes the report into `DIR/report`.
pub(super) fn write_session_report(
    dir: &Path,
    flow: &TrialFlow,
    inputs: &ScoringInputs,
) -> Result<PathBuf, SessionError> {
    let mut scores = Vec::new();
    let mut rejected = Vec::new();
    for trial in flow
        .manifest
        .trials
        .iter()
        .filter(|t| t.status == TrialStatus::Scored)
    {
        let path = dir.join(&trial.file);
        match inputs.score_file(&path) {
            Ok(score) => scores.push(score),
            Err(reason) => rejected.push(scoring::FileProblem {
                file: path.display().to_string(),
                reason: reason.to_string(),
            }),
        }
    }
    let index = review_index(dir, &scores);
    let mut report = inputs.report(scores, rejected, Vec::new());
    let out = dir.join("report");
    write_report_files(&out, &mut report)?;
    let markdown = out.join("report.md");
    let mut text =
        std::fs::read_to_string(&markdown).map_err(|source| SessionError::ReadReport {
            path: markdown.clone(),
            source,
        })?;
    text.push_str(&index);
    write_atomically(&markdown, text.as_bytes())?;
    Ok(markdown)
}

/// The trial's review written into the session's `review/` directory, and what the console
/// says of it: its feedback sentences (none for a clean trial), or why it has no review.
pub(super) fn review_lines(path: &Path, dir: &Path, config: &StationConfig) -> Vec<String> {
    let settings = review::FeedbackSettings::default();
    let out = dir.join(REVIEW_DIR);
    if let Err(e) = std::fs::create_dir_all(&out) {
        return vec![format!(
            "warning: no review: cannot create {}: {e}",
            out.display()
        )];
    }
    match review_trial_file_in_background(path, config, &settings, Some(&out)) {
        Ok(files) => files
            .review
            .feedback
            .iter()
            .map(|f| format!("  feedback: {}", f.text))
            .collect(),
        Err(e) => vec![format!("warning: no review: {e}")],
    }
}
