//! The comparison as CSV (`compare.csv`, RFC 4180 like the other tables): one row per task ×
//! embodiment × group, with its differences from the reference group and their 95 %
//! intervals. Empty cells mean "none"; the `note` column says why (the reference itself, no
//! baseline, no interval).

use crate::compare::{CompareRow, Comparison, GroupResult};
use crate::report_csv::row;
use crate::stats::MeanStd;
use crate::welch::{Difference, DifferenceInterval};

const HEADER: [&str; 26] = [
    "field",
    "reference",
    "task",
    "name",
    "embodiment",
    "group",
    "n",
    "correctness_mean",
    "correctness_std",
    "time_mean_s",
    "time_std_s",
    "score_mean",
    "score_std",
    "correctness_diff",
    "correctness_ci_low",
    "correctness_ci_high",
    "correctness_df",
    "time_diff_s",
    "time_ci_low_s",
    "time_ci_high_s",
    "time_df",
    "score_diff",
    "score_ci_low",
    "score_ci_high",
    "score_df",
    "note",
];

fn num(v: Option<f64>) -> String {
    v.map_or(String::new(), |v| format!("{v}"))
}

/// Mean and std cells.
fn stats(s: Option<MeanStd>) -> [String; 2] {
    [num(s.map(|s| s.mean)), num(s.and_then(|s| s.std))]
}

/// Difference, interval bounds and degrees of freedom cells.
fn difference(d: Option<Difference>) -> [String; 4] {
    let defined = d.and_then(|d| match d.ci {
        DifferenceInterval::Defined { low, high, df, .. } => Some((low, high, df)),
        _ => None,
    });
    [
        num(d.map(|d| d.estimate)),
        num(defined.map(|v| v.0)),
        num(defined.map(|v| v.1)),
        num(defined.map(|v| v.2)),
    ]
}

/// Why cells are empty: the reference, no baseline, an undefined interval.
fn note(c: &Comparison, r: &CompareRow, g: &GroupResult) -> String {
    let mut parts: Vec<String> = Vec::new();
    if g.group == c.reference {
        parts.push("reference".into());
    } else if g.n == 0 {
        parts.push("no trials".into());
    }
    if !r.has_baseline {
        parts.push("no baseline: no score".into());
    }
    if let Some(v) = g.versus_reference {
        let undefined = [Some(v.correctness), Some(v.time_s), v.score]
            .into_iter()
            .flatten()
            .find(|d| !d.ci.is_defined());
        if let Some(d) = undefined {
            parts.push(d.ci.describe(0));
        }
    }
    parts.join("; ")
}

/// Renders `compare.csv`.
pub fn render_compare_csv(c: &Comparison) -> String {
    let mut out = String::new();
    row(&mut out, &HEADER.map(String::from));
    for r in &c.rows {
        for g in &r.groups {
            let v = g.versus_reference;
            let mut fields = vec![
                c.field.clone(),
                c.reference.clone(),
                r.task.clone(),
                r.task_name.clone(),
                r.embodiment.clone(),
                g.group.clone(),
                g.n.to_string(),
            ];
            fields.extend(stats(g.correctness));
            fields.extend(stats(g.time_s));
            fields.extend(stats(g.score));
            fields.extend(difference(v.map(|v| v.correctness)));
            fields.extend(difference(v.map(|v| v.time_s)));
            fields.extend(difference(v.and_then(|v| v.score)));
            fields.push(note(c, r, g));
            row(&mut out, &fields);
        }
    }
    out
}
