//! Painting the trial review figure's frame: the headline and its key, the span lanes, the
//! shared time axis, and the time marks over everything.

use super::label_placement::Rect;
use super::primitives::{Anchor, Drawing, Point, Rgba, Style, Text};
use super::review_chart::{ReviewChart, SpanLane, mark_style, span_style};
use super::review_layout::Layout;
use super::review_legend::{KeyItem, key_name};
use super::review_style::{LABEL_PX, LANE_H, MARGIN, SMALL_PX, SWATCH_GAP, TICK_LEN, width_of};
use super::stroke_font::cap_height;

/// Behind a lane's spans (where it has none).
const LANE_BACKGROUND: Rgba = Rgba::rgb(0xF2, 0xF2, 0xF2);
/// The key's swatch width, pixels.
const KEY_SWATCH_W: f64 = 14.0;
/// The narrowest span drawn, pixels (an instant stays visible).
const MIN_SPAN_PX: f64 = 1.5;
/// Opacity of the mark lines (the data under them stays readable).
const MARK_ALPHA: f64 = 0.7;

/// A fill without outline.
pub(super) fn fill(color: Rgba) -> Style {
    Style {
        fill: Some(color),
        stroke: None,
    }
}

/// The corners of `r`, clockwise from the top left.
pub(super) fn corners(r: Rect) -> Vec<Point> {
    vec![
        Point::new(r.left, r.top),
        Point::new(r.right, r.top),
        Point::new(r.right, r.bottom),
        Point::new(r.left, r.bottom),
    ]
}

/// Light vertical lines at the time ticks from `top` to `bottom`.
pub(super) fn time_grid(d: &mut Drawing, layout: &Layout, top: f64, bottom: f64) {
    for t in layout.time_ticks() {
        let x = layout.x(t);
        let grid = Rgba::GRID.with_alpha(0.6);
        d.line(Point::new(x, top), Point::new(x, bottom), grid, 1.0);
    }
}

/// The headline and the key of span and mark kinds.
pub(super) fn header(d: &mut Drawing, chart: &ReviewChart, layout: &Layout) {
    let (baseline, size) = layout.title;
    let mut title = Text::new(
        chart.title.clone(),
        Point::new(MARGIN, baseline),
        Anchor::Start,
        size,
    );
    title.bold = true;
    d.text(title);
    for &(item, at) in &layout.key {
        let mid = at.y - cap_height(SMALL_PX) / 2.0;
        match item {
            KeyItem::Span(kind) => {
                let swatch = Rect {
                    left: at.x,
                    right: at.x + KEY_SWATCH_W,
                    top: mid - 5.0,
                    bottom: mid + 5.0,
                };
                d.path(corners(swatch), true, fill(span_style(kind).1), Some("key"));
            }
            KeyItem::Mark(kind) => {
                let (_, color, width) = mark_style(kind);
                let (x, style) = (at.x + KEY_SWATCH_W / 2.0, Style::line(color, width));
                let line = vec![Point::new(x, mid - 7.0), Point::new(x, mid + 7.0)];
                d.path(line, false, style, Some("key"));
            }
        }
        let at = Point::new(at.x + KEY_SWATCH_W + SWATCH_GAP, at.y);
        d.text(Text::new(key_name(item), at, Anchor::Start, SMALL_PX));
    }
}

/// One lane from `top`: its label at the left, a light background, the time grid, its spans
/// as filled boxes and their labels.
pub(super) fn lane(d: &mut Drawing, lane: &SpanLane, top: f64, layout: &Layout) {
    let at = Point::new(
        layout.left - 8.0,
        top + (LANE_H + cap_height(LABEL_PX)) / 2.0,
    );
    d.text(Text::new(lane.label.clone(), at, Anchor::End, LABEL_PX));
    let whole = Rect {
        left: layout.left,
        right: layout.right,
        top,
        bottom: top + LANE_H,
    };
    d.path(corners(whole), true, fill(LANE_BACKGROUND), Some("lane"));
    time_grid(d, layout, top, top + LANE_H);
    let rects: Vec<Rect> = (lane.spans.iter())
        .map(|span| {
            let left = layout.x(span.from_s);
            Rect {
                left,
                right: layout.x(span.to_s).max(left + MIN_SPAN_PX),
                top: top + 2.0,
                bottom: top + LANE_H - 2.0,
            }
        })
        .collect();
    for (span, &rect) in lane.spans.iter().zip(&rects) {
        d.path(
            corners(rect),
            true,
            fill(span_style(span.kind).1),
            Some("span"),
        );
    }
    span_labels(d, lane, &rects, layout);
}

