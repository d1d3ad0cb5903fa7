//! The trial review figure ([`ReviewChart`]) drawn: validated, laid out, painted in layers
//! (header, lanes, panels, time axis, then the marks over everything).

use super::primitives::Drawing;
use super::review_chart::{ReviewChart, validate};
use super::review_layout::Layout;
use super::review_paint::{header, lane, marks, time_axis};
use super::review_panel::panel;
use super::review_style::WIDTH;
use super::{Figure, PlotError};

/// Render: PNG and SVG of the same drawing (deterministic bytes). Errors (PlotError) for a
/// non-finite or non-positive duration, a span with from > to, non-finite times; values may
/// be NaN (gaps).
pub fn review_figure(chart: &ReviewChart) -> Result<Figure, PlotError> {
    Figure::render(&review_drawing(chart)?)
}

/// The figure's drawing.
pub(super) fn review_drawing(chart: &ReviewChart) -> Result<Drawing, PlotError> {
    validate(chart)?;
    let layout = Layout::new(chart);
    let mut d = Drawing::new(WIDTH as u32, layout.height as u32, chart.title.clone());
    header(&mut d, chart, &layout);
    for (row, &top) in chart.lanes.iter().zip(&layout.lane_tops) {
        lane(&mut d, row, top, &layout);
    }
    for (content, place) in chart.panels.iter().zip(&layout.panels) {
        panel(&mut d, content, place, &layout);
    }
    time_axis(&mut d, &layout);
    marks(&mut d, chart, &layout);
    Ok(d)
}

#[cfg(test)]
#[path = "review_chart_tests.rs"]
mod tests;
