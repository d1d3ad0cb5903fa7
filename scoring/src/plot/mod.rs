//! Figures in the style of the POMDAR paper, returned as data (SVG text and PNG bytes).
//!
//! - [`radar()`]: one axis per task, clockwise from the top, grid rings every 0.2 up to 1.0 and
//!   on past the largest score when scores exceed 1 (speed is unbounded, so "superhuman"
//!   scores are drawn, not clipped); one translucent polygon with an outline and markers
//!   per embodiment, colours from a fixed colour-blind-safe palette, a legend, and hollow
//!   markers at 0 for tasks not attempted, listed under the legend.
//! - [`dof_scatter`]: overall score against degrees of freedom, one labelled point per
//!   embodiment, ± one standard deviation as error bars when given.
//! - [`pca_scatter`]: principal component scores (the human study's strategy analysis), one
//!   colour per series, round ticks around the data, light zero lines, a legend.
//! - [`grouped_bars`]: one group of bars per category (task × embodiment, the embodiments
//!   named under their runs of tasks), one bar per series in its colour, ± one standard
//!   deviation as error bars, a legend (the source comparison, `pomdar score --compare`).
//! - [`tracking_grid`]: commanded and measured joint angle over time, one small panel per
//!   joint in a grid (`pomdar tracking`).
//! - [`review_figure()`]: one trial on one time axis: coloured span lanes (drive state, arm,
//!   pinches), stacked series panels with dotted thresholds and tick markers, and progress,
//!   drop and feedback marks drawn across everything.
//!
//! The charts build one drawing description (polylines, polygons, circles, text;
//! `primitives`) which two backends render: an SVG writer (`<text>` in a sans-serif family,
//! escaped) and a tiny-skia rasteriser for the PNG, which draws text with this crate's own
//! stroke font (`glyphs`, `stroke_font`) because tiny-skia has none. Everything is
//! deterministic: the same chart gives the same bytes.

mod chart_frame;
mod compare_bars;
mod compare_chart;
mod compare_layout;
mod dof_chart;
mod error;
mod glyphs;
mod label_placement;
mod legend;
mod palette;
mod pca_chart;
mod png_backend;
mod primitives;
mod radar;
mod radar_chart;
mod radar_layout;
mod review_chart;
mod review_figure;
mod review_layout;
mod review_legend;
mod review_lines;
mod review_paint;
mod review_panel;
mod review_style;
mod scale;
mod stroke_font;
mod svg_backend;
mod tracking_chart;

pub use compare_bars::grouped_bars;
pub use compare_chart::{Bar, BarCategory, BarSeries, GroupedBarChart, MAX_BAR_SERIES};
pub use dof_chart::{DofChart, DofPoint, dof_scatter};
pub use error::{PlotError, ValueProblem};
pub use palette::SERIES_COLORS;
pub use pca_chart::{MAX_SCATTER_SERIES, PcaChart, PcaSeries, pca_scatter};
pub use primitives::Rgba;
pub use radar::radar;
pub use radar_chart::{RadarChart, RadarSeries};
pub use review_chart::{
    MarkKind, ReviewChart, ReviewSeries, SeriesPanel, Span, SpanKind, SpanLane, TimeMark,
};
pub use review_figure::review_figure;
pub use scale::MAX_SCORE;
pub use tracking_chart::{TrackingChart, TrackingPanel, tracking_grid};

/// A rendered figure.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Standalone SVG document.
    pub svg: String,
    /// PNG file bytes (8-bit RGBA).
    pub png: Vec<u8>,
    /// Canvas width in pixels (both formats).
    pub width_px: u32,
    /// Canvas height in pixels (both formats).
    pub height_px: u32,
}

impl Figure {
    fn render(drawing: &primitives::Drawing) -> Result<Self, PlotError> {
        Ok(Self {
            svg: svg_backend::render(drawing),
            png: png_backend::render(drawing)?,
            width_px: drawing.width_px,
            height_px: drawing.height_px,
        })
    }
}
