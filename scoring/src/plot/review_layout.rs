//! The trial review figure's geometry: where the title, the key, the mark labels, every lane
//! and every panel go, each panel's value axis and legend slots, and the shared time axis.
//! The canvas is a fixed width and grows downwards with lanes, panels and legend rows.

use super::label_placement::Rect;
use super::pca_chart::LinearAxis;
use super::primitives::Point;
use super::review_chart::{ReviewChart, SeriesPanel};
use super::review_legend::{KeyItem, LegendItem, flow, key_slots, legend_items, unit_text};
use super::review_style::{
    KEY_ROW, LABEL_PX, LANE_H, MARGIN, SMALL_PX, SWATCH_GAP, SWATCH_W, TICK_LEN, TICK_PX, TITLE_PX,
    WIDTH, width_of,
};
use super::stroke_font::cap_height;

const LANE_GAP: f64 = 3.0;
const MARK_ROW: f64 = 14.0;
const MAX_MARK_ROWS: usize = 4;
const PLOT_H: f64 = 130.0;
const LEGEND_ROW: f64 = 16.0;
const PANEL_GAP: f64 = 16.0;
const BLOCK_GAP: f64 = 12.0;
const AXIS_H: f64 = 44.0;
/// Least distance between time ticks, pixels.
const MIN_TIME_STEP_PX: f64 = 64.0;

/// A mark's label: which mark, its box, its baseline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct MarkLabel {
    /// Index into the chart's marks.
    pub mark: usize,
    /// The label's box (horizontal centre = text centre).
    pub rect: Rect,
}

/// A panel's place.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct PanelBox {
    /// Baseline of the title (and of the legend's first row).
    pub title_baseline: f64,
    /// The plot area.
    pub area: Rect,
    /// The value axis.
    pub axis: LinearAxis,
    /// The legend's entries with their swatch's left end on their baseline.
    pub legend: Vec<(LegendItem, String, Point)>,
}

/// Where everything goes.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Layout {
    /// Canvas height, pixels.
    pub height: f64,
    /// The time axis' left end (time 0), pixels.
    pub left: f64,
    /// The time axis' right end (the duration), pixels.
    pub right: f64,
    /// The duration, seconds.
    pub duration: f64,
    /// The headline's baseline and size.
    pub title: (f64, f64),
    /// The key under the title.
    pub key: Vec<(KeyItem, Point)>,
    /// The mark labels.
    pub marks: Vec<MarkLabel>,
    /// Each lane's top edge.
    pub lane_tops: Vec<f64>,
    /// The panels.
    pub panels: Vec<PanelBox>,
    /// The time axis' y (bottom of the last lane or panel).
    pub bottom: f64,
    /// Seconds between time ticks.
    pub time_step: f64,
}

impl Layout {
    /// The figure's layout; `chart` is valid (`review_chart::validate`).
    pub fn new(chart: &ReviewChart) -> Self {
        let axes: Vec<LinearAxis> = (chart.panels.iter())
            .map(|p| value_axis(p, chart.duration_s))
            .collect();
        let left = MARGIN + left_gutter(chart, &axes);
        let right = WIDTH - MARGIN - right_gutter(chart);
        let title_px = TITLE_PX
            .min(TITLE_PX * (WIDTH - 2.0 * MARGIN) / width_of(&chart.title, TITLE_PX).max(1.0));
        let title = (MARGIN + cap_height(TITLE_PX), title_px);
        let (key, key_rows) = key_slots(chart, title.0 + KEY_ROW + 4.0);
        let mut layout = Self {
            height: 0.0,
            left,
            right,
            duration: chart.duration_s,
            title,
            key,
            marks: Vec::new(),
            lane_tops: Vec::new(),
            panels: Vec::new(),
            bottom: 0.0,
            time_step: time_step((right - left) / chart.duration_s),
        };
        let mut y = title.0 + key_rows as f64 * KEY_ROW + 12.0;
        y = layout.place_marks(chart, y);
        for _ in &chart.lanes {
            layout.lane_tops.push(y);
            y += LANE_H + LANE_GAP;
        }
        layout.bottom = y - LANE_GAP;
        y += BLOCK_GAP;
        for (panel, axis) in chart.panels.iter().zip(axes) {
            let panel_box = layout.panel_box(panel, axis, y);
            layout.bottom = panel_box.area.bottom;
            y = panel_box.area.bottom + PANEL_GAP;
            layout.panels.push(panel_box);
        }
        layout.height = (layout.bottom + AXIS_H + MARGIN / 2.0).ceil();
        layout
    }

    /// The x of time `t` (clamped to the axis).
    pub fn x(&self, t: f64) -> f64 {
        self.left + t.clamp(0.0, self.duration) / self.duration * (self.right - self.left)
    }

    /// The time ticks from 0 to the duration.
    pub fn time_ticks(&self) -> Vec<f64> {
        let n = (self.duration / self.time_step + 1e-9).floor() as usize;
        (0..=n).map(|k| k as f64 * self.time_step).collect()
    }

    /// A time tick as text, with as many decimals as the step needs.
    pub fn time_label(&self, t: f64) -> String {
        let decimals = (-(self.time_step.log10() + 1e-9).floor()).max(0.0) as usize;
        format!("{t:.decimals$}")
    }

