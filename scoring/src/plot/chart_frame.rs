//! The frame every scatter chart shares (`dof_chart`, `pca_chart`): canvas size, margins and
//! text sizes, so the figures of one report look alike.

/// Canvas width, pixels.
pub(super) const WIDTH_PX: f64 = 800.0;
/// Canvas height, pixels.
pub(super) const HEIGHT_PX: f64 = 560.0;
/// Margin around the plot, pixels.
pub(super) const MARGIN_PX: f64 = 24.0;
/// Title text size, pixels.
pub(super) const TITLE_PX: f64 = 20.0;
/// Note line (under the title) text size, pixels.
pub(super) const NOTE_PX: f64 = 13.0;
/// Tick label text size, pixels.
pub(super) const TICK_PX: f64 = 13.0;
/// Axis title text size, pixels.
pub(super) const AXIS_TITLE_PX: f64 = 15.0;
/// Tick mark length, pixels.
pub(super) const TICK_LEN_PX: f64 = 5.0;

/// The horizontal grid lines, the ticks and the tick labels of a score axis along the left edge
/// of `area` (a value's y is `bottom − value / top × height`, as both charts draw it).
pub(super) fn draw_score_ticks(
    d: &mut super::primitives::Drawing,
    area: super::label_placement::Rect,
    scale: &super::scale::ScoreAxis,
) {
    use super::primitives::{Anchor, Point, Rgba, Text};
    for tick in std::iter::once(0.0).chain(scale.ticks()) {
        let y = area.bottom - tick / scale.top() * area.height();
        d.line(
            Point::new(area.left, y),
            Point::new(area.right, y),
            Rgba::GRID,
            1.0,
        );
        d.line(
            Point::new(area.left - TICK_LEN_PX, y),
            Point::new(area.left, y),
            Rgba::INK,
            1.0,
        );
        let at = Point::new(
            area.left - TICK_LEN_PX - 4.0,
            y + super::stroke_font::cap_height(TICK_PX) / 2.0,
        );
        d.text(Text::new(scale.label(tick), at, Anchor::End, TICK_PX));
    }
}
