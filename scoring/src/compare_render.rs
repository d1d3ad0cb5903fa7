//! The comparison as text: for a terminal (at most 100 columns) and as Markdown
//! (`compare.md`). JSON is serde; CSV is `compare_csv`.
//!
//! Per task × embodiment, one line per group: n, correctness, time and score (mean ± sample
//! std), and under every group but the reference its differences from the reference with
//! the 95 % interval, or why there is none.

use std::fmt::Write as _;

use crate::compare::{CompareGroup, CompareRow, Comparison, GroupResult};
use crate::report_markdown::md;
use crate::report_terminal::{TERMINAL_WIDTH, wrap};
use crate::stats::MeanStd;
use crate::welch::Difference;

/// Decimals of correctness and score.
const DECIMALS: usize = 2;
/// Decimals of times, seconds.
const TIME_DECIMALS: usize = 1;
/// Width of the group column (terminal).
const GROUP_W: usize = 16;
/// Width of a measure column (terminal).
const MEASURE_W: usize = 25;

/// `0.72 ± 0.05`, `0.72 ± –` for one trial, `–` for none.
fn stats(s: Option<MeanStd>, decimals: usize) -> String {
    s.map_or("–".to_string(), |s| s.format(decimals))
}

/// The score cell: its statistics, or why there is none.
fn score_cell(row: &CompareRow, g: &GroupResult) -> String {
    if row.has_baseline {
        stats(g.score, DECIMALS)
    } else {
        "no baseline".to_string()
    }
}

/// `+0.05 [-0.12, +0.22]`, or `–` when there is no difference.
fn diff(d: Option<Difference>, decimals: usize) -> String {
    d.map_or("–".to_string(), |d| d.describe(decimals))
}

/// The three difference cells of `g` (`–` for the reference and where a group has no trial).
fn diff_cells(row: &CompareRow, g: &GroupResult) -> [String; 3] {
    let v = g.versus_reference;
    [
        diff(v.map(|v| v.correctness), DECIMALS),
        diff(v.map(|v| v.time_s), TIME_DECIMALS),
        if row.has_baseline {
            diff(v.and_then(|v| v.score), DECIMALS)
        } else {
            "no baseline".to_string()
        },
    ]
}

/// The group's name with `(ref)` for the reference.
fn group_label(c: &Comparison, g: &GroupResult) -> String {
    if g.group == c.reference {
        format!("{} (ref)", g.group)
    } else {
        g.group.clone()
    }
}

fn pad(text: &str, width: usize) -> String {
    let n = text.chars().count();
    format!("{text}{}", " ".repeat(width.saturating_sub(n)))
}

/// The heading lines: field, groups, reference, method, warnings and notes.
fn write_heading(out: &mut String, c: &Comparison, w: usize) {
    let _ = writeln!(out, "POMDAR comparison by metadata entry {:?}", c.field);
    let groups: Vec<String> = c.groups.iter().map(CompareGroup::describe).collect();
    let line = format!("  groups    {}", groups.join(", "));
    let _ = writeln!(out, "{}", wrap(&line, w, "            "));
    let _ = writeln!(
        out,
        "{}",
        wrap(
            &format!(
                "  method    mean ± sample std over recorded trials; difference = group − {} \
                 with Welch's {:.0} % t interval (unequal variances)",
                c.reference,
                100.0 * c.confidence_level
            ),
            w,
            "            "
        )
    );
    for warning in &c.warnings {
        let _ = writeln!(
            out,
            "\n{}",
            wrap(&format!("WARNING: {warning}"), w, "         ")
        );
    }
    for note in &c.notes {
        let _ = writeln!(out, "{}", wrap(&format!("note: {note}"), w, "      "));
    }
}

/// Renders the comparison for a terminal.
pub fn render_compare_terminal(c: &Comparison) -> String {
    let mut out = String::new();
    write_heading(&mut out, c, TERMINAL_WIDTH);
    for row in &c.rows {
        let _ = writeln!(out, "\n{} {} · {}", row.task, row.task_name, row.embodiment);
        let _ = writeln!(
            out,
            "  {}   n  {}{}score",
            pad("group", GROUP_W),
            pad("correctness", MEASURE_W),
            pad("time (s)", MEASURE_W),
        );
        for g in &row.groups {
            let _ = writeln!(
                out,
                "  {}{:>4}  {}{}{}",
                pad(&group_label(c, g), GROUP_W),
                g.n,
                pad(&stats(g.correctness, DECIMALS), MEASURE_W),
                pad(&stats(g.time_s, TIME_DECIMALS), MEASURE_W),
                score_cell(row, g)
            );
            if g.versus_reference.is_some() {
                let [dc, dt, ds] = diff_cells(row, g);
                let label = format!("  − {}", c.reference);
                let _ = writeln!(
                    out,
                    "  {}      {}{}{}",
                    pad(&label, GROUP_W),
                    pad(&dc, MEASURE_W),
                    pad(&dt, MEASURE_W),
                    ds
                );
            }
        }
    }
    out
}

