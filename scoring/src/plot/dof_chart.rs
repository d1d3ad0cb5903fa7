//! Overall score against degrees of freedom: one labelled point per embodiment, with error
//! bars when a standard deviation is given.

use serde::Serialize;

use super::chart_frame::{
    AXIS_TITLE_PX, HEIGHT_PX, MARGIN_PX, NOTE_PX, TICK_LEN_PX, TICK_PX, TITLE_PX, WIDTH_PX,
    draw_score_ticks,
};
use super::label_placement::{Rect, place_label};
use super::palette::series_color;
use super::primitives::{Anchor, Drawing, Point, Rgba, Style, Text};
use super::scale::{ScoreAxis, check_score, integer_axis, score_axis};
use super::stroke_font::{FONT_SLACK, cap_height, text_width};
use super::{Figure, PlotError};

/// One embodiment's result.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DofPoint {
    /// Point label, e.g. `Orca_5`.
    pub label: String,
    /// The embodiment's degrees of freedom (x).
    pub dof: u32,
    /// Its overall score (y).
    pub overall: f64,
    /// Standard deviation of the overall score, drawn as ± error bars.
    pub std: Option<f64>,
}

/// A scatter of overall score against degrees of freedom.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DofChart {
    /// Title above the chart.
    pub title: String,
    /// Y axis label, e.g. `Overall score`.
    pub y_label: String,
    /// The embodiments.
    pub points: Vec<DofPoint>,
}

const POINT_LABEL_PX: f64 = 14.0;
const POINT_RADIUS_PX: f64 = 6.5;
const ERROR_CAP_HALF_PX: f64 = 6.0;

/// The plot area and the data-to-pixel mapping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DofGeometry {
    /// Plot area in pixels.
    pub area: Rect,
    /// X axis: first DoF, last DoF, tick step.
    pub dof_range: (u64, u64, u64),
    /// Y axis from 0.
    pub scale: ScoreAxis,
}

impl DofGeometry {
    /// Pixel x of `dof`.
    pub fn x(&self, dof: f64) -> f64 {
        let (lo, hi, _) = self.dof_range;
        self.area.left + (dof - lo as f64) / (hi - lo) as f64 * self.area.width()
    }

    /// Pixel y of `score`.
    pub fn y(&self, score: f64) -> f64 {
        self.area.bottom - score / self.scale.top() * self.area.height()
    }
}

fn validate(chart: &DofChart) -> Result<f64, PlotError> {
    if chart.points.is_empty() {
        return Err(PlotError::NoPoints {
            title: chart.title.clone(),
        });
    }
    let mut max = 0.0_f64;
    for p in &chart.points {
        let bad = |field, value| {
            move |problem| PlotError::BadDofValue {
                label: p.label.clone(),
                field,
                value,
                problem,
            }
        };
        check_score(p.overall).map_err(bad("overall", p.overall))?;
        let std = p.std.unwrap_or(0.0);
        check_score(std).map_err(bad("std", std))?;
        max = max.max(p.overall + std);
    }
    Ok(max)
}

/// The DoF chart as SVG and PNG.
pub fn dof_scatter(chart: &DofChart) -> Result<Figure, PlotError> {
    let (drawing, _) = dof_drawing(chart)?;
    Figure::render(&drawing)
}

/// The DoF chart's drawing and the geometry its points were placed with.
pub fn dof_drawing(chart: &DofChart) -> Result<(Drawing, DofGeometry), PlotError> {
    let max = validate(chart)?;
    let geometry = layout(chart, score_axis(max));
    let mut d = Drawing::new(WIDTH_PX as u32, HEIGHT_PX as u32, chart.title.clone());
    draw_grid_and_axes(&mut d, &geometry);
    draw_titles(&mut d, &geometry, chart);
    draw_points(&mut d, &geometry, chart);
    Ok((d, geometry))
}

/// Baseline x of the rotated y axis title.
fn y_title_x() -> f64 {
    MARGIN_PX + cap_height(AXIS_TITLE_PX)
}

/// Baseline y of the x axis tick labels.
fn x_tick_label_y(area: Rect) -> f64 {
    area.bottom + TICK_LEN_PX + 4.0 + cap_height(TICK_PX)
}

