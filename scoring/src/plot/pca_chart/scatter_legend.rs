//! The scatter's markers (a colour per series; past eight series, a second and third marker
//! style) and its legend: a marker and a label per series, in centred rows.

use super::super::palette::{SERIES_COLORS, series_color};
use super::super::primitives::{Anchor, Drawing, Point, Rgba, Style, Text};
use super::super::stroke_font::{FONT_SLACK, cap_height, text_width};
use super::{MARGIN_PX, POINT_RADIUS_PX, PcaChart, WIDTH_PX};

/// Marker styles: translucent disc, ring, translucent disc with a dark outline.
pub(super) const MARKER_STYLES: usize = 3;
/// Height of one legend row.
pub(super) const LEGEND_ROW_PX: f64 = 22.0;
const LEGEND_PX: f64 = 14.0;
const LEGEND_ENTRY_GAP_PX: f64 = 24.0;

/// Series `index`'s marker: its colour, in the style of its group of eight.
pub(super) fn marker_style(index: usize) -> Style {
    let color = series_color(index);
    match (index / SERIES_COLORS.len()) % MARKER_STYLES {
        0 => Style::filled_and_outlined(color.with_alpha(0.55), color.with_alpha(0.9), 0.8),
        1 => Style::line(color, 2.0),
        _ => Style::filled_and_outlined(color.with_alpha(0.55), Rgba::INK, 1.5),
    }
}

fn legend_entry_width(label: &str) -> f64 {
    2.0 * POINT_RADIUS_PX + 6.0 + FONT_SLACK * text_width(label, LEGEND_PX)
}

/// Series indices in legend rows: as many entries per row as fit in the canvas' width.
pub(super) fn legend_rows(chart: &PcaChart) -> Vec<Vec<usize>> {
    let max_w = WIDTH_PX - 2.0 * MARGIN_PX;
    let mut rows: Vec<Vec<usize>> = Vec::new();
    let mut row_w = 0.0;
    for (i, s) in chart.series.iter().enumerate() {
        let w = legend_entry_width(&s.label);
        match rows.last_mut() {
            Some(row) if row_w + LEGEND_ENTRY_GAP_PX + w <= max_w => {
                row.push(i);
                row_w += LEGEND_ENTRY_GAP_PX + w;
            }
            _ => {
                rows.push(vec![i]);
                row_w = w;
            }
        }
    }
    rows
}

/// A marker and a label per series, in centred rows below `top`.
pub(super) fn draw_legend(d: &mut Drawing, chart: &PcaChart, rows: &[Vec<usize>], top: f64) {
    let mut baseline = top;
    for row in rows {
        baseline += LEGEND_ROW_PX;
        let widths: Vec<f64> = (row.iter())
            .map(|&i| legend_entry_width(&chart.series[i].label))
            .collect();
        let total = widths.iter().sum::<f64>() + LEGEND_ENTRY_GAP_PX * (row.len() as f64 - 1.0);
        let mut x = ((WIDTH_PX - total) / 2.0).max(MARGIN_PX);
        for (&i, w) in row.iter().zip(widths) {
            let marker = Point::new(x + POINT_RADIUS_PX, baseline - cap_height(LEGEND_PX) / 2.0);
            d.circle(
                marker,
                POINT_RADIUS_PX,
                marker_style(i),
                Some("legend-marker"),
            );
            let at = Point::new(x + 2.0 * POINT_RADIUS_PX + 6.0, baseline);
            let label = chart.series[i].label.clone();
            d.text(Text::new(label, at, Anchor::Start, LEGEND_PX));
            x += w + LEGEND_ENTRY_GAP_PX;
        }
    }
}
