//! Grouped bars, the data: one category per task × embodiment on the x axis (task IDs under the bars,
//! each embodiment named once under its run of tasks), one bar per series (the groups of a
//! comparison) in its palette colour, ± one standard deviation as error bars, a legend below.
//! A series without a value in a category gets a hollow marker at 0 instead of a bar.

use serde::Serialize;

use super::PlotError;
use super::palette::SERIES_COLORS;
use super::scale::check_score;

/// One bar: a mean and its standard deviation (none for a single trial).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Bar {
    /// The bar's height (a score or correctness, ≥ 0).
    pub mean: f64,
    /// Drawn as ± error bars (stopping at 0).
    pub std: Option<f64>,
}

/// A place on the x axis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BarCategory {
    /// Under the bars (a task ID).
    pub label: String,
    /// Under a run of consecutive categories with the same band (an embodiment).
    pub band: String,
}

/// One series: its bars, one per category (`None`: no value there).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BarSeries {
    /// Legend label.
    pub label: String,
    /// One entry per category.
    pub values: Vec<Option<Bar>>,
}

/// A grouped bar chart.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GroupedBarChart {
    /// Title above the chart.
    pub title: String,
    /// Grey lines under the title (the error-bar key is added when a bar has a std).
    pub notes: Vec<String>,
    /// Y axis title.
    pub y_label: String,
    /// X axis title.
    pub x_label: String,
    /// The categories, left to right.
    pub categories: Vec<BarCategory>,
    /// The series, in legend and colour order.
    pub series: Vec<BarSeries>,
}

/// Most series a chart draws (the palette's distinct colours).
pub const MAX_BAR_SERIES: usize = SERIES_COLORS.len();

/// Checks the chart; returns the largest mean + std (the top of the data).
pub(super) fn validate(chart: &GroupedBarChart) -> Result<f64, PlotError> {
    let title = || chart.title.clone();
    if chart.categories.is_empty() || chart.series.is_empty() {
        return Err(PlotError::NoBars { title: title() });
    }
    if chart.series.len() > MAX_BAR_SERIES {
        return Err(PlotError::TooManyBarSeries {
            title: title(),
            count: chart.series.len(),
            max: MAX_BAR_SERIES,
        });
    }
    let mut max = 0.0_f64;
    for s in &chart.series {
        if s.values.len() != chart.categories.len() {
            return Err(PlotError::BarCountMismatch {
                series: s.label.clone(),
                values: s.values.len(),
                categories: chart.categories.len(),
            });
        }
        for (value, category) in s.values.iter().zip(&chart.categories) {
            let Some(bar) = value else { continue };
            let bad = |field, value| {
                move |problem| PlotError::BadBarValue {
                    series: s.label.clone(),
                    category: format!("{} {}", category.label, category.band),
                    field,
                    value,
                    problem,
                }
            };
            check_score(bar.mean).map_err(bad("mean", bar.mean))?;
            let std = bar.std.unwrap_or(0.0);
            check_score(std).map_err(bad("std", std))?;
            max = max.max(bar.mean + std);
        }
    }
    Ok(max)
}
