//! The trial review figure's sizes: canvas, text and the measure of text, shared by its
//! layout and painters.

use super::stroke_font::{FONT_SLACK, text_width};

/// Canvas width, pixels.
pub(super) const WIDTH: f64 = 1200.0;
/// Margin around everything, pixels.
pub(super) const MARGIN: f64 = 20.0;
/// Headline size (shrunk to fit the width), pixels.
pub(super) const TITLE_PX: f64 = 18.0;
/// Lane labels and panel titles, pixels.
pub(super) const LABEL_PX: f64 = 12.0;
/// Legends, threshold and mark labels, pixels.
pub(super) const SMALL_PX: f64 = 11.0;
/// Tick labels, pixels.
pub(super) const TICK_PX: f64 = 10.0;
/// Tick mark length, pixels.
pub(super) const TICK_LEN: f64 = 4.0;
/// A lane's height, pixels.
pub(super) const LANE_H: f64 = 22.0;
/// A legend swatch's width, pixels.
pub(super) const SWATCH_W: f64 = 20.0;
/// From a swatch to its label, pixels.
pub(super) const SWATCH_GAP: f64 = 5.0;
/// A key row's height, pixels.
pub(super) const KEY_ROW: f64 = 18.0;
/// Between legend entries on one row, pixels.
pub(super) const ENTRY_GAP: f64 = 16.0;

/// The width `text` takes on the canvas, with slack for an SVG viewer's font.
pub(super) fn width_of(text: &str, size_px: f64) -> f64 {
    FONT_SLACK * text_width(text, size_px)
}
