//! The trial review figure's tests: a canvas that grows with lanes and panels, every name on
//! it, span colours, gaps that break lines, "no data", labels apart, refused input, and the
//! same bytes for the same chart.

use super::*;
use crate::plot::primitives::Primitive;
use crate::plot::review_chart::{
    MarkKind, ReviewSeries, SeriesPanel, Span, SpanKind, SpanLane, TimeMark,
};

fn span(from_s: f64, to_s: f64, kind: SpanKind, label: Option<&str>) -> Span {
    Span {
        from_s,
        to_s,
        kind,
        label: label.map(str::to_owned),
    }
}

fn series(label: &str, color: usize, dashed: bool, f: impl Fn(f64) -> f64) -> ReviewSeries {
    ReviewSeries {
        label: label.into(),
        points: (0..=200)
            .map(|k| k as f64 * 0.05)
            .map(|t| (t, f(t)))
            .collect(),
        color,
        dashed,
    }
}

fn mark(t_s: f64, kind: MarkKind, label: &str) -> TimeMark {
    TimeMark {
        t_s,
        kind,
        label: label.into(),
    }
}

/// A 10 s trial: two lanes, two panels, three marks.
fn chart() -> ReviewChart {
    ReviewChart {
        title: "G4 orca_full trial 3 — correctness 0.50, 10.0 s".into(),
        duration_s: 10.0,
        lanes: vec![
            SpanLane {
                label: "drive".into(),
                spans: vec![
                    span(0.0, 4.0, SpanKind::Engaged, Some("engaged")),
                    span(4.0, 4.4, SpanKind::Held, None),
                    span(4.4, 10.0, SpanKind::Engaged, None),
                ],
            },
            SpanLane {
                label: "arm".into(),
                spans: vec![
                    span(0.0, 10.0, SpanKind::Clutch, None),
                    span(6.0, 6.5, SpanKind::Refused, None),
                ],
            },
        ],
        panels: vec![
            SeriesPanel {
                title: "input age".into(),
                unit: "ms".into(),
                series: vec![series("glove frame", 0, false, |t| 30.0 + 5.0 * t)],
                thresholds: vec![(150.0, "hold 150 ms".into())],
                ticks: vec![2.0, 2.0, 2.000_01, 7.5],
                ticks_label: "rejected frame".into(),
            },
            SeriesPanel {
                title: "thumb–finger distance".into(),
                unit: "mm".into(),
                series: vec![
                    series("index (human)", 1, true, |t| 40.0 + 30.0 * t.sin()),
                    series("index (robot)", 1, false, |t| 42.0 + 28.0 * t.sin()),
                ],
                thresholds: vec![(20.0, "pinch 20 mm".into())],
                ..SeriesPanel::default()
            },
        ],
        marks: vec![
            mark(3.0, MarkKind::Progress, "1"),
            mark(5.0, MarkKind::Progress, "2"),
            mark(8.0, MarkKind::Drop, "drop"),
        ],
    }
}

fn paths<'a>(d: &'a Drawing, class: &str) -> Vec<&'a Primitive> {
    (d.items.iter())
        .filter(|item| matches!(item, Primitive::Path { class: Some(c), .. } if *c == class))
        .collect()
}

fn texts(svg: &str) -> Vec<String> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    (doc.descendants())
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text().map(str::to_owned))
        .collect()
}

#[test]
fn review_canvas_is_fixed_wide_and_grows_with_lanes_and_panels() {
    let base = review_figure(&chart()).unwrap();
    assert_eq!(base.width_px, 1200);
    let mut more_lanes = chart();
    more_lanes.lanes.push(more_lanes.lanes[0].clone());
    let mut more_panels = chart();
    more_panels.panels.push(more_panels.panels[0].clone());
    let lanes = review_figure(&more_lanes).unwrap();
    let panels = review_figure(&more_panels).unwrap();
    assert!(
        lanes.height_px > base.height_px,
        "{} {}",
        lanes.height_px,
        base.height_px
    );
    assert!(
        panels.height_px >= base.height_px + 150,
        "a panel is 150 px or more: {} {}",
        panels.height_px,
        base.height_px
    );
    assert!(base.png.starts_with(b"\x89PNG"));
}

#[test]
fn review_svg_names_the_title_lanes_panels_thresholds_and_marks() {
    let figure = review_figure(&chart()).unwrap();
    let texts = texts(&figure.svg);
    let expected = [
        "G4 orca_full trial 3 — correctness 0.50, 10.0 s",
        "drive",
        "arm",
        "input age",
        "(ms)",
        "thumb–finger distance",
        "hold 150 ms",
        "pinch 20 mm",
        "1",
        "2",
        "drop",
        "rejected frame",
        "index (human)",
        "engaged",
        "refused",
        "time (s)",
    ];
    for text in expected {
        assert!(
            texts.iter().any(|t| t == text),
            "{text} missing from {texts:?}"
        );
    }
}

