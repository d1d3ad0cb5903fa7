//! Small multiples of commanded against measured joint angle over time: one panel per joint
//! in a grid of four columns, each with its own angle axis and the same time axis, the
//! command drawn as held until the next one (steps) and the measurement as a line. Long
//! series are thinned to the panel's pixel columns (each column keeps its first, lowest,
//! highest and last point), so a long trial draws the same envelope at a bounded size.

use serde::Serialize;

use super::pca_chart::LinearAxis;
use super::primitives::{Anchor, Drawing, Point, Rgba, Style, Text};
use super::stroke_font::{cap_height, text_width};
use super::{Figure, PlotError, SERIES_COLORS, ValueProblem};

/// One joint's panel: `(seconds, degrees)` points in time order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrackingPanel {
    /// Title above the panel, e.g. `index_mcp  RMS 2.1 deg`.
    pub title: String,
    /// The commands (each held until the next).
    pub commanded: Vec<(f64, f64)>,
    /// The measured angles.
    pub measured: Vec<(f64, f64)>,
}

/// The grid of panels.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrackingChart {
    /// Title above the grid.
    pub title: String,
    /// A grey line under the title.
    pub note: Option<String>,
    /// The panels, left to right, then top to bottom.
    pub panels: Vec<TrackingPanel>,
}

const COLUMNS: usize = 4;
const PANEL_W: f64 = 300.0;
const PANEL_H: f64 = 180.0;
const MARGIN: f64 = 24.0;
const HEADER_H: f64 = 92.0;
const FOOTER_H: f64 = 40.0;
const TITLE_PX: f64 = 20.0;
const NOTE_PX: f64 = 13.0;
const PANEL_TITLE_PX: f64 = 13.0;
const TICK_PX: f64 = 10.0;
const TICK_LEN: f64 = 4.0;
/// Inside a panel: room for the title above and the tick labels left and below.
const INSET_LEFT: f64 = 46.0;
const INSET_RIGHT: f64 = 12.0;
const INSET_TOP: f64 = 24.0;
const INSET_BOTTOM: f64 = 26.0;
/// Least distance between labelled ticks, pixels.
const MIN_LABEL_GAP: f64 = 22.0;

fn commanded_color() -> Rgba {
    SERIES_COLORS[0]
}

fn measured_color() -> Rgba {
    SERIES_COLORS[1]
}

/// The pixel rectangle of a panel's plot area.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Area {
    left: f64,
    right: f64,
    top: f64,
    bottom: f64,
}

/// The grid as SVG and PNG.
pub fn tracking_grid(chart: &TrackingChart) -> Result<Figure, PlotError> {
    Figure::render(&tracking_drawing(chart)?)
}

/// The time range over every panel, or what is wrong with the chart.
fn validate(chart: &TrackingChart) -> Result<(f64, f64), PlotError> {
    if chart.panels.is_empty() {
        return Err(PlotError::NoPanels {
            title: chart.title.clone(),
        });
    }
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for panel in &chart.panels {
        for (series, points) in [
            ("commanded", &panel.commanded),
            ("measured", &panel.measured),
        ] {
            for (index, &(t, v)) in points.iter().enumerate() {
                for (axis, value) in [("time", t), ("angle", v)] {
                    if !value.is_finite() {
                        return Err(PlotError::BadPanelValue {
                            panel: panel.title.clone(),
                            series,
                            index,
                            axis,
                            value,
                            problem: ValueProblem::NotFinite,
                        });
                    }
                }
                (lo, hi) = (lo.min(t), hi.max(t));
            }
        }
    }
    Ok(if lo > hi { (0.0, 1.0) } else { (lo, hi) })
}

/// The grid's drawing.
pub(super) fn tracking_drawing(chart: &TrackingChart) -> Result<Drawing, PlotError> {
    let (t_min, t_max) = validate(chart)?;
    let mut time = LinearAxis::spanning(t_min, t_max);
    if t_min >= 0.0 && time.lo < 0.0 {
        time.lo = 0.0;
    }
    let rows = chart.panels.len().div_ceil(COLUMNS);
    let width = 2.0 * MARGIN + COLUMNS as f64 * PANEL_W;
    let height = HEADER_H + rows as f64 * PANEL_H + FOOTER_H;
    let mut d = Drawing::new(width as u32, height as u32, chart.title.clone());
    draw_header(&mut d, chart, width);
    for (i, panel) in chart.panels.iter().enumerate() {
        let (row, column) = (i / COLUMNS, i % COLUMNS);
        let left = MARGIN + column as f64 * PANEL_W;
        let top = HEADER_H + row as f64 * PANEL_H;
        let area = Area {
            left: left + INSET_LEFT,
            right: left + PANEL_W - INSET_RIGHT,
            top: top + INSET_TOP,
            bottom: top + PANEL_H - INSET_BOTTOM,
        };
        draw_panel(&mut d, panel, area, (time, t_max));
    }
    let at = Point::new(width / 2.0, height - MARGIN + 6.0);
    d.text(Text::new("time (s)", at, Anchor::Middle, NOTE_PX));
    Ok(d)
}

