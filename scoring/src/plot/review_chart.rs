//! The trial review figure's input ([`ReviewChart`]): coloured span lanes, stacked series
//! panels and time marks on one time axis; the fixed colours of span and mark kinds; and the
//! checks an input must pass before it is drawn.

use super::primitives::Rgba;
use super::{PlotError, ValueProblem};

/// One trial on one time axis, for an operator to read in ten seconds.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ReviewChart {
    /// Headline, e.g. "G4 · orca_full · trial 3 — correctness 0.50, 12.4 s".
    pub title: String,
    /// The time axis runs from 0 (trial start) to this, seconds (> 0).
    pub duration_s: f64,
    /// Rows of coloured spans under the title (drive state, arm, pinches ...), top to bottom.
    pub lanes: Vec<SpanLane>,
    /// Stacked time-series panels, top to bottom, sharing the time axis.
    pub panels: Vec<SeriesPanel>,
    /// Vertical marks drawn across every lane and panel (progress steps, drops).
    pub marks: Vec<TimeMark>,
}

/// One row of spans, labelled at the left.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SpanLane {
    /// The row's name, e.g. `drive`.
    pub label: String,
    /// The spans, painted in order (a later span over an earlier one).
    pub spans: Vec<Span>,
}

/// A stretch of time in one state.
#[derive(Debug, Clone, PartialEq)]
pub struct Span {
    /// Start, seconds from the trial start.
    pub from_s: f64,
    /// End, seconds from the trial start (not before `from_s`).
    pub to_s: f64,
    /// What the stretch was; it picks the colour.
    pub kind: SpanKind,
    /// Short text drawn inside when it fits (beside the span when the lane has room there).
    pub label: Option<String>,
}

/// What a span shows; each kind has one fixed colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SpanKind {
    /// The operator drives the robot (green).
    Engaged,
    /// The robot holds its last pose (amber).
    Held,
    /// The robot does not follow (grey).
    Disengaged,
    /// The arm follows while the clutch is held (blue).
    Clutch,
    /// A command was refused (red).
    Refused,
    /// A pinch was closed (teal).
    PinchClosed,
    /// A pinch was opened (vermillion).
    PinchOpen,
    /// No data (dark grey).
    Gap,
    /// Anything else (light grey).
    Other,
}

/// A point in time drawn as a vertical line.
#[derive(Debug, Clone, PartialEq)]
pub struct TimeMark {
    /// Seconds from the trial start.
    pub t_s: f64,
    /// What happened; it picks the colour.
    pub kind: MarkKind,
    /// Text at the top of the line, e.g. `1` for the first progress step.
    pub label: String,
}

/// What a time mark shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MarkKind {
    /// A progress step (dark).
    Progress,
    /// An object dropped (red).
    Drop,
    /// Feedback given to the operator (purple).
    Feedback,
}

/// One panel of time series with its own value axis.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SeriesPanel {
    /// Title above the panel, e.g. "thumb–finger distance".
    pub title: String,
    /// The value axis' unit, e.g. "mm".
    pub unit: String,
    /// The lines.
    pub series: Vec<ReviewSeries>,
    /// Horizontal reference lines (value, label), e.g. (20.0, "pinch 20 mm"), (150.0, "hold").
    pub thresholds: Vec<(f64, String)>,
    /// Point events drawn as small markers on the panel's bottom edge (e.g. rejected frames),
    /// seconds.
    pub ticks: Vec<f64>,
    /// Label of those ticks in the legend, e.g. "rejected frame".
    pub ticks_label: String,
}

/// One line in a panel.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ReviewSeries {
    /// The legend's text.
    pub label: String,
    /// (t seconds, value), time order; a NaN value breaks the line (a gap).
    pub points: Vec<(f64, f64)>,
    /// Index into the series palette (the same index = the same colour across panels, e.g.
    /// per digit).
    pub color: usize,
    /// Dashed (e.g. the human's series beside the robot's solid one).
    pub dashed: bool,
}

/// Each span kind's name (legend) and fill: Okabe–Ito hues where the kinds need telling
/// apart, greys for the states that mean "nothing happens".
const SPAN_KINDS: [(SpanKind, &str, Rgba); 9] = [
    (SpanKind::Engaged, "engaged", Rgba::rgb(0x3A, 0xA6, 0x3A)),
    (SpanKind::Held, "held", Rgba::rgb(0xE6, 0x9F, 0x00)),
    (
        SpanKind::Disengaged,
        "disengaged",
        Rgba::rgb(0xA6, 0xA6, 0xA6),
    ),
    (SpanKind::Clutch, "clutch", Rgba::rgb(0x56, 0xB4, 0xE9)),
    (SpanKind::Refused, "refused", Rgba::rgb(0xC4, 0x1E, 0x3A)),
    (
        SpanKind::PinchClosed,
        "pinch closed",
        Rgba::rgb(0x00, 0x85, 0x8A),
    ),
    (
        SpanKind::PinchOpen,
        "pinch open",
        Rgba::rgb(0xD5, 0x5E, 0x00),
    ),
    (SpanKind::Gap, "gap", Rgba::rgb(0x4D, 0x4D, 0x4D)),
    (SpanKind::Other, "other", Rgba::rgb(0xD9, 0xD9, 0xD9)),
];

