//! The grouped bar chart's layout and drawing: the canvas grows with the categories (never
//! narrower than the other charts), the y axis is the score axis, the embodiments' bands are
//! separated by light lines and named under bracket lines, the legend flows below.

use super::chart_frame::{
    AXIS_TITLE_PX, HEIGHT_PX, MARGIN_PX, NOTE_PX, TICK_LEN_PX, TICK_PX, TITLE_PX, WIDTH_PX,
    draw_score_ticks,
};
use super::compare_chart::{Bar, GroupedBarChart};
use super::label_placement::Rect;
use super::legend::{self, LegendEntry};
use super::palette::series_color;
use super::primitives::{Anchor, Drawing, Point, Rgba, Style, Text};
use super::scale::{ScoreAxis, score_axis};
use super::stroke_font::{FONT_SLACK, cap_height, text_width};

/// Widest bar, pixels.
const MAX_BAR_W_PX: f64 = 40.0;
/// Narrowest bar the canvas is widened for, pixels.
const MIN_BAR_W_PX: f64 = 14.0;
/// Room left and right of a category's bars, pixels (together).
const CATEGORY_PAD_PX: f64 = 20.0;
/// Plot area height, pixels.
const PLOT_H_PX: f64 = 330.0;
/// Between note lines under the title, pixels.
const NOTE_LINE_PX: f64 = 17.0;
/// Band label text size, pixels.
const BAND_PX: f64 = 14.0;
const ERROR_CAP_HALF_PX: f64 = 5.0;
const HOLLOW_RADIUS_PX: f64 = 4.5;
const NO_BAR_KEY: &str = "Hollow marker at 0 = no trials of the group there";

/// The plot area and the data-to-pixel mapping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarGeometry {
    /// Plot area in pixels.
    pub area: Rect,
    /// Width of one category, pixels.
    pub category_w: f64,
    /// Width of one bar, pixels.
    pub bar_w: f64,
    /// Number of series.
    pub series: usize,
    /// Y axis from 0.
    pub scale: ScoreAxis,
}

impl BarGeometry {
    /// Pixel y of `value`.
    pub fn y(&self, value: f64) -> f64 {
        self.area.bottom - value / self.scale.top() * self.area.height()
    }

    /// Left and right pixel x of the bar of series `s` in category `c`.
    pub fn bar_x(&self, c: usize, s: usize) -> (f64, f64) {
        let start = self.area.left
            + c as f64 * self.category_w
            + (self.category_w - self.bar_w * self.series as f64) / 2.0;
        let left = start + s as f64 * self.bar_w;
        (left, left + self.bar_w)
    }

    /// Pixel x of the middle of category `c`.
    pub fn category_mid(&self, c: usize) -> f64 {
        self.area.left + (c as f64 + 0.5) * self.category_w
    }
}

/// The notes under the title: the chart's, the error-bar key, the hollow-marker key.
fn note_lines(chart: &GroupedBarChart) -> Vec<String> {
    let mut lines = chart.notes.clone();
    let bars = || chart.series.iter().flat_map(|s| &s.values);
    if bars().flatten().any(|b| b.std.is_some()) {
        lines.push("Error bars: \u{b1}1 standard deviation".to_string());
    }
    if bars().any(Option::is_none) {
        lines.push(NO_BAR_KEY.to_string());
    }
    lines
}

