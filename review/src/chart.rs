//! The review figure's data: lanes of spans (drive, arm, pinches), panels of series (progress,
//! glove, input age, thumb–finger distances, tracking), marks for progress, drops and
//! feedback.

use retarget::Finger;
use retarget::quality::{PINCH_CLOSED_M, PINCH_HUMAN_M};
use scoring::plot::{
    MarkKind, ReviewChart, ReviewSeries as PlotSeries, SeriesPanel, Span, SpanKind, SpanLane,
    TimeMark,
};

use crate::facts::TrialReview;
use crate::review::ReviewSeries;

/// The figure of `review` with its `series`.
pub fn review_chart(review: &TrialReview, series: &ReviewSeries) -> ReviewChart {
    let mut panels = vec![
        progress_panel(review),
        glove_panel(series),
        age_panel(review, series),
    ];
    panels.push(distance_panel(series));
    if !series.tracking.t_s.is_empty() {
        panels.push(tracking_panel(series));
    }
    ReviewChart {
        title: title(review),
        duration_s: review.duration_s,
        lanes: vec![drive_lane(review), arm_lane(review), pinch_lane(review)],
        panels,
        marks: marks(review),
    }
}

fn title(review: &TrialReview) -> String {
    let field = |k: &str| review.metadata.get(k).map_or("?", String::as_str);
    let trial = review
        .metadata
        .get("trial_index")
        .map_or(String::new(), |t| format!(", trial {t}"));
    format!(
        "{} {}{trial}: {:.1} s, {}, {} feedback",
        field("task"),
        field("embodiment"),
        review.duration_s,
        review.ending,
        review.feedback.len()
    )
}

fn drive_lane(review: &TrialReview) -> SpanLane {
    let mut spans: Vec<Span> = review
        .drive
        .iter()
        .map(|s| Span {
            from_s: s.from_s,
            to_s: s.to_s,
            kind: match s.state.as_str() {
                "engaged" => SpanKind::Engaged,
                "held" => SpanKind::Held,
                "disengaged" => SpanKind::Disengaged,
                _ => SpanKind::Other,
            },
            label: None,
        })
        .collect();
    // The holds from the commands themselves: the status (5 Hz) can miss a short one.
    spans.extend(review.holds.iter().map(|h| {
        Span {
            from_s: h.from_s,
            to_s: h.to_s,
            kind: SpanKind::Held,
            label: h
                .glove_gap_ms
                .is_finite()
                .then(|| format!("gap {:.0} ms", h.glove_gap_ms)),
        }
    }));
    SpanLane {
        label: "drive".into(),
        spans,
    }
}

fn arm_lane(review: &TrialReview) -> SpanLane {
    let mut spans: Vec<Span> = review
        .arm
        .clutch
        .iter()
        .map(|s| Span {
            from_s: s.from_s,
            to_s: s.to_s,
            kind: SpanKind::Clutch,
            label: review.arm.constraint.clone(),
        })
        .collect();
    spans.extend(review.arm.refusals.iter().map(|r| Span {
        from_s: (r.t_s - 0.2).max(0.0),
        to_s: r.t_s,
        kind: SpanKind::Refused,
        label: Some(r.reasons.join(", ")),
    }));
    SpanLane {
        label: "arm".into(),
        spans,
    }
}

fn pinch_lane(review: &TrialReview) -> SpanLane {
    SpanLane {
        label: "pinches".into(),
        spans: review
            .pinches
            .iter()
            .map(|p| Span {
                from_s: p.from_s,
                to_s: p.to_s.max(p.from_s + 0.05),
                kind: if p.closed {
                    SpanKind::PinchClosed
                } else {
                    SpanKind::PinchOpen
                },
                label: Some(p.finger.clone()),
            })
            .collect(),
    }
}