#[test]
fn review_spans_are_filled_in_their_kinds_colours() {
    let figure = review_figure(&chart()).unwrap();
    let (_, refused) = crate::plot::review_chart::span_style(SpanKind::Refused);
    let fill = format!(
        r##"fill="#{:02x}{:02x}{:02x}""##,
        refused.r, refused.g, refused.b
    );
    assert_eq!(fill, r##"fill="#c41e3a""##);
    let refused_spans = (figure.svg.lines())
        .filter(|l| l.contains(r#"class="span""#) && l.contains(&fill))
        .count();
    assert_eq!(refused_spans, 1, "one refused span, in red");
    assert_eq!(figure.svg.matches(r#"class="span""#).count(), 5);
    // Every kind its own colour.
    let colours: std::collections::BTreeSet<_> = crate::plot::review_chart::span_kinds()
        .map(|k| crate::plot::review_chart::span_style(k).1)
        .map(|c| (c.r, c.g, c.b))
        .collect();
    assert_eq!(colours.len(), 9);
}

#[test]
fn review_a_gap_splits_a_line_and_an_empty_panel_says_no_data() {
    let mut chart = chart();
    let d = review_drawing(&chart).unwrap();
    assert_eq!(
        paths(&d, "series").len(),
        2,
        "two solid series, one piece each"
    );
    assert!(
        paths(&d, "series-dash").len() > 10,
        "the human's series is dashed"
    );
    chart.panels[0].series[0].points[100].1 = f64::NAN;
    chart.panels[1].series[1].points[50].1 = f64::NAN;
    chart.panels[1].series[1].points[51].1 = f64::INFINITY;
    chart.panels[1].series[1].points[150].1 = f64::NAN;
    let d = review_drawing(&chart).unwrap();
    assert_eq!(paths(&d, "series").len(), 5, "2 + 3 pieces");
    let mut empty = chart.clone();
    empty.panels[1].series.clear();
    let figure = review_figure(&empty).unwrap();
    assert!(texts(&figure.svg).iter().any(|t| t == "no data"));
    assert!(
        !texts(&review_figure(&chart).unwrap().svg)
            .iter()
            .any(|t| t == "no data")
    );
}

#[test]
fn review_thresholds_are_dotted_and_ticks_marked_once_per_pixel() {
    let d = review_drawing(&chart()).unwrap();
    assert!(paths(&d, "threshold").len() > 100, "dots along the panel");
    assert_eq!(
        paths(&d, "tick").len(),
        2,
        "2.0, 2.0 and 2.000 01 s share a pixel"
    );
}

#[test]
fn review_mark_labels_stay_apart() {
    let mut chart = chart();
    chart.marks = (0..12)
        .map(|k| mark(5.0 + 0.05 * k as f64, MarkKind::Feedback, "feedback"))
        .collect();
    let layout = Layout::new(&chart);
    assert_eq!(
        layout.marks.len(),
        4,
        "four rows of one label each, the rest left out"
    );
    let rows: std::collections::BTreeSet<u64> = (layout.marks.iter())
        .map(|m| m.rect.top.round() as u64)
        .collect();
    assert_eq!(rows.len(), 4, "stacked in rows: {rows:?}");
    for (i, a) in layout.marks.iter().enumerate() {
        for b in &layout.marks[i + 1..] {
            assert_eq!(a.rect.overlap_area(&b.rect), 0.0, "{a:?} {b:?}");
        }
    }
    let texts = texts(&review_figure(&chart).unwrap().svg);
    assert_eq!(
        texts.iter().filter(|t| *t == "feedback").count(),
        4 + 1,
        "labels + key"
    );
    assert_eq!(
        review_drawing(&chart)
            .map(|d| paths(&d, "mark").len())
            .unwrap(),
        12 * 3
    );
}

#[test]
fn review_bad_durations_and_reversed_spans_are_named() {
    for duration in [0.0, -3.0, f64::NAN, f64::INFINITY] {
        let mut bad = chart();
        bad.duration_s = duration;
        let error = review_figure(&bad).unwrap_err().to_string();
        assert!(error.contains("duration_s"), "{error}");
        assert!(error.contains("must be > 0"), "{error}");
    }
    let mut reversed = chart();
    reversed.lanes[1].spans[1] = span(6.5, 6.0, SpanKind::Refused, None);
    let error = review_figure(&reversed).unwrap_err().to_string();
    for part in ["'arm'", "span point 1", "ends before it starts", "-0.5"] {
        assert!(error.contains(part), "{part} not in {error}");
    }
    let mut late = chart();
    late.panels[0].series[0].points[3].0 = f64::NAN;
    let error = review_figure(&late).unwrap_err().to_string();
    assert!(
        error.contains("input age / glove frame") && error.contains("point 3"),
        "{error}"
    );
    let mut mark_time = chart();
    mark_time.marks[2].t_s = f64::INFINITY;
    let error = review_figure(&mark_time).unwrap_err().to_string();
    assert!(error.contains("'drop'") && error.contains("t_s"), "{error}");
}

#[test]
fn review_same_chart_same_bytes() {
    let a = review_figure(&chart()).unwrap();
    let b = review_figure(&chart()).unwrap();
    assert_eq!(a, b);
    let empty = ReviewChart {
        title: "nothing yet".into(),
        duration_s: 1.0,
        ..ReviewChart::default()
    };
    let figure = review_figure(&empty).unwrap();
    assert!(figure.height_px > 0 && figure.png.starts_with(b"\x89PNG"));
}
