//! Radar chart input, checks and geometry: one axis per task, clockwise from the top, a
//! value's distance from the centre proportional to the score.

use std::f64::consts::TAU;

use serde::Serialize;

use super::PlotError;
use super::palette::SERIES_COLORS;
use super::primitives::Point;
use super::scale::{ScoreAxis, check_score};

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
    pub fn direction(&self, index: f64) -> (f64, f64) {
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
pub(super) fn validate(chart: &RadarChart) -> Result<f64, PlotError> {
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

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A chart of `values` (one slice per series) on axes G1, G2, …
    pub(crate) fn chart(values: &[&[Option<f64>]]) -> RadarChart {
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

    #[test]
    fn axes_run_clockwise_from_the_top() {
        let g = RadarGeometry {
            center: Point::new(100.0, 100.0),
            radius_px: 50.0,
            scale: crate::plot::scale::score_axis(1.0),
            axis_count: 4,
        };
        let close = |a: Point, x: f64, y: f64| (a.x - x).abs() < 1e-9 && (a.y - y).abs() < 1e-9;
        assert!(close(g.point(0.0, 1.0), 100.0, 50.0), "top");
        assert!(close(g.point(1.0, 1.0), 150.0, 100.0), "right");
        assert!(close(g.point(2.0, 0.5), 100.0, 125.0), "bottom, half way");
        assert!(close(g.point(3.0, 0.0), 100.0, 100.0), "zero at the centre");
    }
}
