//! Legend: a swatch (translucent fill, outline, marker) and a label per series, flowed in
//! centred rows; under it, the key to hollow markers and which tasks were not attempted.

use super::primitives::{Anchor, Drawing, Point, Rgba, Style, Text};
use super::stroke_font::{FONT_SLACK, cap_height, text_width, wrap};

/// One legend line's content.
#[derive(Debug, Clone, PartialEq)]
pub struct LegendEntry {
    /// The series' label.
    pub label: String,
    /// The series' colour.
    pub color: Rgba,
    /// Opacity of the swatch's fill, as in the chart.
    pub fill_alpha: f64,
}

const LABEL_PX: f64 = 16.0;
const SWATCH_W_PX: f64 = 26.0;
const SWATCH_H_PX: f64 = 14.0;
/// Between swatch and label.
const INNER_GAP_PX: f64 = 8.0;
/// Between entries on one row.
const ENTRY_GAP_PX: f64 = 32.0;
const ROW_PX: f64 = 26.0;

fn entry_width(entry: &LegendEntry) -> f64 {
    SWATCH_W_PX + INNER_GAP_PX + FONT_SLACK * text_width(&entry.label, LABEL_PX)
}

/// Draws `entries` in rows below `top`, centred on a canvas `width` wide with `margin` on
/// both sides; returns the last row's baseline (`top` when there are no entries).
pub fn draw(
    drawing: &mut Drawing,
    entries: &[LegendEntry],
    top: f64,
    width: f64,
    margin: f64,
) -> f64 {
    // Greedy rows: as many entries as fit in the width.
    let mut rows: Vec<Vec<&LegendEntry>> = Vec::new();
    let mut row_w = 0.0;
    for entry in entries {
        let w = entry_width(entry);
        match rows.last_mut() {
            Some(row) if row_w + ENTRY_GAP_PX + w <= width - 2.0 * margin => {
                row.push(entry);
                row_w += ENTRY_GAP_PX + w;
            }
            _ => {
                rows.push(vec![entry]);
                row_w = w;
            }
        }
    }
    let mut baseline = top;
    for row in rows {
        baseline += ROW_PX;
        let total: f64 = row.iter().map(|e| entry_width(e)).sum::<f64>()
            + ENTRY_GAP_PX * (row.len() as f64 - 1.0);
        let mut x = ((width - total) / 2.0).max(margin);
        let mid_y = baseline - cap_height(LABEL_PX) / 2.0;
        for entry in row {
            let (l, r) = (x, x + SWATCH_W_PX);
            let (t, b) = (mid_y - SWATCH_H_PX / 2.0, mid_y + SWATCH_H_PX / 2.0);
            let swatch = vec![
                Point::new(l, t),
                Point::new(r, t),
                Point::new(r, b),
                Point::new(l, b),
            ];
            let style = Style::filled_and_outlined(
                entry.color.with_alpha(entry.fill_alpha),
                entry.color,
                2.0,
            );
            drawing.path(swatch, true, style, Some("legend-swatch"));
            let marker = Style::filled_and_outlined(entry.color, Rgba::WHITE, 1.0);
            drawing.circle(Point::new((l + r) / 2.0, mid_y), 4.5, marker, None);
            let at = Point::new(r + INNER_GAP_PX, baseline);
            drawing.text(Text::new(entry.label.clone(), at, Anchor::Start, LABEL_PX));
            x += entry_width(entry) + ENTRY_GAP_PX;
        }
    }
    baseline
}

const NOTE_PX: f64 = 14.0;
const NOTE_LINE_PX: f64 = 20.0;
const KEY_MARKER_PX: f64 = 5.0;
/// From the block's left edge to its text (room for the key's hollow marker).
const NOTE_INDENT_PX: f64 = 2.0 * KEY_MARKER_PX + 8.0;

/// When `notes` (one per series with tasks not attempted) is not empty: a hollow marker
/// with its meaning, then the notes, as a left-aligned block centred below `top`. Returns
/// the last baseline (`top` when there are no notes).
pub fn draw_not_attempted(
    drawing: &mut Drawing,
    notes: &[String],
    top: f64,
    width: f64,
    margin: f64,
) -> f64 {
    if notes.is_empty() {
        return top;
    }
    let key = "Hollow marker at 0 = task not attempted";
    let max_text = width - 2.0 * margin - NOTE_INDENT_PX;
    let mut lines = Vec::new();
    for note in notes {
        lines.extend(wrap(note, NOTE_PX, max_text / FONT_SLACK));
    }
    let block_w = std::iter::once(key)
        .chain(lines.iter().map(String::as_str))
        .map(|l| FONT_SLACK * text_width(l, NOTE_PX))
        .fold(0.0, f64::max)
        + NOTE_INDENT_PX;
    let x = ((width - block_w) / 2.0).max(margin);
    let mut y = top + NOTE_LINE_PX + 6.0;
    let icon = Point::new(x + KEY_MARKER_PX + 1.0, y - cap_height(NOTE_PX) / 2.0);
    let hollow = Style::filled_and_outlined(Rgba::WHITE, Rgba::GREY, 2.0);
    drawing.circle(icon, KEY_MARKER_PX, hollow, None);
    let mut text = Text::new(
        key,
        Point::new(x + NOTE_INDENT_PX, y),
        Anchor::Start,
        NOTE_PX,
    );
    text.color = Rgba::GREY;
    drawing.text(text);
    for line in lines {
        y += NOTE_LINE_PX;
        let at = Point::new(x + NOTE_INDENT_PX, y);
        drawing.text(Text::new(line, at, Anchor::Start, NOTE_PX));
    }
    y
}