fn marks(review: &TrialReview) -> Vec<TimeMark> {
    let mut marks: Vec<TimeMark> = review
        .progress
        .iter()
        .map(|m| match m.value {
            Some(v) => TimeMark {
                t_s: m.t_s,
                kind: MarkKind::Progress,
                label: format!("{v}"),
            },
            None => TimeMark {
                t_s: m.t_s,
                kind: MarkKind::Drop,
                label: "drop".into(),
            },
        })
        .collect();
    for (k, f) in review.feedback.iter().enumerate() {
        marks.extend(f.times_s.iter().map(|&t_s| TimeMark {
            t_s,
            kind: MarkKind::Feedback,
            label: format!("{}", k + 1),
        }));
    }
    marks
}

fn progress_panel(review: &TrialReview) -> SeriesPanel {
    let mut points = vec![(0.0, 0.0)];
    let mut level = 0.0;
    for mark in &review.progress {
        points.push((mark.t_s, level));
        level = mark.value.unwrap_or(level);
        points.push((mark.t_s, level));
    }
    points.push((review.duration_s, level));
    SeriesPanel {
        title: "progress".into(),
        unit: "task unit".into(),
        series: vec![line("progress", points, 0, false)],
        ..SeriesPanel::default()
    }
}

fn glove_panel(series: &ReviewSeries) -> SeriesPanel {
    SeriesPanel {
        title: "glove rate".into(),
        unit: "Hz".into(),
        series: vec![line(
            "new frames per second",
            series.glove_rate_hz.clone(),
            0,
            false,
        )],
        ..SeriesPanel::default()
    }
}

fn age_panel(review: &TrialReview, series: &ReviewSeries) -> SeriesPanel {
    let mut ticks: Vec<f64> = Vec::new();
    for r in &review.glove.rejected {
        ticks.extend(std::iter::repeat_n(r.t_s, r.count.min(20) as usize));
    }
    SeriesPanel {
        title: "input age".into(),
        unit: "ms".into(),
        series: vec![line(
            "newest glove frame",
            series.input_age_ms.clone(),
            0,
            false,
        )],
        thresholds: review
            .hold_timeout_ms
            .map(|h| (h, "hold".to_string()))
            .into_iter()
            .collect(),
        ticks,
        ticks_label: "rejected frame".into(),
    }
}

fn distance_panel(series: &ReviewSeries) -> SeriesPanel {
    let mut lines = Vec::new();
    for (k, finger) in Finger::OPPOSING.into_iter().enumerate() {
        let zip = |d: &crate::pinches::DistanceSeries| -> Vec<(f64, f64)> {
            d.t_s.iter().copied().zip(d.mm[k].iter().copied()).collect()
        };
        lines.push(line(
            &format!("{} robot", finger.name()),
            zip(&series.robot),
            k + 1,
            false,
        ));
        lines.push(line(
            &format!("{} human", finger.name()),
            zip(&series.human),
            k + 1,
            true,
        ));
    }
    SeriesPanel {
        title: "thumb–finger distance".into(),
        unit: "mm".into(),
        series: lines,
        thresholds: vec![
            (PINCH_HUMAN_M * 1e3, "human pinch".into()),
            (PINCH_CLOSED_M * 1e3, "robot closed".into()),
        ],
        ..SeriesPanel::default()
    }
}

fn tracking_panel(series: &ReviewSeries) -> SeriesPanel {
    let tracking = &series.tracking;
    SeriesPanel {
        title: "tracking error (commanded − measured)".into(),
        unit: "deg".into(),
        series: Finger::ALL
            .into_iter()
            .map(|f| {
                let points = tracking
                    .t_s
                    .iter()
                    .copied()
                    .zip(tracking.error_deg[f.index()].iter().copied())
                    .collect();
                line(f.name(), points, f.index(), false)
            })
            .collect(),
        ..SeriesPanel::default()
    }
}

fn line(label: &str, points: Vec<(f64, f64)>, color: usize, dashed: bool) -> PlotSeries {
    PlotSeries {
        label: label.to_string(),
        points,
        color,
        dashed,
    }
}
