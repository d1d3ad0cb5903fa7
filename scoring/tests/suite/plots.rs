//! The figures end to end: the paper's example rendered as radar and DoF charts, checked as
//! images (PNG decodes, sized, inked, in the series colours) and as documents (SVG parses,
//! one polygon per series, every label present). The rendered files are written to
//! `/tmp/pomdar_plots/` (the system temp dir) for a person to look at.

use std::collections::HashSet;
use std::path::PathBuf;

use proptest::prelude::*;
use scoring::plot::{
    DofChart, DofPoint, Figure, PlotError, RadarChart, RadarSeries, Rgba, SERIES_COLORS,
    ValueProblem, dof_scatter, radar,
};
use tiny_skia::Pixmap;

const MANIPULATION: [&str; 12] = [
    "V1", "V2", "V3", "H1", "H2", "H3", "H4", "H5", "C1", "C2", "C3", "C4",
];
const GRASPING: [&str; 6] = ["G1", "G2", "G3", "G4", "G5", "G6"];

/// Orca_full's per-task scores as read off the paper's radar figure.
const ORCA_FULL_MANIPULATION: [f64; 12] = [
    0.74, 0.54, 0.67, 0.94, 0.81, 0.86, 0.86, 0.89, 0.81, 0.20, 0.05, 0.83,
];
const ORCA_FULL_GRASPING: [f64; 6] = [0.87, 0.85, 0.85, 0.64, 0.80, 0.78];

/// A made-up reduced hand: H2–H4 not attempted, one superhuman score (C3 at 1.13).
const ORCA_3_MANIPULATION: [Option<f64>; 12] = [
    Some(0.62),
    Some(0.41),
    Some(0.55),
    Some(0.70),
    None,
    None,
    None,
    Some(0.66),
    Some(0.58),
    Some(0.12),
    Some(1.13),
    Some(0.51),
];
/// Made up as well: G3 not attempted.
const ORCA_3_GRASPING: [Option<f64>; 6] = [
    Some(0.80),
    Some(0.62),
    None,
    Some(0.50),
    Some(0.71),
    Some(0.75),
];

fn radar_chart(title: &str, axes: &[&str], full: &[f64], reduced: &[Option<f64>]) -> RadarChart {
    RadarChart {
        title: title.into(),
        axes: axes.iter().map(|a| a.to_string()).collect(),
        series: vec![
            RadarSeries {
                label: "Orca_full".into(),
                values: full.iter().map(|&v| Some(v)).collect(),
            },
            RadarSeries {
                label: "Orca_3".into(),
                values: reduced.to_vec(),
            },
        ],
    }
}

fn manipulation_chart() -> RadarChart {
    radar_chart(
        "POMDAR manipulation tasks",
        &MANIPULATION,
        &ORCA_FULL_MANIPULATION,
        &ORCA_3_MANIPULATION,
    )
}

fn grasping_chart() -> RadarChart {
    radar_chart(
        "POMDAR grasping tasks",
        &GRASPING,
        &ORCA_FULL_GRASPING,
        &ORCA_3_GRASPING,
    )
}

/// The paper's overall scores (Orca_3's DoF is not published: 8 here); the standard
/// deviations are made up to exercise the error bars.
fn dof_chart() -> DofChart {
    let point = |label: &str, dof, overall, std| DofPoint {
        label: label.into(),
        dof,
        overall,
        std,
    };
    DofChart {
        title: "Overall score against degrees of freedom".into(),
        y_label: "Overall score".into(),
        points: vec![
            point("Orca_2", 5, 0.53, Some(0.04)),
            point("Orca_3", 8, 0.62, Some(0.05)),
            point("Orca_5", 11, 0.60, None),
            point("Orca_full", 16, 0.71, Some(0.03)),
        ],
    }
}

/// Writes the figure as `<name>.png` and `<name>.svg` for a person to look at.
fn save(name: &str, figure: &Figure) {
    let dir: PathBuf = std::env::temp_dir().join("pomdar_plots");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join(format!("{name}.png")), &figure.png).unwrap();
    std::fs::write(dir.join(format!("{name}.svg")), &figure.svg).unwrap();
}

