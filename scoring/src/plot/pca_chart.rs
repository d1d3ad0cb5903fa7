//! A labelled scatter of principal component scores: one colour per series (past eight, a
//! second and third marker style), axes with round ticks around the data, light zero lines,
//! a note under the title and a legend under the plot.

mod linear_axis;
mod scatter_legend;

use serde::Serialize;

pub use linear_axis::LinearAxis;

use super::chart_frame::{
    AXIS_TITLE_PX, HEIGHT_PX, MARGIN_PX, NOTE_PX, TICK_LEN_PX, TICK_PX, TITLE_PX, WIDTH_PX,
};
use super::label_placement::Rect;
use super::palette::SERIES_COLORS;
use super::primitives::{Anchor, Drawing, Point, Rgba, Style, Text};
use super::stroke_font::{FONT_SLACK, cap_height, text_width};
use super::{Figure, PlotError, ValueProblem};
use scatter_legend::{LEGEND_ROW_PX, MARKER_STYLES, draw_legend, legend_rows, marker_style};

/// One series (e.g. one task's segments).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PcaSeries {
    /// Legend label.
    pub label: String,
    /// Points as (x, y) in data units.
    pub points: Vec<(f64, f64)>,
}

/// A scatter of component scores.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PcaChart {
    /// Title above the chart.
    pub title: String,
    /// X axis title, e.g. `PC1 (41 % of variance)`.
    pub x_label: String,
    /// Y axis title.
    pub y_label: String,
    /// The series, coloured in order.
    pub series: Vec<PcaSeries>,
    /// A grey line under the title, e.g. the variance explained and the silhouette.
    pub note: Option<String>,
}

/// The most series a scatter tells apart: colours × marker styles.
pub const MAX_SCATTER_SERIES: usize = SERIES_COLORS.len() * MARKER_STYLES;

const POINT_RADIUS_PX: f64 = 4.5;

/// The plot area and the data-to-pixel mapping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PcaGeometry {
    /// Plot area in pixels.
    pub area: Rect,
    /// Horizontal axis.
    pub x_axis: LinearAxis,
    /// Vertical axis.
    pub y_axis: LinearAxis,
}

impl PcaGeometry {
    /// Pixel x of data `x`.
    pub fn x(&self, x: f64) -> f64 {
        let a = self.x_axis;
        self.area.left + (x - a.lo) / (a.hi - a.lo) * self.area.width()
    }

    /// Pixel y of data `y`.
    pub fn y(&self, y: f64) -> f64 {
        let a = self.y_axis;
        self.area.bottom - (y - a.lo) / (a.hi - a.lo) * self.area.height()
    }
}

/// The data's x and y ranges, or what is wrong with the chart.
fn validate(chart: &PcaChart) -> Result<[(f64, f64); 2], PlotError> {
    if chart.series.len() > MAX_SCATTER_SERIES {
        return Err(PlotError::TooManyScatterSeries {
            title: chart.title.clone(),
            count: chart.series.len(),
            max: MAX_SCATTER_SERIES,
        });
    }
    let mut ranges = [(f64::INFINITY, f64::NEG_INFINITY); 2];
    for s in &chart.series {
        for (index, &(x, y)) in s.points.iter().enumerate() {
            for ((axis, value), range) in [("x", x), ("y", y)].into_iter().zip(&mut ranges) {
                if !value.is_finite() {
                    return Err(PlotError::BadScatterValue {
                        series: s.label.clone(),
                        index,
                        axis,
                        value,
                        problem: ValueProblem::NotFinite,
                    });
                }
                *range = (range.0.min(value), range.1.max(value));
            }
        }
    }
    if ranges[0].0 > ranges[0].1 {
        return Err(PlotError::NoScatterPoints {
            title: chart.title.clone(),
        });
    }
    Ok(ranges)
}

/// The scatter as SVG and PNG.
pub fn pca_scatter(chart: &PcaChart) -> Result<Figure, PlotError> {
    let (drawing, _) = pca_drawing(chart)?;
    Figure::render(&drawing)
}

/// The scatter's drawing and the geometry its points were placed with.
pub fn pca_drawing(chart: &PcaChart) -> Result<(Drawing, PcaGeometry), PlotError> {
    let [(x_min, x_max), (y_min, y_max)] = validate(chart)?;
    let rows = legend_rows(chart);
    let geometry = layout(
        LinearAxis::spanning(x_min, x_max),
        LinearAxis::spanning(y_min, y_max),
        rows.len(),
    );
    let mut d = Drawing::new(WIDTH_PX as u32, HEIGHT_PX as u32, chart.title.clone());
    draw_grid_and_axes(&mut d, &geometry);
    draw_titles(&mut d, &geometry, chart);
    for (i, s) in chart.series.iter().enumerate() {
        for &(x, y) in &s.points {
            let at = Point::new(geometry.x(x), geometry.y(y));
            d.circle(at, POINT_RADIUS_PX, marker_style(i), Some("point"));
        }
    }
    draw_legend(&mut d, chart, &rows, x_title_y(geometry.area) + 8.0);
    Ok((d, geometry))
}

