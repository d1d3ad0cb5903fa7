//! The trial review figure's legends: the key of span and mark kinds under the title and
//! each panel's legend of series and ticks, flowed into rows.

use super::primitives::Point;
use super::review_chart::{
    MarkKind, ReviewChart, SeriesPanel, SpanKind, mark_kinds, mark_style, span_kinds, span_style,
};
use super::review_style::{ENTRY_GAP, KEY_ROW, MARGIN, SMALL_PX, SWATCH_GAP, WIDTH, width_of};

/// One entry of the key under the title.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum KeyItem {
    /// A span kind's swatch.
    Span(SpanKind),
    /// A mark kind's line.
    Mark(MarkKind),
}

/// One entry of a panel's legend.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum LegendItem {
    /// The series with this index.
    Series(usize),
    /// The panel's ticks.
    Ticks,
}

/// The unit as drawn after a panel's title: `(mm)`, or nothing.
pub(super) fn unit_text(panel: &SeriesPanel) -> String {
    if panel.unit.is_empty() {
        String::new()
    } else {
        format!("({})", panel.unit)
    }
}

/// A panel's legend: its labelled series, then its ticks when they have a label.
pub(super) fn legend_items(panel: &SeriesPanel) -> Vec<(LegendItem, String)> {
    let series = (panel.series.iter().enumerate())
        .filter(|(_, s)| !s.label.is_empty())
        .map(|(i, s)| (LegendItem::Series(i), s.label.clone()));
    let ticks = (!panel.ticks.is_empty() && !panel.ticks_label.is_empty())
        .then(|| (LegendItem::Ticks, panel.ticks_label.clone()));
    series.chain(ticks).collect()
}

/// Entries of `widths` flowed left to right from `first_x`, wrapping to `row_x` before
/// `max_x`: (row, x) per entry.
pub(super) fn flow(widths: &[f64], first_x: f64, row_x: f64, max_x: f64) -> Vec<(usize, f64)> {
    let (mut row, mut x) = (0, first_x);
    (widths.iter())
        .map(|&w| {
            if x + w > max_x && x > row_x {
                (row, x) = (row + 1, row_x);
            }
            let slot = (row, x);
            x += w + ENTRY_GAP;
            slot
        })
        .collect()
}

/// The key's entries (span kinds, then mark kinds, that occur) from the first row's
/// `baseline`, and its number of rows.
pub(super) fn key_slots(chart: &ReviewChart, baseline: f64) -> (Vec<(KeyItem, Point)>, usize) {
    let spans = span_kinds()
        .filter(|k| {
            chart
                .lanes
                .iter()
                .any(|l| l.spans.iter().any(|s| s.kind == *k))
        })
        .map(KeyItem::Span);
    let marks = mark_kinds()
        .filter(|k| chart.marks.iter().any(|m| m.kind == *k))
        .map(KeyItem::Mark);
    let items: Vec<KeyItem> = spans.chain(marks).collect();
    let widths: Vec<f64> = (items.iter())
        .map(|item| 14.0 + SWATCH_GAP + width_of(key_name(*item), SMALL_PX))
        .collect();
    let slots = flow(&widths, MARGIN, MARGIN, WIDTH - MARGIN);
    let rows = slots.iter().map(|s| s.0 + 1).max().unwrap_or(0);
    let key = (items.into_iter().zip(slots))
        .map(|(item, (row, x))| (item, Point::new(x, baseline + row as f64 * KEY_ROW)))
        .collect();
    (key, rows)
}

/// A key entry's text.
pub(super) fn key_name(item: KeyItem) -> &'static str {
    match item {
        KeyItem::Span(kind) => span_style(kind).0,
        KeyItem::Mark(kind) => mark_style(kind).0,
    }
}