/// Each mark kind's name (legend), line colour and line width.
const MARK_KINDS: [(MarkKind, &str, Rgba, f64); 3] = [
    (
        MarkKind::Progress,
        "progress",
        Rgba::rgb(0x33, 0x33, 0x33),
        1.0,
    ),
    (MarkKind::Drop, "drop", Rgba::rgb(0xD6, 0x1F, 0x1F), 1.8),
    (
        MarkKind::Feedback,
        "feedback",
        Rgba::rgb(0x80, 0x3C, 0xA8),
        1.2,
    ),
];

/// Every span kind in legend order.
pub(super) fn span_kinds() -> impl Iterator<Item = SpanKind> {
    SPAN_KINDS.iter().map(|&(kind, ..)| kind)
}

/// A span kind's legend name and fill.
pub(super) fn span_style(kind: SpanKind) -> (&'static str, Rgba) {
    SPAN_KINDS
        .iter()
        .find(|entry| entry.0 == kind)
        .map_or(("other", Rgba::GRID), |&(_, name, color)| (name, color))
}

/// Every mark kind in legend order.
pub(super) fn mark_kinds() -> impl Iterator<Item = MarkKind> {
    MARK_KINDS.iter().map(|&(kind, ..)| kind)
}

/// A mark kind's legend name, colour and line width.
pub(super) fn mark_style(kind: MarkKind) -> (&'static str, Rgba, f64) {
    MARK_KINDS
        .iter()
        .find(|entry| entry.0 == kind)
        .map_or(("mark", Rgba::INK, 1.0), |&(_, name, color, width)| {
            (name, color, width)
        })
}

/// What is wrong with one number of the chart (the error names where it is).
fn bad(
    place: &str,
    what: &'static str,
    index: usize,
    field: &'static str,
    value: f64,
    problem: ValueProblem,
) -> PlotError {
    PlotError::BadPanelValue {
        panel: place.to_owned(),
        series: what,
        index,
        axis: field,
        value,
        problem,
    }
}

/// `Ok` when every time is finite and in order, the duration is positive and every threshold
/// is finite (series values may be anything: a non-finite one is a gap).
pub(super) fn validate(chart: &ReviewChart) -> Result<(), PlotError> {
    let d = chart.duration_s;
    if !d.is_finite() || d <= 0.0 {
        let problem = if d.is_finite() {
            ValueProblem::Negative
        } else {
            ValueProblem::NotFinite
        };
        let field = "duration_s, which must be > 0";
        return Err(bad(&chart.title, "time axis", 0, field, d, problem));
    }
    for lane in &chart.lanes {
        validate_lane(lane)?;
    }
    for (i, mark) in chart.marks.iter().enumerate() {
        if !mark.t_s.is_finite() {
            let problem = ValueProblem::NotFinite;
            return Err(bad(&mark.label, "time mark", i, "t_s", mark.t_s, problem));
        }
    }
    chart.panels.iter().try_for_each(validate_panel)
}

fn validate_lane(lane: &SpanLane) -> Result<(), PlotError> {
    for (i, span) in lane.spans.iter().enumerate() {
        for (field, t) in [("from_s", span.from_s), ("to_s", span.to_s)] {
            if !t.is_finite() {
                let problem = ValueProblem::NotFinite;
                return Err(bad(&lane.label, "lane span", i, field, t, problem));
            }
        }
        if span.from_s > span.to_s {
            let field = "to_s − from_s (the span ends before it starts)";
            let length = span.to_s - span.from_s;
            let problem = ValueProblem::Negative;
            return Err(bad(&lane.label, "lane span", i, field, length, problem));
        }
    }
    Ok(())
}

fn validate_panel(panel: &SeriesPanel) -> Result<(), PlotError> {
    let not_finite = ValueProblem::NotFinite;
    for series in &panel.series {
        let place = format!("{} / {}", panel.title, series.label);
        if let Some((i, &(t, _))) =
            (series.points.iter().enumerate()).find(|(_, p)| !p.0.is_finite())
        {
            return Err(bad(&place, "series", i, "time", t, not_finite));
        }
    }
    if let Some((i, &(v, _))) =
        (panel.thresholds.iter().enumerate()).find(|(_, h)| !h.0.is_finite())
    {
        return Err(bad(&panel.title, "threshold", i, "value", v, not_finite));
    }
    if let Some((i, &t)) = panel.ticks.iter().enumerate().find(|(_, t)| !t.is_finite()) {
        return Err(bad(&panel.title, "tick", i, "time", t, not_finite));
    }
    Ok(())
}
