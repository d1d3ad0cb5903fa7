//! What can be wrong with a chart's input.

use std::fmt;

/// Why a number cannot be drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ValueProblem {
    /// NaN or infinite.
    NotFinite,
    /// Below zero: scores and standard deviations are never negative.
    Negative,
    /// Above [`MAX_SCORE`](super::MAX_SCORE): taken as a units or parsing mistake.
    TooLarge,
}

impl fmt::Display for ValueProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite => write!(f, "not a finite number"),
            Self::Negative => write!(f, "negative"),
            Self::TooLarge => write!(
                f,
                "above {}, the largest score a figure draws",
                super::MAX_SCORE
            ),
        }
    }
}

/// A chart that cannot be drawn, and why.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlotError {
    /// A radar chart without series.
    #[error("radar chart '{title}' has no series to draw")]
    NoSeries {
        /// The chart's title.
        title: String,
    },
    /// A radar chart with fewer than three axes (no polygon to draw).
    #[error("radar chart '{title}' has {count} axes; a radar chart needs at least 3")]
    TooFewAxes {
        /// The chart's title.
        title: String,
        /// How many axes it has.
        count: usize,
    },
    /// More radar series than the palette has distinct colours.
    #[error("radar chart '{title}' has {count} series; at most {max} can be told apart by colour")]
    TooManySeries {
        /// The chart's title.
        title: String,
        /// How many series it has.
        count: usize,
        /// The palette's size.
        max: usize,
    },
    /// A series with a different number of values than the chart has axes.
    #[error("series '{series}' has {values} values but the chart has {axes} axes")]
    LengthMismatch {
        /// The series' label.
        series: String,
        /// How many values it has.
        values: usize,
        /// How many axes the chart has.
        axes: usize,
    },
    /// A radar value that cannot be drawn.
    #[error("series '{series}', axis '{axis}': value {value} is {problem}")]
    BadRadarValue {
        /// The series' label.
        series: String,
        /// The axis' label.
        axis: String,
        /// The value given.
        value: f64,
        /// What is wrong with it.
        problem: ValueProblem,
    },
    /// A DoF chart without points.
    #[error("DoF chart '{title}' has no points to draw")]
    NoPoints {
        /// The chart's title.
        title: String,
    },
    /// A DoF point's score or standard deviation that cannot be drawn.
    #[error("point '{label}', {field}: value {value} is {problem}")]
    BadDofValue {
        /// The point's label.
        label: String,
        /// `overall` or `std`.
        field: &'static str,
        /// The value given.
        value: f64,
        /// What is wrong with it.
        problem: ValueProblem,
    },
    /// A scatter chart without points.
    #[error("scatter chart '{title}' has no points to draw")]
    NoScatterPoints {
        /// The chart's title.
        title: String,
    },
    /// More scatter series than colours × marker styles.
    #[error(
        "scatter chart '{title}' has {count} series; at most {max} can be told apart by colour \
         and marker"
    )]
    TooManyScatterSeries {
        /// The chart's title.
        title: String,
        /// How many series it has.
        count: usize,
        /// Colours × marker styles.
        max: usize,
    },
    /// A scatter point's coordinate that cannot be drawn.
    #[error("series '{series}', point {index}, {axis}: value {value} is {problem}")]
    BadScatterValue {
        /// The series' label.
        series: String,
        /// The point's index in its series (0-based).
        index: usize,
        /// `x` or `y`.
        axis: &'static str,
        /// The value given.
        value: f64,
        /// What is wrong with it.
        problem: ValueProblem,
    },
    /// A chart of panels without panels.
    #[error("panel chart '{title}' has no panels to draw")]
    NoPanels {
        /// The chart's title.
        title: String,
    },
    /// A panel's point that cannot be drawn.
    #[error("panel '{panel}', {series} point {index}, {axis}: value {value} is {problem}")]
    BadPanelValue {
        /// The panel's title.
        panel: String,
        /// `commanded` or `measured`.
        series: &'static str,
        /// The point's index in its series (0-based).
        index: usize,
        /// `time` or `angle`.
        axis: &'static str,
        /// The value given.
        value: f64,
        /// What is wrong with it.
        problem: ValueProblem,
    },
    /// A bar chart without categories or series.
    #[error("bar chart '{title}' has nothing to draw (no categories or no series)")]
    NoBars {
        /// The chart's title.
        title: String,
    },
    /// More bar series than the palette has distinct colours.
    #[error("bar chart '{title}' has {count} series; at most {max} can be told apart by colour")]
    TooManyBarSeries {
        /// The chart's title.
        title: String,
        /// How many series it has.
        count: usize,
        /// The palette's size.
        max: usize,
    },
    /// A bar series with a different number of values than the chart has categories.
    #[error("bar series '{series}' has {values} values but the chart has {categories} categories")]
    BarCountMismatch {
        /// The series' label.
        series: String,
        /// How many values it has.
        values: usize,
        /// How many categories the chart has.
        categories: usize,
    },
    /// A bar's mean or standard deviation that cannot be drawn.
    #[error("bar series '{series}', category '{category}', {field}: value {value} is {problem}")]
    BadBarValue {
        /// The series' label.
        series: String,
        /// The category's label and band.
        category: String,
        /// `mean` or `std`.
        field: &'static str,
        /// The value given.
        value: f64,
        /// What is wrong with it.
        problem: ValueProblem,
    },
    /// The rasteriser could not make the canvas or encode the PNG.
    #[error("could not rasterise the figure: {reason}")]
    Raster {
        /// What failed.
        reason: String,
    },
}
