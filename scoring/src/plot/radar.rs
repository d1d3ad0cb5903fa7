//! Radar chart: one axis per task, clockwise from the top; one translucent polygon with an
//! outline and point markers per embodiment.

use std::f64::consts::TAU;

use serde::Serialize;

use super::legend::{self, LegendEntry};
use super::palette::{SERIES_COLORS, series_color};
use super::primitives::{Anchor, Drawing, Point, Rgba, Style, Text};
use super::scale::{ScoreAxis, check_score, score_axis};
use super::stroke_font::{cap_height, text_width, wrap};
use super::{Figure, PlotError};

/// One embodiment's scores, one per axis in the chart's axis order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RadarSeries {
    /// Legend label, e.g. `Orca_full`.
    pub label: String,
    /// Score per axis; `None` = task not attempted (drawn at 0 with a hollow marker).
    pub values: Vec<Option<f64>>,
}

/// A radar chart: axes (task IDs) and the series drawn over them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RadarChart {
    /// Title above the chart.
    pub title: String,
    /// Axis labels, drawn clockwise from the top.
    pub axes: Vec<String>,
    /// Up to eight series, one colour each.
    pub series: Vec<RadarSeries>,
}

/// Smallest canvas side in pixels.
const MIN_SIDE_PX: f64 = 800.0;
/// Radius of the outermost ring in pixels.
const RADIUS_PX: f64 = 270.0;
/// Outer margin in pixels.
const MARGIN_PX: f64 = 24.0;
const TITLE_PX: f64 = 22.0;
const AXIS_LABEL_PX: f64 = 18.0;
/// Gap between the outer ring and an axis label.
const AXIS_LABEL_GAP_PX: f64 = 12.0;
const RING_LABEL_PX: f64 = 12.0;
const MARKER_RADIUS_PX: f64 = 5.0;
const FILL_ALPHA: f64 = 0.15;
const OUTLINE_PX: f64 = 2.5;

/// Where values land: the chart's centre, outer radius and axis count.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadarGeometry {
    /// Centre of the rings.
    pub center: Point,
    /// Radius of the outermost ring, in pixels.
    pub radius_px: f64,
    /// The score axis (rings).
    pub scale: ScoreAxis,
    /// Number of axes.
    pub axis_count: usize,
}

impl RadarGeometry {
    /// Unit direction of axis `index` as (sin, cos) of its angle clockwise from the top.
    fn direction(&self, index: f64) -> (f64, f64) {
        (TAU * index / self.axis_count as f64).sin_cos()
    }

    /// Pixel position of `value` on axis `index` (fractional indices lie between axes).
    pub fn point(&self, index: f64, value: f64) -> Point {
        let (sin, cos) = self.direction(index);
        let r = self.radius_px * value / self.scale.top();
        Point::new(self.center.x + r * sin, self.center.y - r * cos)
    }
}

/// Checks `chart` and returns the largest value drawn.
fn validate(chart: &RadarChart) -> Result<f64, PlotError> {
    if chart.axes.len() < 3 {
        return Err(PlotError::TooFewAxes {
            title: chart.title.clone(),
            count: chart.axes.len(),
        });
    }
    if chart.series.is_empty() {
        return Err(PlotError::NoSeries {
            title: chart.title.clone(),
        });
    }
    if chart.series.len() > SERIES_COLORS.len() {
        return Err(PlotError::TooManySeries {
            title: chart.title.clone(),
            count: chart.series.len(),
            max: SERIES_COLORS.len(),
        });
    }
    let mut max = 0.0_f64;
    for series in &chart.series {
        if series.values.len() != chart.axes.len() {
            return Err(PlotError::LengthMismatch {
                series: series.label.clone(),
                values: series.values.len(),
                axes: chart.axes.len(),
            });
        }
        for (axis, value) in chart.axes.iter().zip(&series.values) {
            let Some(value) = *value else { continue };
            check_score(value).map_err(|problem| PlotError::BadRadarValue {
                series: series.label.clone(),
                axis: axis.clone(),
                value,
                problem,
            })?;
            max = max.max(value);
        }
    }
    Ok(max)
}

/// The radar chart as SVG and PNG.
pub fn radar(chart: &RadarChart) -> Result<Figure, PlotError> {
    let (drawing, _) = radar_drawing(chart)?;
    Figure::render(&drawing)
}

