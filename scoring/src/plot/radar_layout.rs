//! Radar chart layout: rings, spokes, series polygons and markers, ring and axis labels,
//! title, legend and notes, on a canvas at least 800 px square.

use super::legend::{self, LegendEntry};
use super::palette::series_color;
use super::primitives::{Anchor, Drawing, Point, Rgba, Style, Text};
use super::radar_chart::{RadarChart, RadarGeometry, RadarSeries};
use super::scale::score_axis;
use super::stroke_font::{FONT_SLACK, cap_height, text_width, wrap};

/// Smallest canvas side in pixels.
const MIN_SIDE_PX: f64 = 800.0;
/// Radius of the outermost ring in pixels.
const RADIUS_PX: f64 = 270.0;
/// Outer margin in pixels.
const MARGIN_PX: f64 = 24.0;
const TITLE_PX: f64 = 22.0;
/// Baseline to baseline of a wrapped title.
const TITLE_LINE_PX: f64 = 28.0;
const AXIS_LABEL_PX: f64 = 18.0;
/// Gap between the outer ring and an axis label.
const AXIS_LABEL_GAP_PX: f64 = 12.0;
const RING_LABEL_PX: f64 = 12.0;
const MARKER_RADIUS_PX: f64 = 5.0;
const FILL_ALPHA: f64 = 0.15;
const OUTLINE_PX: f64 = 2.5;

/// Lays out `chart` (already checked; `max` its largest value) and draws it.
pub fn draw(chart: &RadarChart, max: f64) -> (Drawing, RadarGeometry) {
    let label_w = chart
        .axes
        .iter()
        .map(|a| FONT_SLACK * text_width(a, AXIS_LABEL_PX))
        .fold(0.0, f64::max);
    let width = MIN_SIDE_PX.max(2.0 * (RADIUS_PX + AXIS_LABEL_GAP_PX + label_w + MARGIN_PX));
    let title_lines = wrap(
        &chart.title,
        TITLE_PX,
        (width - 2.0 * MARGIN_PX) / FONT_SLACK,
    );
    let title_bottom = MARGIN_PX
        + cap_height(TITLE_PX)
        + TITLE_LINE_PX * title_lines.len().saturating_sub(1) as f64;
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
            MARGIN_PX + cap_height(TITLE_PX) + TITLE_LINE_PX * i as f64,
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
    (drawing, geometry)
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
    use std::f64::consts::TAU;

    use crate::plot::primitives::Primitive;
    use crate::plot::radar_chart::tests::chart;
    use crate::plot::radar_chart::validate;

    /// `chart` checked and laid out.
    fn laid_out(chart: &RadarChart) -> (Drawing, RadarGeometry) {
        let max = validate(chart).unwrap();
        draw(chart, max)
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
        let (d, g) = laid_out(&chart(&[&[Some(1.0), Some(0.5), Some(0.5)]]));
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
        let (d, g) = laid_out(&chart(&[&[Some(1.13), Some(0.5), Some(1.0)]]));
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
        let (d, g) = laid_out(&chart(&[&[Some(0.8), None, Some(0.4)]]));
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
        let (d, _) = laid_out(&long);
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
}
