//! The comparison's figures: grouped bars per task × embodiment, one bar per group, for the
//! mean score (`compare_score`, tasks with a baseline only) and the mean correctness
//! (`compare_correctness`), ± one sample standard deviation.

use crate::compare::{CompareGroup, CompareRow, Comparison, GroupResult};
use crate::error::ScoringError;
use crate::figures::NamedFigure;
use crate::plot::{self, Bar, BarCategory, BarSeries, GroupedBarChart, MAX_BAR_SERIES, PlotError};
use crate::stats::MeanStd;

/// Which measure a figure shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Measure {
    Score,
    Correctness,
}

impl Measure {
    fn stats(self, g: &GroupResult) -> Option<MeanStd> {
        match self {
            Measure::Score => g.score,
            Measure::Correctness => g.correctness,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Measure::Score => "score",
            Measure::Correctness => "correctness",
        }
    }
}

/// The figures of `comparison`, remarks about figures not drawn or incomplete, and the
/// figures that failed to draw (the others are still returned).
pub fn render_compare_figures(
    comparison: &Comparison,
) -> (Vec<NamedFigure>, Vec<String>, Vec<ScoringError>) {
    let (mut figures, mut notes, mut errors) = (Vec::new(), Vec::new(), Vec::new());
    for measure in [Measure::Score, Measure::Correctness] {
        let stem = format!("compare_{}", measure.name());
        let Some(chart) = chart(comparison, measure, &stem, &mut notes) else {
            continue;
        };
        match plot::grouped_bars(&chart) {
            Ok(figure) => figures.push(NamedFigure { stem, figure }),
            Err(e) => errors.push(figure_error(&stem, &e)),
        }
    }
    (figures, notes, errors)
}

fn figure_error(stem: &str, e: &PlotError) -> ScoringError {
    ScoringError::Figure {
        figure: stem.to_string(),
        reason: e.to_string(),
    }
}

/// The chart of `measure`, or `None` (with a note) when no row has it.
fn chart(
    c: &Comparison,
    measure: Measure,
    stem: &str,
    notes: &mut Vec<String>,
) -> Option<GroupedBarChart> {
    let rows: Vec<&CompareRow> = (c.rows.iter())
        .filter(|r| measure == Measure::Correctness || r.has_baseline)
        .collect();
    if rows.is_empty() {
        notes.push(format!("{stem}: no task has a baseline, not drawn"));
        return None;
    }
    let mut groups: Vec<&CompareGroup> = c.groups.iter().collect();
    if groups.len() > MAX_BAR_SERIES {
        notes.push(format!(
            "{stem}: {} groups, the figure draws the first {MAX_BAR_SERIES}",
            groups.len()
        ));
        groups.truncate(MAX_BAR_SERIES);
    }
    let mut chart_notes = Vec::new();
    let without: Vec<String> = (c.rows.iter())
        .filter(|r| !r.has_baseline)
        .map(|r| format!("{} ({})", r.task, r.embodiment))
        .collect();
    if measure == Measure::Score && c.example_baseline {
        chart_notes.push("EXAMPLE baseline: not real POMDAR scores".to_string());
    }
    if measure == Measure::Score && !without.is_empty() {
        chart_notes.push(format!("No baseline, so no score: {}", without.join(", ")));
    }
    let series = groups
        .iter()
        .map(|g| BarSeries {
            label: g.describe(),
            values: (rows.iter())
                .map(|r| {
                    let s = measure.stats(r.group(&g.name)?)?;
                    Some(Bar {
                        mean: s.mean,
                        std: s.std,
                    })
                })
                .collect(),
        })
        .collect();
    Some(GroupedBarChart {
        title: format!(
            "Mean {} by {}, per task and embodiment",
            measure.name(),
            c.field
        ),
        notes: chart_notes,
        y_label: format!("Mean {}", measure.name()),
        x_label: "Task (grouped by embodiment)".to_string(),
        categories: (rows.iter())
            .map(|r| BarCategory {
                label: r.task.clone(),
                band: r.embodiment.clone(),
            })
            .collect(),
        series,
    })
}
