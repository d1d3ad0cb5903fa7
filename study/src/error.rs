//! What can stop the strategy analysis, with messages that name the setting, trial or
//! component and the allowed range.

use crate::skip::SkippedTrial;

/// Why the strategy analysis (or one of its figures) could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StudyError {
    /// A setting outside its allowed range.
    #[error("strategy setting {name} = {value} is outside its allowed range ({allowed})")]
    BadSetting {
        /// The setting's name, e.g. `segment_s`.
        name: &'static str,
        /// The value given, as text.
        value: String,
        /// The allowed range, in words.
        allowed: &'static str,
    },
    /// No trials were given.
    #[error("strategy analysis was given no trials")]
    NoTrials,
    /// Trials recorded with different keypoint layouts cannot share one feature space.
    #[error(
        "trial '{first_trial}' uses keypoint layout {first_layout} but trial '{other_trial}' \
         uses {other_layout}; analyse one layout at a time"
    )]
    MixedLayouts {
        /// The first usable trial.
        first_trial: String,
        /// Its layout's name.
        first_layout: &'static str,
        /// A later trial with another layout.
        other_trial: String,
        /// That trial's layout's name.
        other_layout: &'static str,
    },
    /// Every trial was skipped.
    #[error("none of the {trials} trials gave a usable segment: {}", list_reasons(.skipped))]
    NoSegments {
        /// How many trials were given.
        trials: usize,
        /// Each trial and why it was skipped.
        skipped: Vec<SkippedTrial>,
    },
    /// Fewer than two segments overall.
    #[error("strategy analysis needs at least 2 segments; the usable trials gave {found}")]
    TooFewSegments {
        /// How many segments there were.
        found: usize,
    },
    /// Fewer than two tasks among the usable segments: there is nothing to separate.
    #[error(
        "strategy analysis needs segments from at least 2 tasks; found {} ({}) over {segments} \
         segments",
        .tasks.len(),
        .tasks.join(", ")
    )]
    TooFewTasks {
        /// The tasks found.
        tasks: Vec<String>,
        /// How many segments they have.
        segments: usize,
    },
    /// Every feature is the same in every segment.
    #[error(
        "all {segments} segments have identical features (no feature varies by more than \
         {tolerance:e} hand lengths): there is no motion to analyse"
    )]
    NoVariance {
        /// How many segments there were.
        segments: usize,
        /// The largest standard deviation still counted as constant.
        tolerance: f64,
    },
    /// The singular value decomposition did not converge.
    #[error(
        "the PCA's singular value decomposition of {rows} segments × {columns} features did \
         not converge"
    )]
    PcaNotConverged {
        /// Segments.
        rows: usize,
        /// Features.
        columns: usize,
    },
    /// A figure asked for a principal component the analysis did not keep.
    #[error(
        "the figure asks for PC{requested} but the analysis kept {kept} components \
         (PC1 to PC{kept}); pick two different components in that range"
    )]
    BadComponent {
        /// The component asked for (1-based).
        requested: usize,
        /// How many components the analysis kept.
        kept: usize,
    },
    /// A figure with the same component on both axes.
    #[error("the figure has PC{component} on both axes; pick two different components")]
    SameComponent {
        /// The component (1-based).
        component: usize,
    },
    /// The chart could not be drawn.
    #[error("could not draw the strategy figure: {0}")]
    Plot(#[from] scoring::plot::PlotError),
}

fn list_reasons(skipped: &[SkippedTrial]) -> String {
    let reasons: Vec<String> = skipped.iter().map(ToString::to_string).collect();
    reasons.join("; ")
}
