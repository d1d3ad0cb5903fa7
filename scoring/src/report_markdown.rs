//! The report as Markdown (`report.md`).

use std::fmt::Write as _;

use crate::report::{ScoreReport, opt};
use crate::report_terminal::cell;

/// Escapes `|` so a value cannot break a table row.
pub(crate) fn md(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}

/// Renders `report` as Markdown; figures listed in [`ScoreReport::figures`] are linked
/// relative to the report.
pub fn render_markdown(report: &ScoreReport) -> String {
    let mut out = String::new();
    write_summary(&mut out, report);
    write_overall(&mut out, report);
    write_per_task(&mut out, report);
    write_figures(&mut out, report);
    write_unscored_files(&mut out, report);
    write_trials(&mut out, report);
    out
}

/// The title, the warnings, the inputs table and the notes.
fn write_summary(out: &mut String, report: &ScoreReport) {
    let practice = report.trials.iter().filter(|t| t.practice).count();
    let _ = writeln!(out, "# POMDAR scores\n");
    for warning in &report.warnings {
        let _ = writeln!(out, "> **WARNING:** {}\n", md(warning));
    }
    let _ = writeln!(out, "| | |\n|---|---|");
    let _ = writeln!(out, "| catalog | {} |", md(&report.catalog));
    let _ = writeln!(
        out,
        "| rules | {} ({}) |",
        md(&report.rules.description),
        md(&report.rules.origin)
    );
    let baseline = match &report.baseline {
        Some(b) => format!(
            "{}{} ({} tasks): {}",
            if b.example { "**EXAMPLE** " } else { "" },
            md(&b.origin),
            b.tasks.len(),
            md(&b.source)
        ),
        None => "none: correctness only".to_string(),
    };
    let _ = writeln!(out, "| baseline | {baseline} |");
    let _ = writeln!(
        out,
        "| trials | {} scored ({} counted, {practice} practice), {} rejected, {} skipped |",
        report.trials.len(),
        report.counted_trials(),
        report.rejected.len(),
        report.skipped.len()
    );
    for note in &report.notes {
        let _ = writeln!(out, "\n- {}", md(note));
    }
}

/// The overall scores per embodiment.
fn write_overall(out: &mut String, report: &ScoreReport) {
    let total = report.catalog_tasks.len();
    let _ = writeln!(out, "\n## Overall per embodiment\n");
    let _ = writeln!(
        out,
        "Mean of the per-task mean scores; ± is the spread (sample std) across tasks. \
         \"All {total}\" counts tasks not attempted as 0.\n"
    );
    let _ = writeln!(
        out,
        "| embodiment | DoF | tasks attempted | trials | overall (attempted) | overall (all {total}, missing = 0) | correctness (attempted) | correctness (all {total}) |"
    );
    let _ = writeln!(out, "|---|---:|---:|---:|---:|---:|---:|---:|");
    for e in &report.embodiments {
        let attempted = match (e.overall_attempted, e.overall_spread) {
            (Some(m), Some(s)) => format!("{m:.3} ± {s:.3}"),
            (Some(m), None) => format!("{m:.3}"),
            (None, _) => format!(
                "– (no baseline for {})",
                e.tasks_without_baseline.join(", ")
            ),
        };
        let _ = writeln!(
            out,
            "| {} | {} | {}/{} | {} | {attempted} | {} | {} | {} |",
            md(&e.embodiment),
            e.dof.map_or("?".to_string(), |d| d.to_string()),
            e.tasks_attempted,
            e.tasks_total,
            e.trials,
            opt(e.overall_all, 3),
            opt(e.correctness_attempted, 3),
            opt(e.correctness_all, 3)
        );
    }
}

/// The task × embodiment table.
fn write_per_task(out: &mut String, report: &ScoreReport) {
    let _ = writeln!(out, "\n## Per task\n");
    let _ = writeln!(
        out,
        "Mean score ± sample std (trials counted); `*` = correctness only (no baseline for the task).\n"
    );
    let mut header = "| task | name | baseline s |".to_string();
    let mut rule = "|---|---|---:|".to_string();
    for e in &report.embodiments {
        let _ = write!(header, " {} |", md(&e.embodiment));
        rule.push_str("---:|");
    }
    let _ = writeln!(out, "{header}\n{rule}");
    for t in &report.catalog_tasks {
        let mut line = format!(
            "| {} | {} | {} |",
            md(&t.id),
            md(&t.name),
            opt(t.baseline_s, 2)
        );
        for e in &report.embodiments {
            let _ = write!(
                line,
                " {} |",
                cell(report.task_result(&t.id, &e.embodiment))
            );
        }
        let _ = writeln!(out, "{line}");
    }
}

/// Links to the SVG figures, if any.
fn write_figures(out: &mut String, report: &ScoreReport) {
    if !report.figures.is_empty() {
        let _ = writeln!(out, "\n## Figures\n");
        for f in report.figures.iter().filter(|f| f.ends_with(".svg")) {
            let _ = writeln!(out, "![{f}]({f})\n");
        }
    }
}

/// The rejected and the skipped files, with the reasons.
fn write_unscored_files(out: &mut String, report: &ScoreReport) {
    if !report.rejected.is_empty() {
        let _ = writeln!(out, "\n## Rejected files\n");
        for r in &report.rejected {
            let _ = writeln!(out, "- `{}`: {}", r.file, md(&r.reason));
        }
    }
    if !report.skipped.is_empty() {
        let _ = writeln!(out, "\n## Skipped files\n");
        for r in &report.skipped {
            let _ = writeln!(out, "- `{}`: {}", r.file, md(&r.reason));
        }
    }
}

/// One row per trial.
fn write_trials(out: &mut String, report: &ScoreReport) {
    if !report.trials.is_empty() {
        let _ = writeln!(out, "\n## Trials\n");
        let _ = writeln!(
            out,
            "| file | task | embodiment | user | practice | outcome | time s | progress | correctness | speed | score | notes |"
        );
        let _ = writeln!(
            out,
            "|---|---|---|---|---|---|---:|---:|---:|---:|---:|---|"
        );
        for t in &report.trials {
            let _ = writeln!(
                out,
                "| `{}` | {} | {} | {} | {} | {} | {:.3} | {} | {:.3} | {} | {} | {} |",
                t.file,
                md(&t.task),
                md(&t.embodiment),
                md(t.user.as_deref().unwrap_or("")),
                if t.practice { "yes" } else { "" },
                t.outcome.name(),
                t.time_s,
                t.progress,
                t.correctness,
                opt(t.speed, 3),
                opt(t.score, 3),
                md(&t.notes.join("; "))
            );
        }
    }
}
