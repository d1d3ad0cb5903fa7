//! Painting one panel of the trial review figure: value grid and ticks, the time grid,
//! dotted thresholds labelled in the right margin, the series (dashed where asked, broken at
//! gaps), the tick markers on the bottom edge, the frame, and the title, unit and legend.

use super::palette::series_color;
use super::primitives::{Anchor, Drawing, Point, Rgba, Style, Text};
use super::review_chart::{ReviewSeries, SeriesPanel};
use super::review_layout::{Layout, PanelBox};
use super::review_legend::{LegendItem, unit_text};
use super::review_lines::{dashes, runs, thin};
use super::review_paint::{corners, fill, time_grid};
use super::review_style::{LABEL_PX, SMALL_PX, SWATCH_GAP, SWATCH_W, TICK_LEN, TICK_PX, width_of};
use super::stroke_font::cap_height;

/// Series stroke width, pixels.
const SERIES_W: f64 = 1.5;
/// A dashed series' pattern (on, off), pixels.
const DASH: (f64, f64) = (7.0, 4.0);
/// A threshold's pattern (on, off), pixels; round caps make the short dashes dots.
const DOT: (f64, f64) = (1.0, 4.0);
const THRESHOLD: Rgba = Rgba::rgb(0x44, 0x44, 0x44);
const TICK_MARK: Rgba = Rgba::rgb(0x33, 0x33, 0x33);
/// A tick marker's height (and width), pixels.
const TICK_MARK_H: f64 = 7.0;
/// Least distance between labelled value ticks, pixels.
const MIN_LABEL_GAP: f64 = 18.0;
/// Least distance between threshold labels' baselines, pixels.
const THRESHOLD_LABEL_GAP: f64 = 12.0;

/// The y of `value` in the panel.
fn y_of(b: &PanelBox, value: f64) -> f64 {
    let (lo, hi) = (b.axis.lo, b.axis.hi);
    b.area.bottom - (value - lo) / (hi - lo) * b.area.height()
}

/// One panel in its box.
pub(super) fn panel(d: &mut Drawing, panel: &SeriesPanel, b: &PanelBox, layout: &Layout) {
    value_grid(d, b);
    time_grid(d, layout, b.area.top, b.area.bottom);
    thresholds(d, panel, b);
    let mut drawn = false;
    for series in &panel.series {
        drawn |= draw_series(d, series, b, layout);
    }
    ticks(d, panel, b, layout);
    d.path(
        corners(b.area),
        true,
        Style::line(Rgba::INK, 1.0),
        Some("panel"),
    );
    header(d, panel, b);
    if !drawn {
        let at = Point::new(
            (b.area.left + b.area.right) / 2.0,
            (b.area.top + b.area.bottom + cap_height(LABEL_PX)) / 2.0,
        );
        let mut text = Text::new("no data", at, Anchor::Middle, LABEL_PX);
        (text.color, text.halo) = (Rgba::GREY, true);
        d.text(text);
    }
}

/// Horizontal grid lines at the value ticks, labelled (at least [`MIN_LABEL_GAP`] apart)
/// left of the panel.
fn value_grid(d: &mut Drawing, b: &PanelBox) {
    let ticks = b.axis.ticks();
    let px_per_step = b.area.height() / (ticks.len().max(2) - 1) as f64;
    let every = (MIN_LABEL_GAP / px_per_step).ceil().max(1.0) as usize;
    for (k, v) in ticks.into_iter().enumerate() {
        let y = y_of(b, v);
        let (left, right) = (b.area.left, b.area.right);
        let grid = Rgba::GRID.with_alpha(0.6);
        d.line(Point::new(left, y), Point::new(right, y), grid, 1.0);
        if k % every == 0 {
            d.line(
                Point::new(left - TICK_LEN, y),
                Point::new(left, y),
                Rgba::INK,
                1.0,
            );
            let at = Point::new(left - TICK_LEN - 3.0, y + cap_height(TICK_PX) / 2.0);
            d.text(Text::new(b.axis.label(v), at, Anchor::End, TICK_PX));
        }
    }
}