/// Renders the comparison as Markdown; figures listed in [`Comparison::figures`] are
/// linked relative to it.
pub fn render_compare_markdown(c: &Comparison) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# POMDAR comparison by `{}`\n", md(&c.field));
    for warning in &c.warnings {
        let _ = writeln!(out, "> **WARNING:** {}\n", md(warning));
    }
    let _ = writeln!(out, "| group | recorded trials | |\n|---|---|---|");
    for g in &c.groups {
        let role = match (g.reference, g.missing) {
            (true, _) => "reference",
            (false, true) => "no such entry",
            (false, false) => "",
        };
        let _ = writeln!(out, "| {} | {} | {role} |", md(&g.name), g.trials);
    }
    let _ = writeln!(
        out,
        "\nMean ± sample standard deviation over the recorded trials (practice and excluded \
         trials left out, as in the score report). Δ = group − `{}`, with Welch's {:.0} % t \
         interval (unequal variances, Welch–Satterthwaite degrees of freedom); none where a \
         group has fewer than 2 trials or neither group varies.\n",
        md(&c.reference),
        100.0 * c.confidence_level
    );
    for note in &c.notes {
        let _ = writeln!(out, "- {}", md(note));
    }
    write_markdown_table(&mut out, c);
    if !c.figures.is_empty() {
        let _ = writeln!(out, "\n## Figures\n");
        for f in c.figures.iter().filter(|f| f.ends_with(".png")) {
            let svg = f.trim_end_matches(".png");
            let _ = writeln!(out, "![{svg}]({f}) ([SVG]({svg}.svg))\n");
        }
    }
    out
}

fn write_markdown_table(out: &mut String, c: &Comparison) {
    let _ = writeln!(
        out,
        "\n| task | embodiment | group | n | correctness | time (s) | score | Δ correctness [95 % CI] | Δ time (s) [95 % CI] | Δ score [95 % CI] |"
    );
    let _ = writeln!(out, "|---|---|---|--:|---|---|---|---|---|---|");
    for row in &c.rows {
        for g in &row.groups {
            let [dc, dt, ds] = diff_cells(row, g);
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} | {} | {} | {} | {dc} | {dt} | {ds} |",
                md(&row.task),
                md(&row.embodiment),
                md(&group_label(c, g)),
                g.n,
                stats(g.correctness, DECIMALS),
                stats(g.time_s, TIME_DECIMALS),
                score_cell(row, g),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compare::compare_by;
    use crate::compare::tests::{report, trials};
    use crate::compare_csv::render_compare_csv;

    fn comparison() -> Comparison {
        compare_by(&report(trials()), "keypoint_source", Some("rokoko")).unwrap()
    }

    #[test]
    fn the_terminal_table_fits_and_shows_groups_differences_and_missing_scores() {
        let text = render_compare_terminal(&comparison());
        for line in text.lines() {
            assert!(line.chars().count() <= TERMINAL_WIDTH, "too wide: {line}");
        }
        assert!(
            text.contains("avp (5 trials), rokoko (4 trials, reference), (missing) (2 trials)")
        );
        // V1 on orca_full: avp's time 15.0 ± 2.0 s, 3.0 s slower than rokoko's.
        let avp = text
            .lines()
            .find(|l| l.starts_with("  avp ") && l.contains("15.0 ± 2.0"));
        assert!(avp.is_some(), "{text}");
        assert!(text.contains("  − rokoko"), "{text}");
        assert!(text.contains("+3.0 ["), "{text}");
        assert!(text.contains("no baseline"), "H2 has no score: {text}");
        assert!(text.contains("no CI (n < 2)"), "{text}");
    }

    #[test]
    fn markdown_and_csv_have_a_row_per_task_embodiment_and_group() {
        let c = comparison();
        let md = render_compare_markdown(&c);
        let table_rows = md
            .lines()
            .filter(|l| l.starts_with("| H2 ") || l.starts_with("| V1 "));
        assert_eq!(table_rows.count(), 2 * 3);
        assert!(md.contains("| V1 | orca_full | rokoko (ref) | 3 |"), "{md}");
        let csv = render_compare_csv(&c);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 1 + 2 * 3);
        let columns = lines[0].split(',').count();
        assert!(
            lines.iter().all(|l| l.split(',').count() == columns),
            "{csv}"
        );
        let avp = lines
            .iter()
            .find(|l| l.contains(",V1,") && l.contains(",avp,"))
            .unwrap();
        // avp − rokoko = 3 s, 3 ∓ t(0.975, 4) · √(8/3) = 3 ∓ 2.7764451 · 1.6329932, ν = 4.
        assert!(avp.contains(",3,-1.5339158"), "{avp}");
        assert!(avp.contains(",7.5339158"), "{avp}");
    }
}