/// Baseline x of the rotated y axis title.
fn y_title_x() -> f64 {
    MARGIN_PX + cap_height(AXIS_TITLE_PX)
}

/// Baseline y of the x axis tick labels.
fn x_tick_label_y(area: Rect) -> f64 {
    area.bottom + TICK_LEN_PX + 4.0 + cap_height(TICK_PX)
}

/// Baseline y of the x axis title.
fn x_title_y(area: Rect) -> f64 {
    x_tick_label_y(area) + 14.0 + cap_height(AXIS_TITLE_PX)
}

/// The plot area, leaving room for the widest y tick label and the legend's rows.
fn layout(x_axis: LinearAxis, y_axis: LinearAxis, legend_rows: usize) -> PcaGeometry {
    let tick_w = (y_axis.ticks().iter())
        .map(|&t| text_width(&y_axis.label(t), TICK_PX))
        .fold(0.0, f64::max);
    PcaGeometry {
        area: Rect {
            left: y_title_x() + 14.0 + FONT_SLACK * tick_w + 8.0 + TICK_LEN_PX,
            right: WIDTH_PX - 30.0,
            top: 84.0,
            bottom: HEIGHT_PX - 70.0 - legend_rows as f64 * LEGEND_ROW_PX,
        },
        x_axis,
        y_axis,
    }
}

/// Grid lines, zero lines, ticks and tick labels, then the frame.
fn draw_grid_and_axes(d: &mut Drawing, g: &PcaGeometry) {
    let area = g.area;
    let grid = Rgba::GRID.with_alpha(0.6);
    for x in g.x_axis.ticks() {
        let px = g.x(x);
        d.line(
            Point::new(px, area.top),
            Point::new(px, area.bottom),
            grid,
            1.0,
        );
        let tick_end = Point::new(px, area.bottom + TICK_LEN_PX);
        d.line(Point::new(px, area.bottom), tick_end, Rgba::INK, 1.0);
        let at = Point::new(px, x_tick_label_y(area));
        d.text(Text::new(g.x_axis.label(x), at, Anchor::Middle, TICK_PX));
    }
    for y in g.y_axis.ticks() {
        let py = g.y(y);
        d.line(
            Point::new(area.left, py),
            Point::new(area.right, py),
            grid,
            1.0,
        );
        let tick_start = Point::new(area.left - TICK_LEN_PX, py);
        d.line(tick_start, Point::new(area.left, py), Rgba::INK, 1.0);
        let at = Point::new(
            area.left - TICK_LEN_PX - 4.0,
            py + cap_height(TICK_PX) / 2.0,
        );
        d.text(Text::new(g.y_axis.label(y), at, Anchor::End, TICK_PX));
    }
    let zero = Style::line(Rgba::GREY.with_alpha(0.55), 1.2);
    if g.x_axis.lo < 0.0 && g.x_axis.hi > 0.0 {
        let px = g.x(0.0);
        let line = vec![Point::new(px, area.top), Point::new(px, area.bottom)];
        d.path(line, false, zero, Some("zero-line"));
    }
    if g.y_axis.lo < 0.0 && g.y_axis.hi > 0.0 {
        let py = g.y(0.0);
        let line = vec![Point::new(area.left, py), Point::new(area.right, py)];
        d.path(line, false, zero, Some("zero-line"));
    }
    let frame = vec![
        Point::new(area.left, area.top),
        Point::new(area.right, area.top),
        Point::new(area.right, area.bottom),
        Point::new(area.left, area.bottom),
    ];
    d.path(frame, true, Style::line(Rgba::INK, 1.2), Some("axes"));
}

/// The title, the note and the axis titles.
fn draw_titles(d: &mut Drawing, g: &PcaGeometry, chart: &PcaChart) {
    let area = g.area;
    let at = Point::new(WIDTH_PX / 2.0, MARGIN_PX + cap_height(TITLE_PX));
    let mut title = Text::new(chart.title.clone(), at, Anchor::Middle, TITLE_PX);
    title.bold = true;
    d.text(title);
    if let Some(note) = &chart.note {
        let at = Point::new(WIDTH_PX / 2.0, 64.0);
        let mut note = Text::new(note.clone(), at, Anchor::Middle, NOTE_PX);
        note.color = Rgba::GREY;
        d.text(note);
    }
    let at = Point::new((area.left + area.right) / 2.0, x_title_y(area));
    d.text(Text::new(
        chart.x_label.clone(),
        at,
        Anchor::Middle,
        AXIS_TITLE_PX,
    ));
    let at = Point::new(y_title_x(), (area.top + area.bottom) / 2.0);
    let mut y_title = Text::new(chart.y_label.clone(), at, Anchor::Middle, AXIS_TITLE_PX);
    y_title.rotate_deg = -90.0;
    d.text(y_title);
}

#[cfg(test)]
mod tests;
