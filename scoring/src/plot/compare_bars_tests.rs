//! The grouped bar chart's tests: bars where their values say, error bars, hollow markers,
//! bands, legend, a canvas that grows, refused input, and the PNG's colours.

use super::*;
use crate::plot::compare_chart::{Bar, BarCategory, BarSeries};
use crate::plot::primitives::Primitive;
use crate::plot::{PlotError, SERIES_COLORS, ValueProblem};

fn bar(mean: f64, std: Option<f64>) -> Option<Bar> {
    Some(Bar { mean, std })
}

/// Tasks V1, C1 on orca_full and V1 on orca_5; series rokoko and avp (no avp on orca_5).
fn chart() -> GroupedBarChart {
    let category = |label: &str, band: &str| BarCategory {
        label: label.into(),
        band: band.into(),
    };
    GroupedBarChart {
        title: "Mean score by keypoint_source".into(),
        notes: vec!["a note".into()],
        y_label: "Score".into(),
        x_label: "Task".into(),
        categories: vec![
            category("V1", "orca_full"),
            category("C1", "orca_full"),
            category("V1", "orca_5"),
        ],
        series: vec![
            BarSeries {
                label: "rokoko".into(),
                values: vec![bar(0.8, Some(0.1)), bar(0.6, None), bar(0.05, Some(0.2))],
            },
            BarSeries {
                label: "avp".into(),
                values: vec![bar(0.7, Some(0.05)), bar(1.1, Some(0.1)), None],
            },
        ],
    }
}

fn paths<'a>(d: &'a Drawing, class: &str) -> Vec<(&'a [crate::plot::primitives::Point], Style)> {
    (d.items.iter())
        .filter_map(|item| match item {
            Primitive::Path {
                points,
                style,
                class: Some(c),
                ..
            } if *c == class => Some((points.as_slice(), *style)),
            _ => None,
        })
        .collect()
}

fn texts(d: &Drawing) -> Vec<&str> {
    (d.items.iter())
        .filter_map(|item| match item {
            Primitive::Text(t) => Some(t.content.as_str()),
            _ => None,
        })
        .collect()
}

use crate::plot::primitives::Style;

#[test]
fn bars_stand_on_zero_at_their_mean_in_their_category_and_colour() {
    let (d, g) = grouped_bars_drawing(&chart()).unwrap();
    let bars = paths(&d, "bar");
    assert_eq!(
        bars.len(),
        5,
        "one bar per value; the missing one is not a bar"
    );
    // Drawn series by series: rokoko's three, then avp's two.
    let expected = [
        (0, 0, 0.8),
        (1, 0, 0.6),
        (2, 0, 0.05),
        (0, 1, 0.7),
        (1, 1, 1.1),
    ];
    for ((points, style), (c, s, mean)) in bars.iter().zip(expected) {
        let top = points.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
        let bottom = points.iter().map(|p| p.y).fold(0.0, f64::max);
        assert!((top - g.y(mean)).abs() < 1e-9, "bar {c},{s}: {top}");
        assert!((bottom - g.area.bottom).abs() < 1e-9);
        let (left, right) = g.bar_x(c, s);
        let mid = (points[0].x + points[2].x) / 2.0;
        assert!(mid > left && mid < right, "bar {c},{s} outside its slot");
        assert!(left >= g.area.left + c as f64 * g.category_w);
        assert!(right <= g.area.left + (c + 1) as f64 * g.category_w);
        assert_eq!(style.fill, Some(SERIES_COLORS[s]));
    }
    // 1.1 + 0.1 needs a score axis to 1.2.
    assert!((g.scale.top() - 1.2).abs() < 1e-9);
}