/// Each labelled span's label: inside when it fits, else beside it (right, then left) where
/// no other span and no other label is; a span that covers this one entirely is its
/// background, not in the way.
fn span_labels(d: &mut Drawing, lane: &SpanLane, rects: &[Rect], layout: &Layout) {
    let mut taken: Vec<Rect> = Vec::new();
    for (i, (span, rect)) in lane.spans.iter().zip(rects).enumerate() {
        let Some(label) = span.label.as_deref().filter(|l| !l.is_empty()) else {
            continue;
        };
        let w = width_of(label, SMALL_PX);
        let baseline = rect.top + (rect.height() + cap_height(SMALL_PX)) / 2.0;
        if w + 6.0 <= rect.width() {
            let at = Point::new((rect.left + rect.right) / 2.0, baseline);
            let mut text = Text::new(label, at, Anchor::Middle, SMALL_PX);
            text.color = ink_on(span_style(span.kind).1);
            d.text(text);
            continue;
        }
        let in_the_way = |spot: &Rect| {
            let spans = (rects.iter().enumerate()).filter(|&(j, other)| {
                j != i && !(other.left <= rect.left && other.right >= rect.right)
            });
            spans
                .map(|(_, r)| r)
                .chain(&taken)
                .any(|r| r.overlap_area(spot) > 0.0)
        };
        let spots = [rect.right + 4.0, rect.left - 4.0 - w].map(|left| Rect {
            left,
            right: left + w,
            ..*rect
        });
        let free = spots.into_iter().find(|spot| {
            spot.left >= layout.left && spot.right <= layout.right && !in_the_way(spot)
        });
        if let Some(spot) = free {
            let mut text = Text::new(
                label,
                Point::new(spot.left, baseline),
                Anchor::Start,
                SMALL_PX,
            );
            text.halo = true;
            d.text(text);
            taken.push(spot);
        }
    }
}

/// Text colour that reads on `fill`: white on dark fills, ink on light ones.
fn ink_on(fill: Rgba) -> Rgba {
    let luma = 0.299 * f64::from(fill.r) + 0.587 * f64::from(fill.g) + 0.114 * f64::from(fill.b);
    if luma < 150.0 { Rgba::WHITE } else { Rgba::INK }
}

/// The time axis along the bottom: a line, ticks, their labels and the axis title.
pub(super) fn time_axis(d: &mut Drawing, layout: &Layout) {
    let y = layout.bottom;
    d.line(
        Point::new(layout.left, y),
        Point::new(layout.right, y),
        Rgba::INK,
        1.0,
    );
    for t in layout.time_ticks() {
        let x = layout.x(t);
        d.line(
            Point::new(x, y),
            Point::new(x, y + TICK_LEN),
            Rgba::INK,
            1.0,
        );
        let at = Point::new(x, y + TICK_LEN + 3.0 + cap_height(SMALL_PX));
        d.text(Text::new(
            layout.time_label(t),
            at,
            Anchor::Middle,
            SMALL_PX,
        ));
    }
    let at = Point::new((layout.left + layout.right) / 2.0, y + 38.0);
    d.text(Text::new("time (s)", at, Anchor::Middle, LABEL_PX));
}

/// The marks: a vertical line each from its label (or the first lane or panel) down through
/// the lanes and every panel to the time axis (not through the panel headers), over
/// everything, and the labels.
pub(super) fn marks(d: &mut Drawing, chart: &ReviewChart, layout: &Layout) {
    let first = (layout.lane_tops.first().copied())
        .or_else(|| layout.panels.first().map(|p| p.area.top))
        .unwrap_or(layout.bottom);
    let lanes_end = layout.lane_tops.last().map_or(first, |top| top + LANE_H);
    for (i, mark) in chart.marks.iter().enumerate() {
        if !(0.0..=layout.duration).contains(&mark.t_s) {
            continue;
        }
        let (_, color, width) = mark_style(mark.kind);
        let style = Style::line(color.with_alpha(MARK_ALPHA), width);
        let label = layout.marks.iter().find(|m| m.mark == i);
        let top = label.map_or(first, |m| m.rect.bottom);
        let x = layout.x(mark.t_s);
        let pieces = std::iter::once((top, lanes_end.max(top)))
            .chain(layout.panels.iter().map(|p| (p.area.top, p.area.bottom)));
        for (from, to) in pieces.filter(|(from, to)| to > from) {
            let line = vec![Point::new(x, from), Point::new(x, to)];
            d.path(line, false, style, Some("mark"));
        }
        if let Some(m) = label {
            let at = Point::new((m.rect.left + m.rect.right) / 2.0, m.rect.bottom - 3.0);
            let mut text = Text::new(mark.label.clone(), at, Anchor::Middle, SMALL_PX);
            (text.color, text.bold, text.halo) = (color, true, true);
            d.text(text);
        }
    }
}