/// The title, the note and the legend.
fn draw_header(d: &mut Drawing, chart: &TrackingChart, width: f64) {
    let at = Point::new(width / 2.0, MARGIN + cap_height(TITLE_PX));
    let mut title = Text::new(chart.title.clone(), at, Anchor::Middle, TITLE_PX);
    title.bold = true;
    d.text(title);
    if let Some(note) = &chart.note {
        let mut note = Text::new(
            note.clone(),
            Point::new(width / 2.0, 64.0),
            Anchor::Middle,
            NOTE_PX,
        );
        note.color = Rgba::GREY;
        d.text(note);
    }
    let mut x = MARGIN;
    let y = 82.0;
    for (label, color, class) in [
        (
            "commanded (held until the next)",
            commanded_color(),
            "legend-commanded",
        ),
        ("measured", measured_color(), "legend-measured"),
    ] {
        let line = vec![Point::new(x, y - 4.0), Point::new(x + 24.0, y - 4.0)];
        d.path(line, false, Style::line(color, 2.0), Some(class));
        d.text(Text::new(
            label,
            Point::new(x + 30.0, y),
            Anchor::Start,
            NOTE_PX,
        ));
        x += 30.0 + text_width(label, NOTE_PX) * 1.15 + 24.0;
    }
}

/// Every `k`-th tick, `k` so that labelled ticks are at least [`MIN_LABEL_GAP`] apart.
fn labelled_every(axis: LinearAxis, span_px: f64) -> usize {
    let steps = ((axis.hi - axis.lo) / axis.step).round().max(1.0);
    let px_per_step = span_px / steps;
    (MIN_LABEL_GAP / px_per_step).ceil().max(1.0) as usize
}

/// One panel: frame, ticks, title, the two series (the last command held until `end`, the
/// chart's last sample).
fn draw_panel(d: &mut Drawing, panel: &TrackingPanel, area: Area, (time, end): (LinearAxis, f64)) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &(_, v) in panel.commanded.iter().chain(&panel.measured) {
        (lo, hi) = (lo.min(v), hi.max(v));
    }
    let angle = if lo > hi {
        LinearAxis::spanning(0.0, 0.0)
    } else {
        LinearAxis::spanning(lo, hi)
    };
    let x = |t: f64| area.left + (t - time.lo) / (time.hi - time.lo) * (area.right - area.left);
    let y =
        |v: f64| area.bottom - (v - angle.lo) / (angle.hi - angle.lo) * (area.bottom - area.top);
    let grid = Rgba::GRID.with_alpha(0.6);
    let every = labelled_every(angle, area.bottom - area.top);
    for (k, v) in angle.ticks().into_iter().enumerate() {
        let py = y(v);
        d.line(
            Point::new(area.left, py),
            Point::new(area.right, py),
            grid,
            1.0,
        );
        if k % every == 0 {
            d.line(
                Point::new(area.left - TICK_LEN, py),
                Point::new(area.left, py),
                Rgba::INK,
                1.0,
            );
            let at = Point::new(area.left - TICK_LEN - 3.0, py + cap_height(TICK_PX) / 2.0);
            d.text(Text::new(angle.label(v), at, Anchor::End, TICK_PX));
        }
    }
    let every = labelled_every(time, area.right - area.left);
    for (k, t) in time.ticks().into_iter().enumerate() {
        let px = x(t);
        d.line(
            Point::new(px, area.top),
            Point::new(px, area.bottom),
            grid,
            1.0,
        );
        if k % every == 0 {
            d.line(
                Point::new(px, area.bottom),
                Point::new(px, area.bottom + TICK_LEN),
                Rgba::INK,
                1.0,
            );
            let at = Point::new(px, area.bottom + TICK_LEN + 3.0 + cap_height(TICK_PX));
            d.text(Text::new(time.label(t), at, Anchor::Middle, TICK_PX));
        }
    }
    let frame = vec![
        Point::new(area.left, area.top),
        Point::new(area.right, area.top),
        Point::new(area.right, area.bottom),
        Point::new(area.left, area.bottom),
    ];
    d.path(frame, true, Style::line(Rgba::INK, 1.0), Some("panel"));
    let mut title = Text::new(
        panel.title.clone(),
        Point::new(area.left, area.top - 8.0),
        Anchor::Start,
        PANEL_TITLE_PX,
    );
    title.bold = true;
    d.text(title);
    let commanded: Vec<Point> = held(&panel.commanded, end)
        .map(|(t, v)| Point::new(x(t), y(v)))
        .collect();
    let measured: Vec<Point> = panel
        .measured
        .iter()
        .map(|&(t, v)| Point::new(x(t), y(v)))
        .collect();
    for (points, color, class) in [
        (commanded, commanded_color(), "commanded"),
        (measured, measured_color(), "measured"),
    ] {
        if !points.is_empty() {
            d.path(thin(&points), false, Style::line(color, 1.3), Some(class));
        }
    }
    if panel.measured.is_empty() {
        let at = Point::new(
            (area.left + area.right) / 2.0,
            (area.top + area.bottom) / 2.0,
        );
        let mut text = Text::new("no measured angles", at, Anchor::Middle, NOTE_PX);
        text.color = Rgba::GREY;
        text.halo = true;
        d.text(text);
    }
}

