//! The report as aligned text for a terminal, at most 100 columns wide.

use std::fmt::Write as _;

use crate::aggregate::TaskResult;
use crate::report::{ScoreReport, opt};

/// Widest line the terminal report writes (except unbreakable file names).
pub const TERMINAL_WIDTH: usize = 100;

/// Trials listed one per line when there are at most this many.
const TRIAL_LINES_MAX: usize = 30;

/// Width of a task × embodiment cell.
const CELL: usize = 16;
/// Width of the task ID and name columns, with their separating spaces.
const TASK_COLUMNS: usize = 4 + 1 + 16;

/// `text` wrapped at spaces to `width` columns, continuation lines indented by `indent`;
/// runs of spaces inside a line (alignment) are kept.
pub(crate) fn wrap(text: &str, width: usize, indent: &str) -> String {
    let mut out = String::new();
    let mut line = String::new();
    let mut has_word = false;
    for (i, word) in text.split(' ').enumerate() {
        let sep = if i == 0 { "" } else { " " };
        let too_long = line.chars().count() + sep.len() + word.chars().count() > width;
        if has_word && !word.is_empty() && too_long {
            out.push_str(line.trim_end());
            out.push('\n');
            line = format!("{indent}{word}");
        } else {
            line.push_str(sep);
            line.push_str(word);
        }
        has_word |= !word.is_empty();
    }
    out.push_str(&line);
    out
}

/// A task × embodiment cell: `0.74±0.05 (20)`, correctness with `*` when the task has no
/// baseline, `practice` or `excluded` when no trial counts.
pub(crate) fn cell(result: Option<&TaskResult>) -> String {
    let Some(r) = result else {
        return String::new();
    };
    let stats = if r.has_baseline {
        r.score
    } else {
        r.correctness
    };
    match stats {
        Some(s) => format!(
            "{:.2}±{} ({}){}",
            s.mean,
            s.std.map_or("–   ".to_string(), |v| format!("{v:.2}")),
            s.n,
            if r.has_baseline { "" } else { "*" }
        ),
        None if r.excluded > 0 => format!("excluded ({})", r.excluded),
        None => format!("practice ({})", r.practice),
    }
}

fn pad(text: &str, width: usize) -> String {
    let n = text.chars().count();
    if n >= width {
        text.chars().take(width).collect()
    } else {
        format!("{text}{}", " ".repeat(width - n))
    }
}

fn pad_left(text: &str, width: usize) -> String {
    let n = text.chars().count();
    format!("{}{text}", " ".repeat(width.saturating_sub(n)))
}

/// Renders `report` for a terminal.
pub fn render_terminal(report: &ScoreReport) -> String {
    let mut out = String::new();
    write_summary(&mut out, report);
    if !report.embodiments.is_empty() {
        write_overall(&mut out, report);
        write_per_task(&mut out, report);
    }
    write_trials(&mut out, report);
    write_unscored_files(&mut out, report);
    out
}

/// The title, the inputs, the warnings and the notes.
fn write_summary(out: &mut String, report: &ScoreReport) {
    let w = TERMINAL_WIDTH;
    let practice = report.trials.iter().filter(|t| t.practice).count();
    let _ = writeln!(out, "POMDAR scores");
    let _ = writeln!(
        out,
        "{}",
        wrap(
            &format!("  catalog   {}", report.catalog),
            w,
            "            "
        )
    );
    let _ = writeln!(
        out,
        "{}",
        wrap(
            &format!(
                "  rules     {} ({})",
                report.rules.description, report.rules.origin
            ),
            w,
            "            "
        )
    );
    let baseline = match &report.baseline {
        Some(b) => format!(
            "  baseline  {}{} ({} tasks): {}",
            if b.example { "EXAMPLE " } else { "" },
            b.origin,
            b.tasks.len(),
            b.source
        ),
        None => "  baseline  none (correctness only)".to_string(),
    };
    let _ = writeln!(out, "{}", wrap(&baseline, w, "            "));
    let _ = writeln!(
        out,
        "  trials    {} scored ({} counted, {} practice), {} rejected, {} skipped",
        report.trials.len(),
        report.counted_trials(),
        practice,
        report.rejected.len(),
        report.skipped.len()
    );
    for warning in &report.warnings {
        let _ = writeln!(
            out,
            "\n{}",
            wrap(&format!("WARNING: {warning}"), w, "         ")
        );
    }
    for note in &report.notes {
        let _ = writeln!(out, "{}", wrap(&format!("note: {note}"), w, "      "));
    }
}

