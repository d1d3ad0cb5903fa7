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