/// The commands as steps: each held until the next, the last until `end`.
fn held(points: &[(f64, f64)], end: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
    points.iter().enumerate().flat_map(move |(i, &(t, v))| {
        let until = points.get(i + 1).map_or(end.max(t), |p| p.0);
        [(t, v), (until, v)]
    })
}

/// `points` (pixels, left to right) thinned to each pixel column's first, lowest, highest and
/// last point, in their order.
fn thin(points: &[Point]) -> Vec<Point> {
    let mut out = Vec::new();
    let mut start = 0;
    while start < points.len() {
        let column = points[start].x.floor();
        let end = start + points[start..].partition_point(|p| p.x.floor() <= column);
        let bucket = &points[start..end.max(start + 1)];
        let last = bucket.len() - 1;
        let (mut low, mut high) = (0, 0);
        for (k, p) in bucket.iter().enumerate() {
            if p.y > bucket[low].y {
                low = k;
            }
            if p.y < bucket[high].y {
                high = k;
            }
        }
        let mut keep = [0, low, high, last];
        keep.sort_unstable();
        let mut previous = None;
        for k in keep {
            if previous != Some(k) {
                out.push(bucket[k]);
                previous = Some(k);
            }
        }
        start = end.max(start + 1);
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    fn panel(name: &str, n: usize) -> TrackingPanel {
        let commanded = (0..n / 4).map(|k| (k as f64 * 0.04, (k as f64 * 0.1).sin() * 40.0));
        let measured = (0..n).map(|k| (k as f64 * 0.01 + 0.005, (k as f64 * 0.025).sin() * 38.0));
        TrackingPanel {
            title: format!("{name}  RMS 1.2 deg"),
            commanded: commanded.collect(),
            measured: measured.collect(),
        }
    }

    #[test]
    fn one_titled_panel_per_joint_with_both_series() {
        let names: Vec<String> = (0..17).map(|i| format!("joint_{i}")).collect();
        let chart = TrackingChart {
            title: "Commanded vs measured".into(),
            note: Some("trial.mcap".into()),
            panels: names.iter().map(|n| panel(n, 400)).collect(),
        };
        let figure = tracking_grid(&chart).unwrap();
        let doc = roxmltree::Document::parse(&figure.svg).unwrap();
        let texts: Vec<&str> = doc.descendants().filter_map(|n| n.text()).collect();
        for name in &names {
            let title = format!("{name}  RMS 1.2 deg");
            assert!(texts.contains(&title.as_str()), "{title} missing");
        }
        for class in ["panel", "commanded", "measured"] {
            let count = (doc.descendants())
                .filter(|n| n.attribute("class") == Some(class))
                .count();
            assert_eq!(count, 17, "{class}");
        }
        assert_eq!(figure.height_px as f64, HEADER_H + 5.0 * PANEL_H + FOOTER_H);
        assert!(figure.png.starts_with(b"\x89PNG"));
        assert_eq!(figure, tracking_grid(&chart).unwrap(), "deterministic");
    }

    #[test]
    fn a_long_series_is_thinned_to_its_pixel_columns() {
        let chart = TrackingChart {
            title: "long".into(),
            note: None,
            panels: vec![panel("long", 200_000)],
        };
        let d = tracking_drawing(&chart).unwrap();
        let drawn = d.items.iter().find_map(|item| match item {
            super::super::primitives::Primitive::Path {
                points,
                class: Some("measured"),
                ..
            } => Some(points.len()),
            _ => None,
        });
        let drawn = drawn.unwrap();
        assert!(drawn <= 4 * (PANEL_W as usize), "{drawn} points drawn");
        assert!(drawn > PANEL_W as usize, "{drawn} points drawn");
    }

    #[test]
    fn bad_values_and_no_panels_are_named() {
        let mut bad = panel("index_mcp", 40);
        bad.measured[3].1 = f64::NAN;
        let chart = TrackingChart {
            title: "t".into(),
            note: None,
            panels: vec![bad],
        };
        let error = tracking_grid(&chart).unwrap_err().to_string();
        assert!(
            error.contains("index_mcp") && error.contains("measured"),
            "{error}"
        );
        let empty = TrackingChart {
            title: "t".into(),
            note: None,
            panels: vec![],
        };
        assert!(matches!(
            tracking_grid(&empty),
            Err(PlotError::NoPanels { .. })
        ));
    }
}