/// Decoded pixels as straight RGBA.
fn pixels(figure: &Figure) -> (Pixmap, Vec<[u8; 4]>) {
    let pixmap = Pixmap::decode_png(&figure.png).expect("the PNG decodes");
    let px = pixmap
        .pixels()
        .iter()
        .map(|p| {
            let c = p.demultiply();
            [c.red(), c.green(), c.blue(), c.alpha()]
        })
        .collect();
    (pixmap, px)
}

fn rgba(c: Rgba) -> [u8; 4] {
    [c.r, c.g, c.b, c.a]
}

/// The PNG has the figure's size, a good share of ink, many colours and each series colour
/// at full strength (marker centres).
fn check_png(figure: &Figure, series: usize, min_ink_share: f64) {
    let (pixmap, px) = pixels(figure);
    assert_eq!(
        (pixmap.width(), pixmap.height()),
        (figure.width_px, figure.height_px)
    );
    assert!(px.iter().all(|p| p[3] == 255), "background not opaque");
    let ink = px.iter().filter(|p| p[..3] != [255, 255, 255]).count();
    let share = ink as f64 / px.len() as f64;
    assert!(
        share >= min_ink_share,
        "only {:.1} % non-white",
        100.0 * share
    );
    assert!(share < 0.6, "{:.1} % non-white: flooded", 100.0 * share);
    let distinct: HashSet<[u8; 4]> = px.iter().copied().collect();
    assert!(distinct.len() >= 50, "only {} colours", distinct.len());
    for (i, color) in SERIES_COLORS.iter().take(series).enumerate() {
        let exact = px.iter().filter(|p| **p == rgba(*color)).count();
        assert!(
            exact >= 40,
            "series {i} colour {color:?} on only {exact} pixels"
        );
    }
}

fn text_of(doc: &roxmltree::Document) -> Vec<String> {
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| n.text().unwrap_or_default().to_owned())
        .collect()
}

fn count_class(doc: &roxmltree::Document, tag: &str, class: &str) -> usize {
    doc.descendants()
        .filter(|n| n.has_tag_name(tag) && n.attribute("class") == Some(class))
        .count()
}

fn check_radar_svg(figure: &Figure, chart: &RadarChart) {
    let doc = roxmltree::Document::parse(&figure.svg).expect("the SVG parses");
    let root = doc.root_element();
    assert_eq!(
        root.attribute("width"),
        Some(figure.width_px.to_string().as_str())
    );
    assert_eq!(count_class(&doc, "polygon", "series"), chart.series.len());
    let missing = chart
        .series
        .iter()
        .flat_map(|s| &s.values)
        .filter(|v| v.is_none())
        .count();
    assert_eq!(count_class(&doc, "circle", "not-attempted"), missing);
    assert_eq!(
        count_class(&doc, "circle", "marker"),
        chart.series.len() * chart.axes.len() - missing
    );
    let texts = text_of(&doc);
    for label in chart
        .axes
        .iter()
        .chain(chart.series.iter().map(|s| &s.label))
    {
        assert!(texts.contains(label), "no text {label:?} in {texts:?}");
    }
    assert!(
        root.attribute("font-family")
            .unwrap()
            .contains("sans-serif")
    );
}

#[test]
fn paper_radar_charts_render_as_png_and_svg() {
    for (name, chart) in [
        ("radar_manipulation", manipulation_chart()),
        ("radar_grasping", grasping_chart()),
    ] {
        let figure = radar(&chart).unwrap();
        save(name, &figure);
        assert_eq!((figure.width_px, figure.height_px), (800, 800), "{name}");
        check_png(&figure, chart.series.len(), 0.08);
        check_radar_svg(&figure, &chart);
        let texts = text_of(&roxmltree::Document::parse(&figure.svg).unwrap());
        assert!(
            texts.iter().any(|t| t.contains("not attempted")),
            "{name}: {texts:?}"
        );
    }
}

#[test]
fn superhuman_scores_extend_the_rings_and_the_1_0_ring_stays() {
    let figure = radar(&manipulation_chart()).unwrap();
    let texts = text_of(&roxmltree::Document::parse(&figure.svg).unwrap());
    for ring in ["0.2", "0.4", "0.6", "0.8", "1.0", "1.2"] {
        assert!(texts.iter().any(|t| t == ring), "no ring label {ring}");
    }
    assert!(!texts.iter().any(|t| t == "1.4"));
    let grasp = radar(&grasping_chart()).unwrap();
    let texts = text_of(&roxmltree::Document::parse(&grasp.svg).unwrap());
    assert!(texts.iter().any(|t| t == "1.0") && !texts.iter().any(|t| t == "1.2"));
}

