//! The grouped bar chart ([`GroupedBarChart`]) drawn: validated, laid out, rendered.

use super::compare_chart::{GroupedBarChart, validate};
use super::compare_layout::{BarGeometry, draw};
use super::primitives::Drawing;
use super::{Figure, PlotError};

/// The chart as SVG and PNG.
pub fn grouped_bars(chart: &GroupedBarChart) -> Result<Figure, PlotError> {
    let (drawing, _) = grouped_bars_drawing(chart)?;
    Figure::render(&drawing)
}

/// The chart's drawing and the geometry its bars were placed with.
pub fn grouped_bars_drawing(chart: &GroupedBarChart) -> Result<(Drawing, BarGeometry), PlotError> {
    let max = validate(chart)?;
    Ok(draw(chart, max))
}

#[cfg(test)]
#[path = "compare_bars_tests.rs"]
mod tests;