/// The geometry: the canvas is widened when the categories need more room.
fn layout(chart: &GroupedBarChart, scale: ScoreAxis, notes: usize) -> (BarGeometry, f64) {
    let tick_w = scale
        .ticks()
        .map(|t| text_width(&scale.label(t), TICK_PX))
        .fold(text_width("0.0", TICK_PX), f64::max);
    let left = MARGIN_PX + cap_height(AXIS_TITLE_PX) + 14.0 + FONT_SLACK * tick_w + 8.0;
    let series = chart.series.len();
    let widest_label = (chart.categories.iter())
        .map(|c| FONT_SLACK * text_width(&c.label, TICK_PX) + 8.0)
        .fold(0.0, f64::max);
    let widest_band = (band_runs(chart).into_iter())
        .map(|(start, end)| {
            let name = &chart.categories[start].band;
            (FONT_SLACK * text_width(name, BAND_PX) + 16.0) / (end - start) as f64
        })
        .fold(0.0, f64::max);
    let least_category = (series as f64 * MIN_BAR_W_PX + CATEGORY_PAD_PX)
        .max(widest_label)
        .max(widest_band);
    let n = chart.categories.len() as f64;
    let width = WIDTH_PX.max(left + TICK_LEN_PX + n * least_category + 30.0);
    let top = (64.0 + NOTE_LINE_PX * notes as f64).max(84.0);
    let area = Rect {
        left: left + TICK_LEN_PX,
        right: width - 30.0,
        top,
        bottom: top + PLOT_H_PX,
    };
    let category_w = area.width() / n;
    let bar_w = ((category_w - CATEGORY_PAD_PX) / series as f64).min(MAX_BAR_W_PX);
    let geometry = BarGeometry {
        area,
        category_w,
        bar_w,
        series,
        scale,
    };
    (geometry, width)
}

/// Draws `chart` (validated, data up to `max`).
pub fn draw(chart: &GroupedBarChart, max: f64) -> (Drawing, BarGeometry) {
    let notes = note_lines(chart);
    let (g, width) = layout(chart, score_axis(max), notes.len());
    let mut d = Drawing::new(width.round() as u32, HEIGHT_PX as u32, chart.title.clone());
    draw_title(&mut d, chart, &notes, width);
    draw_y_axis(&mut d, &g, &chart.y_label);
    draw_bars(&mut d, &g, chart);
    let below = draw_x_axis(&mut d, &g, chart);
    let entries: Vec<LegendEntry> = (chart.series.iter().enumerate())
        .map(|(i, s)| LegendEntry {
            label: s.label.clone(),
            color: series_color(i),
            fill_alpha: 1.0,
        })
        .collect();
    let last = legend::draw(&mut d, &entries, below + 6.0, width, MARGIN_PX);
    d.height_px = (last + MARGIN_PX + 4.0).ceil() as u32;
    (d, g)
}

fn draw_title(d: &mut Drawing, chart: &GroupedBarChart, notes: &[String], width: f64) {
    let mut title = Text::new(
        chart.title.clone(),
        Point::new(width / 2.0, MARGIN_PX + cap_height(TITLE_PX)),
        Anchor::Middle,
        TITLE_PX,
    );
    title.bold = true;
    d.text(title);
    for (i, line) in notes.iter().enumerate() {
        let at = Point::new(width / 2.0, 64.0 + NOTE_LINE_PX * i as f64);
        let mut note = Text::new(line.clone(), at, Anchor::Middle, NOTE_PX);
        note.color = Rgba::GREY;
        d.text(note);
    }
}

/// Grid lines, ticks, tick labels and the title of the y axis.
fn draw_y_axis(d: &mut Drawing, g: &BarGeometry, y_label: &str) {
    let area = g.area;
    draw_score_ticks(d, area, &g.scale);
    let mut title = Text::new(
        y_label,
        Point::new(
            MARGIN_PX + cap_height(AXIS_TITLE_PX),
            (area.top + area.bottom) / 2.0,
        ),
        Anchor::Middle,
        AXIS_TITLE_PX,
    );
    title.rotate_deg = -90.0;
    d.text(title);
}

