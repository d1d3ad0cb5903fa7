//! The strategy analysis: segments of every trial, their principal components, and how well
//! the segments separate by task.

use std::collections::BTreeSet;

use retarget::KeypointLayout;
use serde::Serialize;

use crate::cluster_strength::ClusterStrength;
use crate::error::StudyError;
use crate::motion::TrialMotion;
use crate::pca;
use crate::segments::{feature_names, trial_segments};
use crate::settings::StrategySettings;
use crate::silhouette::silhouette_values;
use crate::skip::SkippedTrial;

/// One segment's place in the principal component space.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SegmentScore {
    /// Participant label.
    pub participant: String,
    /// Task label.
    pub task: String,
    /// Trial label.
    pub trial: String,
    /// Window start on the trial's clock, seconds.
    pub start_s: f64,
    /// Usable frames in the window.
    pub frames: usize,
    /// Score on each kept component (PC1 first).
    pub scores: Vec<f64>,
    /// This segment's silhouette value, clusters = tasks.
    pub silhouette: f64,
}

/// How well one task's segments separate from the others'.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TaskSeparation {
    /// Task label.
    pub task: String,
    /// Its segments.
    pub segments: usize,
    /// Its trials that gave segments.
    pub trials: usize,
    /// Distinct participants among them.
    pub participants: usize,
    /// Mean silhouette value of its segments.
    pub mean_silhouette: f64,
}

/// The result of [`analyse`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StrategyAnalysis {
    /// The settings used.
    pub settings: StrategySettings,
    /// The keypoint layout of every analysed trial.
    pub layout: KeypointLayout,
    /// One name per feature, in feature (and loading) order.
    pub feature_names: Vec<String>,
    /// Features constant over all segments (standardised to 0).
    pub constant_features: usize,
    /// Components kept: the requested number, or fewer when segments − 1 or the number of
    /// varying features is smaller.
    pub components_kept: usize,
    /// Per kept component: its fraction of the standardised features' total variance.
    pub variance_explained: Vec<f64>,
    /// Per kept component: its unit-length loading on each feature.
    pub loadings: Vec<Vec<f64>>,
    /// Every segment, in trial order then time order.
    pub segments: Vec<SegmentScore>,
    /// Mean silhouette over all segments, Euclidean in the kept components' score space,
    /// clusters = tasks.
    pub silhouette: f64,
    /// Per task, in order of first appearance in the input.
    pub per_task: Vec<TaskSeparation>,
    /// Distinct participants among the analysed segments.
    pub participants: usize,
    /// Trials that gave segments.
    pub trials_used: usize,
    /// Trials left out, with the reason.
    pub skipped: Vec<SkippedTrial>,
    /// Frames left out of analysed trials because their palm frame collapsed.
    pub collapsed_frames: usize,
    /// Complete windows of analysed trials dropped for too few usable frames.
    pub dropped_windows: usize,
}

impl StrategyAnalysis {
    /// Kaufman & Rousseeuw's band of the overall mean silhouette.
    pub fn verdict(&self) -> ClusterStrength {
        ClusterStrength::from_silhouette(self.silhouette)
    }
}

/// Every trial's segments, before the PCA.
struct Collected {
    layout: KeypointLayout,
    rows: Vec<Vec<f64>>,
    segments: Vec<SegmentScore>,
    trials_used: usize,
    skipped: Vec<SkippedTrial>,
    collapsed_frames: usize,
    dropped_windows: usize,
}

