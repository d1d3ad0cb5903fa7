//! The radar chart figure: the chart checked, laid out and rendered.

use super::primitives::Drawing;
use super::radar_chart::{RadarChart, RadarGeometry, validate};
use super::radar_layout;
use super::{Figure, PlotError};

/// The radar chart as SVG and PNG.
pub fn radar(chart: &RadarChart) -> Result<Figure, PlotError> {
    let (drawing, _) = radar_drawing(chart)?;
    Figure::render(&drawing)
}

/// The radar chart's drawing and the geometry its values were placed with.
pub fn radar_drawing(chart: &RadarChart) -> Result<(Drawing, RadarGeometry), PlotError> {
    let max = validate(chart)?;
    Ok(radar_layout::draw(chart, max))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::ValueProblem;
    use crate::plot::radar_chart::tests::chart;

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