/// The overall scores per embodiment.
fn write_overall(out: &mut String, report: &ScoreReport) {
    let total = report.catalog_tasks.len();
    let _ = writeln!(
        out,
        "\nOverall per embodiment (mean of the task means; ± spread across tasks)"
    );
    let all = format!("overall (all {total})");
    let _ = writeln!(
        out,
        "{} {} {} {}  {} {}  {}",
        pad("embodiment", 15),
        pad_left("DoF", 4),
        pad_left("tasks", 6),
        pad_left("trials", 7),
        pad("overall (attempted)", 19),
        pad_left(&all, 17),
        pad_left("correctness att./all", 20)
    );
    for e in &report.embodiments {
        let attempted = match (e.overall_attempted, e.overall_spread) {
            (Some(m), Some(s)) => format!("{m:.2} ± {s:.2}"),
            (Some(m), None) => format!("{m:.2}"),
            (None, _) => "– (no baseline)".to_string(),
        };
        let _ = writeln!(
            out,
            "{} {} {} {}  {} {}  {}",
            pad(&e.embodiment, 15),
            pad_left(&e.dof.map_or("?".to_string(), |d| d.to_string()), 4),
            pad_left(&format!("{}/{}", e.tasks_attempted, e.tasks_total), 6),
            pad_left(&e.trials.to_string(), 7),
            pad(&attempted, 19),
            pad_left(&opt(e.overall_all, 2), 17),
            pad_left(
                &format!(
                    "{} / {}",
                    opt(e.correctness_attempted, 2),
                    opt(e.correctness_all, 2)
                ),
                20
            )
        );
    }
}

/// The task × embodiment tables, as many embodiments per block as fit the width.
fn write_per_task(out: &mut String, report: &ScoreReport) {
    let w = TERMINAL_WIDTH;
    let per_block = ((w - TASK_COLUMNS) / (CELL + 1)).max(1);
    for block in report.embodiments.chunks(per_block) {
        let _ = writeln!(
            out,
            "\nPer task: mean score ± std (trials); * = correctness only (no baseline)"
        );
        let mut header = format!("{} {}", pad("task", 4), pad("name", 16));
        for e in block {
            header.push(' ');
            header.push_str(&pad(&e.embodiment, CELL));
        }
        let _ = writeln!(out, "{}", header.trim_end());
        for t in &report.catalog_tasks {
            let mut line = format!("{} {}", pad(&t.id, 4), pad(&t.name, 16));
            for e in block {
                line.push(' ');
                line.push_str(&pad(&cell(report.task_result(&t.id, &e.embodiment)), CELL));
            }
            let _ = writeln!(out, "{}", line.trim_end());
        }
    }
}

/// One line per trial when there are few, else where to find them.
fn write_trials(out: &mut String, report: &ScoreReport) {
    if !report.trials.is_empty() && report.trials.len() <= TRIAL_LINES_MAX {
        let _ = writeln!(out, "\nTrials");
        let _ = writeln!(
            out,
            "{} {} {} {} {} {} {} file",
            pad("task", 4),
            pad("embodiment", 11),
            pad("outcome", 9),
            pad_left("time s", 8),
            pad_left("correct", 7),
            pad_left("speed", 6),
            pad_left("score", 6),
        );
        for t in &report.trials {
            let _ = writeln!(
                out,
                "{} {} {} {} {} {} {} {}{}",
                pad(&t.task, 4),
                pad(&t.embodiment, 11),
                pad(t.outcome.name(), 9),
                pad_left(&format!("{:.2}", t.time_s), 8),
                pad_left(&format!("{:.2}", t.correctness), 7),
                pad_left(&opt(t.speed, 2), 6),
                pad_left(&opt(t.score, 2), 6),
                t.file,
                if t.practice { " (practice)" } else { "" }
            );
        }
    } else if !report.trials.is_empty() {
        let _ = writeln!(
            out,
            "\nPer-trial scores: trials.csv and scores.json (written with --out), or --json."
        );
    }
}

/// The rejected and the skipped files, with the reasons.
fn write_unscored_files(out: &mut String, report: &ScoreReport) {
    let w = TERMINAL_WIDTH;
    if !report.rejected.is_empty() {
        let _ = writeln!(out, "\nRejected files ({})", report.rejected.len());
        for r in &report.rejected {
            let _ = writeln!(
                out,
                "{}",
                wrap(&format!("  {}: {}", r.file, r.reason), w, "      ")
            );
        }
    }
    if !report.skipped.is_empty() {
        let _ = writeln!(out, "\nSkipped files ({})", report.skipped.len());
        for r in &report.skipped {
            let _ = writeln!(
                out,
                "{}",
                wrap(&format!("  {}: {}", r.file, r.reason), w, "      ")
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapping_keeps_alignment_and_indents_continuations() {
        assert_eq!(wrap("  a  b", 80, "    "), "  a  b");
        assert_eq!(wrap("one two three", 8, "  "), "one two\n  three");
    }
}