/// Every bar with its error bar, or a hollow marker where a series has no value.
fn draw_bars(d: &mut Drawing, g: &BarGeometry, chart: &GroupedBarChart) {
    for (s, series) in chart.series.iter().enumerate() {
        let color = series_color(s);
        for (c, value) in series.values.iter().enumerate() {
            let (left, right) = g.bar_x(c, s);
            let Some(Bar { mean, std }) = *value else {
                let hollow = Style::filled_and_outlined(Rgba::WHITE, color, 2.0);
                let at = Point::new((left + right) / 2.0, g.area.bottom);
                d.circle(at, HOLLOW_RADIUS_PX, hollow, Some("no-bar"));
                continue;
            };
            let (top, bottom) = (g.y(mean), g.area.bottom);
            let outline = vec![
                Point::new(left + 1.0, bottom),
                Point::new(left + 1.0, top),
                Point::new(right - 1.0, top),
                Point::new(right - 1.0, bottom),
            ];
            let style = Style::filled_and_outlined(color, color, 1.0);
            d.path(outline, true, style, Some("bar"));
            if let Some(std) = std {
                draw_error_bar(
                    d,
                    (left + right) / 2.0,
                    g.y(mean + std),
                    g.y((mean - std).max(0.0)),
                );
            }
        }
    }
}

fn draw_error_bar(d: &mut Drawing, x: f64, top: f64, bottom: f64) {
    let ink = Style::line(Rgba::INK, 1.6);
    d.path(
        vec![Point::new(x, top), Point::new(x, bottom)],
        false,
        ink,
        Some("error-bar"),
    );
    for y in [top, bottom] {
        d.line(
            Point::new(x - ERROR_CAP_HALF_PX, y),
            Point::new(x + ERROR_CAP_HALF_PX, y),
            Rgba::INK,
            1.6,
        );
    }
}

/// The runs of consecutive categories with the same band, as `(first, one past the last)`.
fn band_runs(chart: &GroupedBarChart) -> Vec<(usize, usize)> {
    let mut runs: Vec<(usize, usize)> = Vec::new();
    for (c, category) in chart.categories.iter().enumerate() {
        match runs.last_mut() {
            Some(run) if chart.categories[run.0].band == category.band => run.1 = c + 1,
            _ => runs.push((c, c + 1)),
        }
    }
    runs
}

/// The axis lines, category labels, band brackets and names, the x axis title; returns the
/// title's baseline.
fn draw_x_axis(d: &mut Drawing, g: &BarGeometry, chart: &GroupedBarChart) -> f64 {
    let area = g.area;
    let axes = vec![
        Point::new(area.left, area.top),
        Point::new(area.left, area.bottom),
        Point::new(area.right, area.bottom),
    ];
    d.path(axes, false, Style::line(Rgba::INK, 1.2), Some("axes"));
    let label_y = area.bottom + TICK_LEN_PX + 6.0 + cap_height(TICK_PX);
    for (c, category) in chart.categories.iter().enumerate() {
        let at = Point::new(g.category_mid(c), label_y);
        d.text(Text::new(
            category.label.clone(),
            at,
            Anchor::Middle,
            TICK_PX,
        ));
    }
    let bracket_y = label_y + 8.0;
    let band_y = bracket_y + 6.0 + cap_height(BAND_PX);
    for (start, end) in band_runs(chart) {
        let left = area.left + start as f64 * g.category_w;
        let right = area.left + end as f64 * g.category_w;
        if start > 0 {
            let separator = (Point::new(left, area.top), Point::new(left, area.bottom));
            d.line(separator.0, separator.1, Rgba::GRID, 1.0);
        }
        let bracket = vec![
            Point::new(left + 6.0, bracket_y),
            Point::new(right - 6.0, bracket_y),
        ];
        d.path(bracket, false, Style::line(Rgba::GREY, 1.2), Some("band"));
        let at = Point::new((left + right) / 2.0, band_y);
        let mut name = Text::new(
            chart.categories[start].band.clone(),
            at,
            Anchor::Middle,
            BAND_PX,
        );
        name.bold = true;
        d.text(name);
    }
    let title_y = band_y + 16.0 + cap_height(AXIS_TITLE_PX);
    let at = Point::new((area.left + area.right) / 2.0, title_y);
    d.text(Text::new(
        chart.x_label.clone(),
        at,
        Anchor::Middle,
        AXIS_TITLE_PX,
    ));
    title_y
}