/// The plot area (leaving room for the widest score tick label) and the axes' ranges.
fn layout(chart: &DofChart, scale: ScoreAxis) -> DofGeometry {
    let tick_w = scale
        .ticks()
        .map(|t| text_width(&scale.label(t), TICK_PX))
        .fold(text_width("0.0", TICK_PX), f64::max);
    let dofs = chart.points.iter().map(|p| p.dof);
    let (min_dof, max_dof) = (dofs.clone().min().unwrap_or(0), dofs.max().unwrap_or(0));
    DofGeometry {
        area: Rect {
            left: y_title_x() + 14.0 + FONT_SLACK * tick_w + 8.0 + TICK_LEN_PX,
            right: WIDTH_PX - 30.0,
            top: 84.0,
            bottom: HEIGHT_PX - 82.0,
        },
        dof_range: integer_axis(min_dof, max_dof),
        scale,
    }
}

/// Grid lines, ticks and tick labels on both axes, then the axis lines.
fn draw_grid_and_axes(d: &mut Drawing, geometry: &DofGeometry) {
    let area = geometry.area;
    let tick_y = x_tick_label_y(area);
    let (lo, hi, step) = geometry.dof_range;
    for dof in (lo..=hi).step_by(step.max(1) as usize) {
        let x = geometry.x(dof as f64);
        d.line(
            Point::new(x, area.top),
            Point::new(x, area.bottom),
            Rgba::GRID,
            1.0,
        );
        d.line(
            Point::new(x, area.bottom),
            Point::new(x, area.bottom + TICK_LEN_PX),
            Rgba::INK,
            1.0,
        );
        d.text(Text::new(
            dof.to_string(),
            Point::new(x, tick_y),
            Anchor::Middle,
            TICK_PX,
        ));
    }
    let scale = geometry.scale;
    draw_score_ticks(d, area, &scale);
    let axes = vec![
        Point::new(area.left, area.top),
        Point::new(area.left, area.bottom),
        Point::new(area.right, area.bottom),
    ];
    d.path(axes, false, Style::line(Rgba::INK, 1.2), Some("axes"));
}

/// The chart title, the error bar note (when any point has a std) and the axis titles.
fn draw_titles(d: &mut Drawing, geometry: &DofGeometry, chart: &DofChart) {
    let area = geometry.area;
    let mut title = Text::new(
        chart.title.clone(),
        Point::new(WIDTH_PX / 2.0, MARGIN_PX + cap_height(TITLE_PX)),
        Anchor::Middle,
        TITLE_PX,
    );
    title.bold = true;
    d.text(title);
    if chart.points.iter().any(|p| p.std.is_some()) {
        let mut note = Text::new(
            "Error bars: \u{b1}1 standard deviation",
            Point::new(WIDTH_PX / 2.0, 64.0),
            Anchor::Middle,
            NOTE_PX,
        );
        note.color = Rgba::GREY;
        d.text(note);
    }
    let x_title_at = Point::new(
        (area.left + area.right) / 2.0,
        x_tick_label_y(area) + 14.0 + cap_height(AXIS_TITLE_PX),
    );
    d.text(Text::new(
        "Degrees of freedom (DoF)",
        x_title_at,
        Anchor::Middle,
        AXIS_TITLE_PX,
    ));
    let mut y_title = Text::new(
        chart.y_label.clone(),
        Point::new(y_title_x(), (area.top + area.bottom) / 2.0),
        Anchor::Middle,
        AXIS_TITLE_PX,
    );
    y_title.rotate_deg = -90.0;
    d.text(y_title);
}