/// The strategy analysis of `trials` (see the crate documentation for the method).
pub fn analyse(
    trials: &[TrialMotion],
    settings: &StrategySettings,
) -> Result<StrategyAnalysis, StudyError> {
    settings.validate()?;
    let c = collect(trials, settings)?;
    let tasks = first_appearance(c.segments.iter().map(|s| s.task.as_str()));
    if c.segments.len() < 2 {
        return Err(StudyError::TooFewSegments {
            found: c.segments.len(),
        });
    }
    if tasks.len() < 2 {
        return Err(StudyError::TooFewTasks {
            tasks,
            segments: c.segments.len(),
        });
    }
    let labels: Vec<usize> = (c.segments.iter())
        .map(|s| tasks.iter().position(|t| *t == s.task).unwrap_or(0))
        .collect();
    let fit = pca::fit(&c.rows, settings.components)?;
    let values = silhouette_values(&fit.scores, &labels);
    let mut segments = c.segments;
    for ((segment, scores), s) in segments.iter_mut().zip(fit.scores).zip(&values) {
        segment.scores = scores;
        segment.silhouette = *s;
    }
    Ok(StrategyAnalysis {
        settings: settings.clone(),
        layout: c.layout,
        feature_names: feature_names(c.layout),
        constant_features: fit.constant_features,
        components_kept: fit.variance_explained.len(),
        variance_explained: fit.variance_explained,
        loadings: fit.loadings,
        silhouette: mean(&values),
        per_task: tasks.iter().map(|t| separation(t, &segments)).collect(),
        participants: first_appearance(segments.iter().map(|s| s.participant.as_str())).len(),
        segments,
        trials_used: c.trials_used,
        skipped: c.skipped,
        collapsed_frames: c.collapsed_frames,
        dropped_windows: c.dropped_windows,
    })
}

/// Segments and feature rows of every usable trial; skipped trials with their reasons.
fn collect(trials: &[TrialMotion], settings: &StrategySettings) -> Result<Collected, StudyError> {
    let Some(first) = trials.first() else {
        return Err(StudyError::NoTrials);
    };
    let mut c = Collected {
        layout: first.layout,
        rows: Vec::new(),
        segments: Vec::new(),
        trials_used: 0,
        skipped: Vec::new(),
        collapsed_frames: 0,
        dropped_windows: 0,
    };
    let mut layout_from: Option<&TrialMotion> = None;
    for trial in trials {
        let found = match trial_segments(trial, settings) {
            Ok(found) => found,
            Err(reason) => {
                c.skipped.push(SkippedTrial {
                    participant: trial.participant.clone(),
                    task: trial.task.clone(),
                    trial: trial.trial.clone(),
                    reason,
                });
                continue;
            }
        };
        match layout_from {
            Some(earlier) if earlier.layout != trial.layout => {
                return Err(StudyError::MixedLayouts {
                    first_trial: earlier.trial.clone(),
                    first_layout: earlier.layout.name(),
                    other_trial: trial.trial.clone(),
                    other_layout: trial.layout.name(),
                });
            }
            Some(_) => {}
            None => {
                layout_from = Some(trial);
                c.layout = trial.layout;
            }
        }
        c.trials_used += 1;
        c.collapsed_frames += found.collapsed_frames;
        c.dropped_windows += found.dropped_windows;
        for segment in found.segments {
            c.rows.push(segment.features);
            c.segments.push(SegmentScore {
                participant: trial.participant.clone(),
                task: trial.task.clone(),
                trial: trial.trial.clone(),
                start_s: segment.start_s,
                frames: segment.frames,
                scores: Vec::new(),
                silhouette: 0.0,
            });
        }
    }
    if c.segments.is_empty() {
        return Err(StudyError::NoSegments {
            trials: trials.len(),
            skipped: c.skipped,
        });
    }
    Ok(c)
}

/// Distinct labels in order of first appearance.
fn first_appearance<'a>(labels: impl Iterator<Item = &'a str>) -> Vec<String> {
    let mut seen = Vec::<String>::new();
    for label in labels {
        if !seen.iter().any(|s| s == label) {
            seen.push(label.to_owned());
        }
    }
    seen
}

fn separation(task: &str, segments: &[SegmentScore]) -> TaskSeparation {
    let own: Vec<&SegmentScore> = segments.iter().filter(|s| s.task == task).collect();
    let trials: BTreeSet<(&str, &str)> = (own.iter())
        .map(|s| (s.participant.as_str(), s.trial.as_str()))
        .collect();
    let participants: BTreeSet<&str> = own.iter().map(|s| s.participant.as_str()).collect();
    let values: Vec<f64> = own.iter().map(|s| s.silhouette).collect();
    TaskSeparation {
        task: task.to_owned(),
        segments: own.len(),
        trials: trials.len(),
        participants: participants.len(),
        mean_silhouette: mean(&values),
    }
}

fn mean(values: &[f64]) -> f64 {
    if values.is_empty() {
        0.0
    } else {
        values.iter().sum::<f64>() / values.len() as f64
    }
}