    /// The mark labels in rows (the first nearest the lanes) from `top`, in time order, each
    /// in the first row where it overlaps no other; a label with no such row among
    /// [`MAX_MARK_ROWS`] is left out (its line is still drawn). Returns the y under the rows.
    fn place_marks(&mut self, chart: &ReviewChart, top: f64) -> f64 {
        let mut order: Vec<usize> = (0..chart.marks.len())
            .filter(|&i| {
                let mark = &chart.marks[i];
                !mark.label.is_empty() && (0.0..=chart.duration_s).contains(&mark.t_s)
            })
            .collect();
        order.sort_by(|&a, &b| chart.marks[a].t_s.total_cmp(&chart.marks[b].t_s));
        let mut placed: Vec<(usize, usize, f64, f64)> = Vec::new();
        for i in order {
            let half = width_of(&chart.marks[i].label, SMALL_PX) / 2.0 + 2.0;
            let centre = (self.x(chart.marks[i].t_s).max(MARGIN + half)).min(WIDTH - MARGIN - half);
            let (l, r) = (centre - half, centre + half);
            let overlap = |row: usize| -> f64 {
                (placed.iter().filter(|p| p.1 == row))
                    .map(|p| (r.min(p.3) - l.max(p.2)).max(0.0))
                    .sum()
            };
            let Some(row) = (0..MAX_MARK_ROWS).find(|&row| overlap(row) == 0.0) else {
                continue;
            };
            placed.push((i, row, l, r));
        }
        let rows = placed.iter().map(|p| p.1 + 1).max().unwrap_or(0);
        let bottom = top + rows as f64 * MARK_ROW + 4.0;
        self.marks = (placed.into_iter())
            .map(|(mark, row, left, right)| {
                let baseline = bottom - 6.0 - row as f64 * MARK_ROW;
                let rect = Rect {
                    left,
                    right,
                    top: baseline - cap_height(SMALL_PX) - 1.0,
                    bottom: baseline + 3.0,
                };
                MarkLabel { mark, rect }
            })
            .collect();
        bottom
    }

    /// A panel's box with its header from `top`.
    fn panel_box(&self, panel: &SeriesPanel, axis: LinearAxis, top: f64) -> PanelBox {
        let title_baseline = top + cap_height(LABEL_PX) + 4.0;
        let header_w = width_of(&panel.title, LABEL_PX) + width_of(&unit_text(panel), LABEL_PX);
        let items = legend_items(panel);
        let widths: Vec<f64> = (items.iter())
            .map(|(_, label)| SWATCH_W + SWATCH_GAP + width_of(label, SMALL_PX))
            .collect();
        let slots = flow(&widths, self.left + header_w + 28.0, self.left, self.right);
        let rows = slots.iter().map(|s| s.0 + 1).max().unwrap_or(1);
        let legend = (items.into_iter().zip(slots))
            .map(|((item, label), (row, x))| {
                let at = Point::new(x, title_baseline + row as f64 * LEGEND_ROW);
                (item, label, at)
            })
            .collect();
        let area_top = title_baseline + (rows - 1) as f64 * LEGEND_ROW + 8.0;
        let area = Rect {
            left: self.left,
            right: self.right,
            top: area_top,
            bottom: area_top + PLOT_H,
        };
        PanelBox {
            title_baseline,
            area,
            axis,
            legend,
        }
    }
}

/// A panel's value axis: round ticks around its finite values in the time range and its
/// thresholds, from 0 when nothing is negative; 0 to 1 when there is nothing.
fn value_axis(panel: &SeriesPanel, duration: f64) -> LinearAxis {
    let values = (panel.series.iter())
        .flat_map(|s| &s.points)
        .filter(|(t, v)| (0.0..=duration).contains(t) && v.is_finite())
        .map(|&(_, v)| v)
        .chain(panel.thresholds.iter().map(|h| h.0));
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if lo > hi {
        return LinearAxis {
            lo: 0.0,
            hi: 1.0,
            step: 0.2,
        };
    }
    let mut axis = LinearAxis::spanning(lo, hi);
    if lo >= 0.0 && axis.lo < 0.0 {
        axis.lo = 0.0;
    }
    axis
}

/// Room left of the time axis for the lane labels and the value tick labels.
fn left_gutter(chart: &ReviewChart, axes: &[LinearAxis]) -> f64 {
    let lanes = (chart.lanes.iter()).map(|l| width_of(&l.label, LABEL_PX) + 10.0);
    let ticks = (axes.iter())
        .flat_map(|a| a.ticks().into_iter().map(|v| a.label(v)))
        .map(|label| width_of(&label, TICK_PX) + TICK_LEN + 6.0);
    lanes.chain(ticks).fold(40.0, f64::max)
}

/// Room right of the time axis for the threshold labels.
fn right_gutter(chart: &ReviewChart) -> f64 {
    (chart.panels.iter())
        .flat_map(|p| &p.thresholds)
        .map(|(_, label)| width_of(label, SMALL_PX) + 10.0)
        .fold(16.0, f64::max)
}

/// The round step (1, 2 or 5 times a power of ten) that puts time ticks at least
/// [`MIN_TIME_STEP_PX`] apart.
fn time_step(px_per_s: f64) -> f64 {
    let raw = MIN_TIME_STEP_PX / px_per_s;
    let power = 10_f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * power)
        .find(|&step| step >= raw * (1.0 - 1e-9))
        .unwrap_or(10.0 * power)
}