/// Dotted lines at the thresholds, labelled right of the panel (pushed apart downwards).
fn thresholds(d: &mut Drawing, panel: &SeriesPanel, b: &PanelBox) {
    let mut lines: Vec<(f64, &str)> = (panel.thresholds.iter())
        .map(|(v, label)| (y_of(b, *v), label.as_str()))
        .collect();
    lines.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut previous = f64::NEG_INFINITY;
    for (y, label) in lines {
        let line = [Point::new(b.area.left, y), Point::new(b.area.right, y)];
        for dot in dashes(&line, DOT) {
            d.path(dot, false, Style::line(THRESHOLD, 1.6), Some("threshold"));
        }
        if label.is_empty() {
            continue;
        }
        let baseline = (y + cap_height(SMALL_PX) / 2.0).max(previous + THRESHOLD_LABEL_GAP);
        previous = baseline;
        let at = Point::new(b.area.right + 6.0, baseline);
        let mut text = Text::new(label, at, Anchor::Start, SMALL_PX);
        text.color = THRESHOLD;
        d.text(text);
    }
}

/// One series: its runs between gaps as polylines (dashed: as dashes), a lone point as a
/// dot. Whether anything was drawn.
fn draw_series(d: &mut Drawing, series: &ReviewSeries, b: &PanelBox, layout: &Layout) -> bool {
    let color = series_color(series.color);
    let to_px = |t: f64, v: f64| Point::new(layout.x(t), y_of(b, v));
    let runs = runs(&series.points, layout.duration, to_px);
    for run in &runs {
        if let [point] = run.as_slice() {
            d.circle(*point, SERIES_W, fill(color), Some("series-dot"));
        } else if series.dashed {
            for dash in dashes(&thin(run), DASH) {
                d.path(
                    dash,
                    false,
                    Style::line(color, SERIES_W),
                    Some("series-dash"),
                );
            }
        } else {
            d.path(
                thin(run),
                false,
                Style::line(color, SERIES_W),
                Some("series"),
            );
        }
    }
    !runs.is_empty()
}

/// A small upward triangle standing on `base`.
fn tick_marker(base: Point) -> Vec<Point> {
    vec![
        Point::new(base.x - TICK_MARK_H / 2.0, base.y),
        Point::new(base.x + TICK_MARK_H / 2.0, base.y),
        Point::new(base.x, base.y - TICK_MARK_H),
    ]
}

/// The ticks as markers on the bottom edge, one per pixel column at most.
fn ticks(d: &mut Drawing, panel: &SeriesPanel, b: &PanelBox, layout: &Layout) {
    let mut columns: Vec<i64> = (panel.ticks.iter())
        .filter(|t| (0.0..=layout.duration).contains(*t))
        .map(|&t| layout.x(t).round() as i64)
        .collect();
    columns.sort_unstable();
    columns.dedup();
    for x in columns {
        let base = Point::new(x as f64, b.area.bottom);
        d.path(tick_marker(base), true, fill(TICK_MARK), Some("tick"));
    }
}

/// The title, the unit in grey after it, and the legend.
fn header(d: &mut Drawing, panel: &SeriesPanel, b: &PanelBox) {
    let at = Point::new(b.area.left, b.title_baseline);
    let mut title = Text::new(panel.title.clone(), at, Anchor::Start, LABEL_PX);
    title.bold = true;
    d.text(title);
    let unit = unit_text(panel);
    if !unit.is_empty() {
        let x = b.area.left + width_of(&panel.title, LABEL_PX) + 6.0;
        let mut text = Text::new(
            unit,
            Point::new(x, b.title_baseline),
            Anchor::Start,
            LABEL_PX,
        );
        text.color = Rgba::GREY;
        d.text(text);
    }
    for (item, label, at) in &b.legend {
        let mid = at.y - cap_height(SMALL_PX) / 2.0;
        match *item {
            LegendItem::Series(i) => {
                let series = &panel.series[i];
                let style = Style::line(series_color(series.color), 2.0);
                let line = [Point::new(at.x, mid), Point::new(at.x + SWATCH_W, mid)];
                let pieces = if series.dashed {
                    dashes(&line, (5.0, 3.0))
                } else {
                    vec![line.to_vec()]
                };
                for piece in pieces {
                    d.path(piece, false, style, Some("legend"));
                }
            }
            LegendItem::Ticks => {
                let base = Point::new(at.x + SWATCH_W / 2.0, mid + TICK_MARK_H / 2.0);
                d.path(tick_marker(base), true, fill(TICK_MARK), Some("legend"));
            }
        }
        let at = Point::new(at.x + SWATCH_W + SWATCH_GAP, at.y);
        d.text(Text::new(label.clone(), at, Anchor::Start, SMALL_PX));
    }
}