/// The radar chart's drawing and the geometry its values were placed with.
pub fn radar_drawing(chart: &RadarChart) -> Result<(Drawing, RadarGeometry), PlotError> {
    let max = validate(chart)?;
    let label_w = chart
        .axes
        .iter()
        .map(|a| text_width(a, AXIS_LABEL_PX))
        .fold(0.0, f64::max);
    let width = MIN_SIDE_PX.max(2.0 * (RADIUS_PX + AXIS_LABEL_GAP_PX + label_w + MARGIN_PX));
    let title_lines = wrap(&chart.title, TITLE_PX, width - 2.0 * MARGIN_PX);
    let title_bottom =
        MARGIN_PX + cap_height(TITLE_PX) + 28.0 * title_lines.len().saturating_sub(1) as f64;
    let label_room = AXIS_LABEL_GAP_PX + cap_height(AXIS_LABEL_PX);
    let geometry = RadarGeometry {
        center: Point::new(width / 2.0, title_bottom + 24.0 + label_room + RADIUS_PX),
        radius_px: RADIUS_PX,
        scale: score_axis(max),
        axis_count: chart.axes.len(),
    };

    let mut items = Drawing::new(0, 0, chart.title.clone());
    draw_grid(&mut items, &geometry);
    draw_series(&mut items, &geometry, chart);
    draw_ring_labels(&mut items, &geometry);
    draw_axis_labels(&mut items, &geometry, &chart.axes);
    for (i, line) in title_lines.iter().enumerate() {
        let at = Point::new(
            width / 2.0,
            MARGIN_PX + cap_height(TITLE_PX) + 28.0 * i as f64,
        );
        let mut title = Text::new(line.clone(), at, Anchor::Middle, TITLE_PX);
        title.bold = true;
        items.text(title);
    }
    let entries: Vec<LegendEntry> = chart
        .series
        .iter()
        .enumerate()
        .map(|(i, s)| LegendEntry {
            label: s.label.clone(),
            color: series_color(i),
            fill_alpha: FILL_ALPHA,
        })
        .collect();
    let legend_top = geometry.center.y + RADIUS_PX + label_room + 28.0;
    let mut bottom = legend::draw(&mut items, &entries, legend_top, width, MARGIN_PX);
    bottom = legend::draw_not_attempted(
        &mut items,
        &not_attempted_notes(chart),
        bottom,
        width,
        MARGIN_PX,
    );

    let height = MIN_SIDE_PX.max((bottom + MARGIN_PX).ceil());
    let drawing = Drawing {
        width_px: width.ceil() as u32,
        height_px: height as u32,
        ..items
    };
    Ok((drawing, geometry))
}

fn draw_grid(drawing: &mut Drawing, geometry: &RadarGeometry) {
    let scale = geometry.scale;
    for tick in scale.ticks() {
        // The 1.0 ring (full correctness at human speed) is darker when scores pass it.
        let emphasised = scale.top() > 1.0 && (tick - 1.0).abs() < 1e-9;
        let (color, width) = if emphasised {
            (Rgba::rgb(136, 136, 136), 1.5)
        } else {
            (Rgba::GRID, 1.0)
        };
        let radius = geometry.radius_px * tick / scale.top();
        drawing.circle(
            geometry.center,
            radius,
            Style::line(color, width),
            Some("ring"),
        );
    }
    for i in 0..geometry.axis_count {
        let end = geometry.point(i as f64, scale.top());
        drawing.line(geometry.center, end, Rgba::GRID, 1.0);
    }
}

fn draw_series(drawing: &mut Drawing, geometry: &RadarGeometry, chart: &RadarChart) {
    let placed = |series: &RadarSeries| -> Vec<Point> {
        (series.values.iter().enumerate())
            .map(|(i, v)| geometry.point(i as f64, v.unwrap_or(0.0)))
            .collect()
    };
    for (i, series) in chart.series.iter().enumerate() {
        let color = series_color(i);
        let style = Style::filled_and_outlined(color.with_alpha(FILL_ALPHA), color, OUTLINE_PX);
        drawing.path(placed(series), true, style, Some("series"));
    }
    // Markers after every polygon, so no fill covers another series' markers.
    for (i, series) in chart.series.iter().enumerate() {
        let color = series_color(i);
        for (value, at) in series.values.iter().zip(placed(series)) {
            if value.is_some() {
                let style = Style::filled_and_outlined(color, Rgba::WHITE, 1.0);
                drawing.circle(at, MARKER_RADIUS_PX, style, Some("marker"));
            } else {
                let style = Style::filled_and_outlined(Rgba::WHITE, color, 2.0);
                drawing.circle(at, MARKER_RADIUS_PX, style, Some("not-attempted"));
            }
        }
    }
}