#[test]
fn dof_chart_renders_with_points_labels_and_error_bars() {
    let chart = dof_chart();
    let figure = dof_scatter(&chart).unwrap();
    save("dof_overall", &figure);
    assert_eq!((figure.width_px, figure.height_px), (800, 560));
    check_png(&figure, chart.points.len(), 0.03);
    let doc = roxmltree::Document::parse(&figure.svg).unwrap();
    assert_eq!(count_class(&doc, "circle", "point"), 4);
    assert_eq!(count_class(&doc, "polyline", "error-bar"), 3);
    let texts = text_of(&doc);
    for expected in [
        "Orca_2  0.53 ± 0.04",
        "Orca_3  0.62 ± 0.05",
        "Orca_5  0.60",
        "Orca_full  0.71 ± 0.03",
        "Overall score",
        "Degrees of freedom (DoF)",
        // Ticks: DoF 4..18 in steps of 2, score 0.0..1.0.
        "4",
        "8",
        "18",
        "0.0",
        "1.0",
    ] {
        assert!(
            texts.iter().any(|t| t == expected),
            "no {expected:?} in {texts:?}"
        );
    }
}

#[test]
fn rendering_is_deterministic() {
    assert_eq!(radar(&manipulation_chart()), radar(&manipulation_chart()));
    assert_eq!(dof_scatter(&dof_chart()), dof_scatter(&dof_chart()));
}

#[test]
fn bad_inputs_say_what_is_wrong() {
    let mut chart = manipulation_chart();
    chart.series[1].values[9] = Some(f64::INFINITY);
    let err = radar(&chart).unwrap_err();
    assert_eq!(
        err.to_string(),
        "series 'Orca_3', axis 'C2': value inf is not a finite number"
    );
    let mut chart = dof_chart();
    chart.points[2].std = Some(-0.1);
    assert_eq!(
        dof_scatter(&chart),
        Err(PlotError::BadDofValue {
            label: "Orca_5".into(),
            field: "std",
            value: -0.1,
            problem: ValueProblem::Negative,
        })
    );
    chart.points.clear();
    assert!(matches!(
        dof_scatter(&chart),
        Err(PlotError::NoPoints { .. })
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Any valid chart renders; the SVG parses with one polygon per series and every series
    /// vertex lies within the outermost ring.
    #[test]
    fn any_valid_radar_chart_renders(
        axes in 3usize..=18,
        values in prop::collection::vec(
            prop::collection::vec(prop::option::weighted(0.8, 0.0..3.0f64), 18),
            1..=4,
        ),
    ) {
        let chart = RadarChart {
            title: "property".into(),
            axes: (0..axes).map(|i| format!("T{i}")).collect(),
            series: values.iter().enumerate().map(|(i, v)| RadarSeries {
                label: format!("S{i}"),
                values: v[..axes].to_vec(),
            }).collect(),
        };
        let figure = radar(&chart).unwrap();
        let doc = roxmltree::Document::parse(&figure.svg).unwrap();
        prop_assert_eq!(count_class(&doc, "polygon", "series"), chart.series.len());
        let (cx, cy, outer) = doc
            .descendants()
            .filter(|n| n.attribute("class") == Some("ring"))
            .map(|n| ["cx", "cy", "r"].map(|a| n.attribute(a).unwrap().parse::<f64>().unwrap()))
            .map(|[x, y, r]| (x, y, r))
            .next_back()
            .unwrap();
        for polygon in doc.descendants().filter(|n| n.attribute("class") == Some("series")) {
            for pair in polygon.attribute("points").unwrap().split(' ') {
                let (x, y) = pair.split_once(',').unwrap();
                let (x, y): (f64, f64) = (x.parse().unwrap(), y.parse().unwrap());
                prop_assert!((x - cx).hypot(y - cy) <= outer + 0.02);
            }
        }
        let pixmap = Pixmap::decode_png(&figure.png).unwrap();
        prop_assert_eq!((pixmap.width(), pixmap.height()), (figure.width_px, figure.height_px));
    }
}