#[test]
fn error_bars_span_one_std_and_stop_at_zero_and_missing_values_are_hollow() {
    let (d, g) = grouped_bars_drawing(&chart()).unwrap();
    let errors = paths(&d, "error-bar");
    assert_eq!(errors.len(), 4, "one per bar with a std");
    let (p, _) = errors[0];
    assert!((p[0].y - g.y(0.9)).abs() < 1e-9 && (p[1].y - g.y(0.7)).abs() < 1e-9);
    let (p, _) = errors[1];
    assert!(
        (p[1].y - g.area.bottom).abs() < 1e-9,
        "0.05 − 0.2 stops at 0"
    );
    let hollow = (d.items.iter())
        .filter(|i| {
            matches!(
                i,
                Primitive::Circle {
                    class: Some("no-bar"),
                    ..
                }
            )
        })
        .count();
    assert_eq!(hollow, 1);
    let t = texts(&d);
    assert!(t.contains(&"Error bars: \u{b1}1 standard deviation"));
    assert!(t.contains(&"Hollow marker at 0 = no trials of the group there"));
    assert!(t.contains(&"a note"));
}

#[test]
fn bands_legend_and_labels_are_written_once_each() {
    let (d, _) = grouped_bars_drawing(&chart()).unwrap();
    let t = texts(&d);
    let count = |s: &str| t.iter().filter(|x| **x == s).count();
    assert_eq!((count("orca_full"), count("orca_5")), (1, 1));
    assert_eq!((count("V1"), count("C1")), (2, 1));
    assert_eq!((count("rokoko"), count("avp")), (1, 1), "legend");
    assert_eq!(paths(&d, "band").len(), 2);
    assert_eq!(paths(&d, "legend-swatch").len(), 2);
    assert!(t.contains(&"Mean score by keypoint_source") && t.contains(&"Score"));
}

#[test]
fn many_categories_widen_the_canvas() {
    let mut wide = chart();
    let n = 40;
    wide.categories = (0..n)
        .map(|i| BarCategory {
            label: format!("T{i}"),
            band: format!("e{}", i / 4),
        })
        .collect();
    for s in &mut wide.series {
        s.values = vec![bar(0.5, None); n];
    }
    let (d, g) = grouped_bars_drawing(&wide).unwrap();
    assert!(d.width_px > 800, "{}", d.width_px);
    assert!(g.bar_w >= 14.0 - 1e-9, "{}", g.bar_w);
    let (small, _) = grouped_bars_drawing(&chart()).unwrap();
    assert_eq!(small.width_px, 800);
}

#[test]
fn bad_charts_are_refused_by_name() {
    let mut c = chart();
    c.series[1].values[0] = bar(f64::NAN, None);
    let err = grouped_bars(&c).unwrap_err();
    assert!(matches!(
        &err,
        PlotError::BadBarValue { series, field: "mean", problem: ValueProblem::NotFinite, .. }
            if series == "avp"
    ));
    assert!(err.to_string().contains("category 'V1 orca_full'"), "{err}");
    let mut c = chart();
    c.series[0].values.pop();
    assert!(matches!(
        grouped_bars(&c),
        Err(PlotError::BarCountMismatch {
            values: 2,
            categories: 3,
            ..
        })
    ));
    let mut c = chart();
    c.series = (0..9).map(|_| chart().series[0].clone()).collect();
    assert!(matches!(
        grouped_bars(&c),
        Err(PlotError::TooManyBarSeries {
            count: 9,
            max: 8,
            ..
        })
    ));
    let mut c = chart();
    c.categories.clear();
    assert!(matches!(grouped_bars(&c), Err(PlotError::NoBars { .. })));
}

#[test]
fn the_png_has_each_series_colour_and_matches_the_svg_size() {
    let figure = grouped_bars(&chart()).unwrap();
    let pixmap = tiny_skia::Pixmap::decode_png(&figure.png).unwrap();
    assert_eq!(
        (pixmap.width(), pixmap.height()),
        (figure.width_px, figure.height_px)
    );
    for color in &SERIES_COLORS[..2] {
        let found = (pixmap.pixels().iter())
            .filter(|p| {
                (p.red(), p.green(), p.blue(), p.alpha()) == (color.r, color.g, color.b, 255)
            })
            .count();
        assert!(found > 500, "{color:?}: {found} pixels");
    }
    assert_eq!(figure.svg.matches("class=\"bar\"").count(), 5);
}