/// Ring values along the bisector of the first two axes, haloed over the series.
fn draw_ring_labels(drawing: &mut Drawing, geometry: &RadarGeometry) {
    for tick in geometry.scale.ticks() {
        let at = geometry.point(0.5, tick);
        let baseline = Point::new(at.x + 3.0, at.y + cap_height(RING_LABEL_PX) / 2.0);
        let mut text = Text::new(
            geometry.scale.label(tick),
            baseline,
            Anchor::Start,
            RING_LABEL_PX,
        );
        text.color = Rgba::GREY;
        text.halo = true;
        drawing.text(text);
    }
}

/// Axis labels outside the outer ring, anchored away from the centre.
fn draw_axis_labels(drawing: &mut Drawing, geometry: &RadarGeometry, axes: &[String]) {
    let r = geometry.radius_px + AXIS_LABEL_GAP_PX;
    for (i, label) in axes.iter().enumerate() {
        let (sin, cos) = geometry.direction(i as f64);
        let anchor = if sin > 0.25 {
            Anchor::Start
        } else if sin < -0.25 {
            Anchor::End
        } else {
            Anchor::Middle
        };
        // Baseline at the anchor point on top (cos = 1), a cap height lower at the bottom.
        let cap = cap_height(AXIS_LABEL_PX);
        let at = Point::new(
            geometry.center.x + r * sin,
            geometry.center.y - r * cos + cap * (1.0 - cos) / 2.0,
        );
        drawing.text(Text::new(label.clone(), at, anchor, AXIS_LABEL_PX));
    }
}

