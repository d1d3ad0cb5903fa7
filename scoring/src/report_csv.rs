//! The report as CSV (RFC 4180: comma-separated, `"` quoting, `\n` line ends).
//!
//! Three tables: per task × embodiment (`scores.csv`), per embodiment (`overall.csv`) and per
//! trial (`trials.csv`). CSV has no place for a header note, so every row carries a `warning`
//! column: `no baseline: correctness only`, `EXAMPLE baseline`, or empty.

use std::fmt::Write as _;

use crate::report::ScoreReport;
use crate::stats::MeanStd;

/// One CSV field, quoted when it holds a comma, quote or line break.
fn field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

pub(crate) fn row(out: &mut String, fields: &[String]) {
    let line: Vec<String> = fields.iter().map(|f| field(f)).collect();
    let _ = writeln!(out, "{}", line.join(","));
}

fn num(v: Option<f64>) -> String {
    v.map_or(String::new(), |v| format!("{v}"))
}

fn mean(s: Option<MeanStd>) -> String {
    num(s.map(|s| s.mean))
}

fn std(s: Option<MeanStd>) -> String {
    num(s.and_then(|s| s.std))
}

fn warning(report: &ScoreReport, has_baseline: bool) -> String {
    let mut parts = Vec::new();
    if !has_baseline {
        parts.push("no baseline: correctness only");
    }
    if report.baseline.as_ref().is_some_and(|b| b.example) {
        parts.push("EXAMPLE baseline: not real scores");
    }
    parts.join("; ")
}

/// Per task × embodiment (`scores.csv`).
pub fn render_scores_csv(report: &ScoreReport) -> String {
    let mut out = String::new();
    row(
        &mut out,
        &[
            "task",
            "name",
            "embodiment",
            "counted",
            "practice",
            "excluded",
            "aborted",
            "timed_out",
            "score_mean",
            "score_std",
            "correctness_mean",
            "correctness_std",
            "time_mean_s",
            "time_std_s",
            "baseline_s",
            "warning",
        ]
        .map(String::from),
    );
    for e in &report.embodiments {
        for info in &report.catalog_tasks {
            let Some(t) = report.task_result(&info.id, &e.embodiment) else {
                continue;
            };
            row(
                &mut out,
                &[
                    t.task.clone(),
                    info.name.clone(),
                    t.embodiment.clone(),
                    t.counted.to_string(),
                    t.practice.to_string(),
                    t.excluded.to_string(),
                    t.aborted.to_string(),
                    t.timed_out.to_string(),
                    mean(t.score),
                    std(t.score),
                    mean(t.correctness),
                    std(t.correctness),
                    mean(t.time_s),
                    std(t.time_s),
                    num(info.baseline_s),
                    warning(report, t.has_baseline),
                ],
            );
        }
    }
    out
}

/// Per embodiment (`overall.csv`).
pub fn render_overall_csv(report: &ScoreReport) -> String {
    let mut out = String::new();
    row(
        &mut out,
        &[
            "embodiment",
            "dof",
            "tasks_attempted",
            "tasks_total",
            "trials",
            "overall_attempted",
            "overall_all_missing_zero",
            "overall_spread",
            "correctness_attempted",
            "correctness_all_missing_zero",
            "warning",
        ]
        .map(String::from),
    );
    for e in &report.embodiments {
        let mut warn = warning(report, e.tasks_without_baseline.is_empty());
        if !e.tasks_without_baseline.is_empty() {
            warn = format!(
                "{warn} ({}): overall score not computed",
                e.tasks_without_baseline.join(" ")
            );
        }
        row(
            &mut out,
            &[
                e.embodiment.clone(),
                e.dof.map_or(String::new(), |d| d.to_string()),
                e.tasks_attempted.to_string(),
                e.tasks_total.to_string(),
                e.trials.to_string(),
                num(e.overall_attempted),
                num(e.overall_all),
                num(e.overall_spread),
                num(e.correctness_attempted),
                num(e.correctness_all),
                warn,
            ],
        );
    }
    out
}

/// Per trial (`trials.csv`).
pub fn render_trials_csv(report: &ScoreReport) -> String {
    let mut out = String::new();
    row(
        &mut out,
        &[
            "file",
            "task",
            "embodiment",
            "user",
            "operator",
            "trial_index",
            "practice",
            "counted",
            "outcome",
            "time_s",
            "progress",
            "correctness",
            "speed",
            "score",
            "notes",
            "warning",
        ]
        .map(String::from),
    );
    for t in &report.trials {
        row(
            &mut out,
            &[
                t.file.clone(),
                t.task.clone(),
                t.embodiment.clone(),
                t.user.clone().unwrap_or_default(),
                t.operator.clone().unwrap_or_default(),
                t.trial_index.clone().unwrap_or_default(),
                t.practice.to_string(),
                t.counted.to_string(),
                t.outcome.name().to_string(),
                format!("{}", t.time_s),
                format!("{}", t.progress),
                format!("{}", t.correctness),
                num(t.speed),
                num(t.score),
                t.notes.join("; "),
                warning(report, t.score.is_some()),
            ],
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_with_commas_and_quotes_are_quoted() {
        assert_eq!(field("plain"), "plain");
        assert_eq!(field("a,b"), "\"a,b\"");
        assert_eq!(field("say \"hi\""), "\"say \"\"hi\"\"\"");
    }
}