fn draw_points(d: &mut Drawing, geometry: &DofGeometry, chart: &DofChart) {
    let centre = |p: &DofPoint| Point::new(geometry.x(f64::from(p.dof)), geometry.y(p.overall));
    // Everything a label must not cover: markers and error bars.
    let mut obstacles = Vec::new();
    for (i, p) in chart.points.iter().enumerate() {
        let c = centre(p);
        obstacles.push(Rect::around(
            c,
            POINT_RADIUS_PX + 2.0,
            POINT_RADIUS_PX + 2.0,
        ));
        let Some(std) = p.std else { continue };
        let color = series_color(i);
        let (top, bottom) = (
            geometry.y(p.overall + std),
            geometry.y((p.overall - std).max(0.0)),
        );
        d.path(
            vec![Point::new(c.x, top), Point::new(c.x, bottom)],
            false,
            Style::line(color, 1.8),
            Some("error-bar"),
        );
        for y in [top, bottom] {
            d.line(
                Point::new(c.x - ERROR_CAP_HALF_PX, y),
                Point::new(c.x + ERROR_CAP_HALF_PX, y),
                color,
                1.8,
            );
        }
        obstacles.push(Rect {
            left: c.x - ERROR_CAP_HALF_PX,
            right: c.x + ERROR_CAP_HALF_PX,
            top,
            bottom,
        });
    }
    for (i, p) in chart.points.iter().enumerate() {
        let style = Style::filled_and_outlined(series_color(i), Rgba::WHITE, 1.5);
        d.circle(centre(p), POINT_RADIUS_PX, style, Some("point"));
    }
    for p in &chart.points {
        let content = match p.std {
            Some(std) => format!("{}  {:.2} \u{b1} {:.2}", p.label, p.overall, std),
            None => format!("{}  {:.2}", p.label, p.overall),
        };
        let (text, used) = place_label(
            content,
            centre(p),
            POINT_LABEL_PX,
            geometry.area,
            &obstacles,
        );
        obstacles.push(used);
        d.text(text);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::ValueProblem;
    use crate::plot::primitives::Primitive;

    fn chart(points: &[(u32, f64, Option<f64>)]) -> DofChart {
        DofChart {
            title: "DoF".into(),
            y_label: "Overall score".into(),
            points: (points.iter().enumerate())
                .map(|(i, &(dof, overall, std))| DofPoint {
                    label: format!("Orca_{i}"),
                    dof,
                    overall,
                    std,
                })
                .collect(),
        }
    }

    fn shapes<'a>(d: &'a Drawing, class: &str) -> Vec<&'a Primitive> {
        (d.items.iter())
            .filter(|item| match item {
                Primitive::Path { class: c, .. } | Primitive::Circle { class: c, .. } => {
                    *c == Some(class)
                }
                Primitive::Text(_) => false,
            })
            .collect()
    }

    #[test]
    fn points_land_on_their_dof_and_score() {
        let (d, g) = dof_drawing(&chart(&[(5, 0.53, None), (16, 0.71, None)])).unwrap();
        assert_eq!(g.dof_range, (4, 18, 2));
        assert_eq!(g.scale.top(), 1.0);
        assert!((g.x(4.0) - g.area.left).abs() < 1e-9 && (g.x(18.0) - g.area.right).abs() < 1e-9);
        assert!((g.y(0.0) - g.area.bottom).abs() < 1e-9 && (g.y(1.0) - g.area.top).abs() < 1e-9);
        let centres: Vec<Point> = (shapes(&d, "point").into_iter())
            .filter_map(|p| match p {
                Primitive::Circle { center, .. } => Some(*center),
                _ => None,
            })
            .collect();
        assert_eq!(
            centres,
            [
                Point::new(g.x(5.0), g.y(0.53)),
                Point::new(g.x(16.0), g.y(0.71))
            ]
        );
        assert!(shapes(&d, "error-bar").is_empty());
    }

    #[test]
    fn error_bars_span_one_std_and_stop_at_zero() {
        let (d, g) = dof_drawing(&chart(&[(8, 0.62, Some(0.05)), (11, 0.03, Some(0.1))])).unwrap();
        let bars: Vec<(f64, f64)> = (shapes(&d, "error-bar").into_iter())
            .filter_map(|p| match p {
                Primitive::Path { points, .. } => Some((points[0].y, points[1].y)),
                _ => None,
            })
            .collect();
        assert_eq!(bars.len(), 2);
        assert!((bars[0].0 - g.y(0.67)).abs() < 1e-9 && (bars[0].1 - g.y(0.57)).abs() < 1e-9);
        assert!((bars[1].1 - g.area.bottom).abs() < 1e-9, "clamped at 0");
    }

    #[test]
    fn the_score_axis_grows_past_one_for_superhuman_results() {
        let (_, g) = dof_drawing(&chart(&[(16, 1.1, Some(0.15))])).unwrap();
        assert!((g.scale.top() - 1.4).abs() < 1e-9, "{}", g.scale.top());
    }

    #[test]
    fn bad_points_are_named() {
        let err = dof_scatter(&chart(&[(5, f64::NAN, None)])).unwrap_err();
        assert!(matches!(
            &err,
            PlotError::BadDofValue { label, field: "overall", problem: ValueProblem::NotFinite, .. }
                if label == "Orca_0"
        ));
        assert!(
            err.to_string()
                .starts_with("point 'Orca_0', overall: value NaN"),
            "{err}"
        );
        let err = dof_scatter(&chart(&[(5, 0.5, Some(f64::INFINITY))])).unwrap_err();
        assert!(matches!(err, PlotError::BadDofValue { field: "std", .. }));
        assert_eq!(
            dof_scatter(&chart(&[])),
            Err(PlotError::NoPoints {
                title: "DoF".into()
            })
        );
    }
}
