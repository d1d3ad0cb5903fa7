//! The scatter checked as a drawing, an SVG document and a PNG image.

use super::*;

fn chart(series: &[&[(f64, f64)]]) -> PcaChart {
    PcaChart {
        title: "Strategy".into(),
        x_label: "PC1 (41 % of variance)".into(),
        y_label: "PC2 (22 % of variance)".into(),
        series: (series.iter().enumerate())
            .map(|(i, points)| PcaSeries {
                label: format!("task {i}"),
                points: points.to_vec(),
            })
            .collect(),
        note: Some("silhouette 0.78".into()),
    }
}

fn example() -> PcaChart {
    chart(&[
        &[(-2.1, 0.4), (-1.8, 0.9), (-2.4, 0.1)],
        &[(1.5, -1.2), (1.9, -0.7)],
        &[(0.3, 2.2), (0.1, 1.7), (0.6, 2.6), (-0.2, 1.9)],
    ])
}

#[test]
fn one_circle_per_point_where_the_geometry_puts_it() {
    let c = example();
    let (d, g) = pca_drawing(&c).unwrap();
    let figure = Figure::render(&d).unwrap();
    let doc = roxmltree::Document::parse(&figure.svg).unwrap();
    let circles: Vec<(f64, f64)> = (doc.descendants())
        .filter(|n| n.has_tag_name("circle") && n.attribute("class") == Some("point"))
        .map(|n| {
            let coord = |a| n.attribute(a).unwrap().parse::<f64>().unwrap();
            (coord("cx"), coord("cy"))
        })
        .collect();
    assert_eq!(circles.len(), 9);
    let (cx, cy) = circles[3];
    assert!((cx - g.x(1.5)).abs() < 0.01 && (cy - g.y(-1.2)).abs() < 0.01);
    let legend = (doc.descendants())
        .filter(|n| n.attribute("class") == Some("legend-marker"))
        .count();
    assert_eq!(legend, 3);
    let texts: Vec<&str> = doc.descendants().filter_map(|n| n.text()).collect();
    for wanted in [
        "task 0",
        "task 2",
        "silhouette 0.78",
        "PC2 (22 % of variance)",
    ] {
        assert!(texts.contains(&wanted), "{wanted} missing from {texts:?}");
    }
    assert_eq!(figure, pca_scatter(&c).unwrap(), "deterministic");
}

#[test]
fn the_png_decodes_with_points_in_their_colours() {
    let c = example();
    let (_, g) = pca_drawing(&c).unwrap();
    let figure = pca_scatter(&c).unwrap();
    assert_eq!((figure.width_px, figure.height_px), (800, 560));
    let pixmap = tiny_skia::Pixmap::decode_png(&figure.png).unwrap();
    assert_eq!((pixmap.width(), pixmap.height()), (800, 560));
    let at = |x: f64, y: f64| {
        let p = (pixmap.pixel(g.x(x).round() as u32, g.y(y).round() as u32)).unwrap();
        let p = p.demultiply();
        (p.red(), p.green(), p.blue())
    };
    // Series 1 is vermillion (0xD5, 0x5E, 0x00) at 55 % over white.
    let (r, gr, b) = at(1.9, -0.7);
    assert!(r > gr && gr > b && b < 140, "{:?}", (r, gr, b));
    assert_eq!(at(-1.5, -0.5), (255, 255, 255), "empty plot area is white");
}

#[test]
fn bad_charts_are_named() {
    let err = pca_scatter(&chart(&[&[(0.0, 1.0)], &[(1.0, f64::NAN)]])).unwrap_err();
    assert!(matches!(
        &err,
        PlotError::BadScatterValue { series, index: 0, axis: "y", problem: ValueProblem::NotFinite, .. }
            if series == "task 1"
    ));
    assert_eq!(
        err.to_string(),
        "series 'task 1', point 0, y: value NaN is not a finite number"
    );
    assert_eq!(
        pca_scatter(&chart(&[&[], &[]])),
        Err(PlotError::NoScatterPoints {
            title: "Strategy".into()
        })
    );
    let row: &[(f64, f64)] = &[(0.0, 0.0)];
    assert!(matches!(
        pca_scatter(&chart(&[row; MAX_SCATTER_SERIES + 1])),
        Err(PlotError::TooManyScatterSeries {
            count: 25,
            max: 24,
            ..
        })
    ));
    let many = pca_scatter(&chart(&[row; MAX_SCATTER_SERIES])).unwrap();
    assert!(many.svg.contains("task 23"));
}