/// Per series with tasks not attempted: `label: not attempted H2, H3`.
fn not_attempted_notes(chart: &RadarChart) -> Vec<String> {
    let mut notes = Vec::new();
    for series in &chart.series {
        let missing: Vec<&str> = (chart.axes.iter().zip(&series.values))
            .filter(|(_, v)| v.is_none())
            .map(|(a, _)| a.as_str())
            .collect();
        if !missing.is_empty() {
            notes.push(format!(
                "{}: not attempted {}",
                series.label,
                missing.join(", ")
            ));
        }
    }
    notes
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::ValueProblem;
    use crate::plot::primitives::Primitive;

    fn chart(values: &[&[Option<f64>]]) -> RadarChart {
        RadarChart {
            title: "Grasping".into(),
            axes: (1..=values[0].len()).map(|i| format!("G{i}")).collect(),
            series: (values.iter().enumerate())
                .map(|(i, v)| RadarSeries {
                    label: format!("Orca_{i}"),
                    values: v.to_vec(),
                })
                .collect(),
        }
    }

    fn circles(d: &Drawing, class: &str) -> Vec<(Point, f64)> {
        (d.items.iter())
            .filter_map(|item| match item {
                Primitive::Circle {
                    center,
                    radius,
                    class: Some(c),
                    ..
                } if *c == class => Some((*center, *radius)),
                _ => None,
            })
            .collect()
    }

    fn series_polygons(d: &Drawing) -> Vec<&[Point]> {
        (d.items.iter())
            .filter_map(|item| match item {
                Primitive::Path {
                    points,
                    class: Some("series"),
                    ..
                } => Some(points.as_slice()),
                _ => None,
            })
            .collect()
    }

    fn close(a: Point, b: Point) -> bool {
        (a.x - b.x).abs() < 1e-9 && (a.y - b.y).abs() < 1e-9
    }

    #[test]
    fn a_score_of_one_on_the_top_axis_lands_on_the_top_of_the_outer_ring() {
        let (d, g) = radar_drawing(&chart(&[&[Some(1.0), Some(0.5), Some(0.5)]])).unwrap();
        let rings = circles(&d, "ring");
        assert_eq!(rings.len(), 5, "rings at 0.2 .. 1.0");
        let (center, outer) = rings[4];
        let polygon = series_polygons(&d)[0];
        assert!(
            close(polygon[0], Point::new(center.x, center.y - outer)),
            "{:?}",
            polygon[0]
        );
        assert!(close(center, g.center));
        // Axis 1 of 3 is 120° clockwise from the top: right of centre, below it.
        let p = polygon[1];
        let r = 0.5 * outer;
        assert!(close(
            p,
            Point::new(
                center.x + r * (TAU / 3.0).sin(),
                center.y - r * (TAU / 3.0).cos()
            )
        ));
        assert!(p.x > center.x && p.y > center.y);
    }

    #[test]
    fn superhuman_scores_add_rings_and_stay_inside_the_outer_one() {
        let (d, g) = radar_drawing(&chart(&[&[Some(1.13), Some(0.5), Some(1.0)]])).unwrap();
        let rings = circles(&d, "ring");
        assert_eq!(rings.len(), 6, "rings at 0.2 .. 1.2");
        assert!((g.scale.top() - 1.2).abs() < 1e-12);
        let polygon = series_polygons(&d)[0];
        let outer = rings[5].1;
        let top_dist = g.center.y - polygon[0].y;
        assert!((top_dist - outer * 1.13 / 1.2).abs() < 1e-9);
        // The 1.0 value sits on the 1.0 ring.
        let one = (polygon[2].x - g.center.x).hypot(polygon[2].y - g.center.y);
        assert!((one - rings[4].1).abs() < 1e-9);
    }

    #[test]
    fn not_attempted_values_sit_at_the_centre_with_hollow_markers_and_a_note() {
        let (d, g) = radar_drawing(&chart(&[&[Some(0.8), None, Some(0.4)]])).unwrap();
        assert!(close(series_polygons(&d)[0][1], g.center));
        assert_eq!(circles(&d, "not-attempted").len(), 1);
        assert_eq!(circles(&d, "marker").len(), 2);
        let texts: Vec<&str> = (d.items.iter())
            .filter_map(|i| match i {
                Primitive::Text(t) => Some(t.content.as_str()),
                _ => None,
            })
            .collect();
        assert!(texts.contains(&"Orca_0: not attempted G2"), "{texts:?}");
    }

    #[test]
    fn everything_stays_on_the_canvas() {
        let long = chart(&[&[Some(0.9); 12], &[None; 12]]);
        let (d, _) = radar_drawing(&long).unwrap();
        let (w, h) = (f64::from(d.width_px), f64::from(d.height_px));
        for item in &d.items {
            if let Primitive::Text(t) = item {
                let tw = text_width(&t.content, t.size_px);
                let left = match t.anchor {
                    Anchor::Start => t.at.x,
                    Anchor::Middle => t.at.x - tw / 2.0,
                    Anchor::End => t.at.x - tw,
                };
                assert!(
                    left >= 0.0 && left + tw <= w,
                    "{:?} leaves the canvas",
                    t.content
                );
                assert!(
                    t.at.y - cap_height(t.size_px) >= 0.0 && t.at.y + 0.3 * t.size_px <= h,
                    "{:?}",
                    t.content
                );
            }
        }
    }

    #[test]
    fn bad_inputs_are_named() {
        let mut c = chart(&[&[Some(0.1), Some(0.2), Some(0.3)]]);
        c.series[0].values[1] = Some(f64::NAN);
        let err = radar(&c).unwrap_err();
        assert!(
            matches!(&err, PlotError::BadRadarValue { series, axis, problem: ValueProblem::NotFinite, .. } if series == "Orca_0" && axis == "G2"),
            "{err:?}"
        );
        assert!(err.to_string().contains("'Orca_0', axis 'G2'"), "{err}");
        c.series[0].values[1] = Some(-0.5);
        assert!(matches!(
            radar(&c),
            Err(PlotError::BadRadarValue {
                problem: ValueProblem::Negative,
                ..
            })
        ));
        c.series[0].values.pop();
        assert_eq!(
            radar(&c),
            Err(PlotError::LengthMismatch {
                series: "Orca_0".into(),
                values: 2,
                axes: 3
            })
        );
        c.series.clear();
        assert_eq!(
            radar(&c),
            Err(PlotError::NoSeries {
                title: "Grasping".into()
            })
        );
        c.axes.truncate(2);
        assert_eq!(
            radar(&c),
            Err(PlotError::TooFewAxes {
                title: "Grasping".into(),
                count: 2
            })
        );
        let row: &[Option<f64>] = &[Some(0.5); 3];
        let many = chart(&[row; 9]);
        assert!(matches!(
            radar(&many),
            Err(PlotError::TooManySeries {
                count: 9,
                max: 8,
                ..
            })
        ));
    }
}
