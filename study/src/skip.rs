//! Trials the analysis leaves out, and why.

use std::fmt;

use serde::Serialize;

/// Why a trial gave no segment.
#[derive(Debug, Clone, PartialEq, Serialize, thiserror::Error)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SkipReason {
    /// The trial has no frames.
    #[error("it has no frames")]
    NoFrames,
    /// A frame with the wrong number of keypoints for the trial's layout.
    #[error("frame {frame} has {found} points but layout {layout} has {expected}")]
    WrongPointCount {
        /// Frame index (0-based).
        frame: usize,
        /// Points in that frame.
        found: usize,
        /// Points the layout has.
        expected: usize,
        /// The layout's name.
        layout: &'static str,
    },
    /// A frame time that is NaN or infinite.
    #[error("frame {frame} has time {t_s} s, not a finite number")]
    NonFiniteTime {
        /// Frame index (0-based).
        frame: usize,
        /// The time given.
        t_s: f64,
    },
    /// A keypoint coordinate that is NaN or infinite.
    #[error("frame {frame}, point {point} ({name}) is not finite")]
    NonFinitePoint {
        /// Frame index (0-based).
        frame: usize,
        /// Point index in the layout.
        point: usize,
        /// The point's name in the layout.
        name: String,
    },
    /// Frame times that do not strictly increase.
    #[error(
        "frame {frame} is at {t_s} s, not after the previous frame at {previous_s} s \
         (times must strictly increase)"
    )]
    TimeNotIncreasing {
        /// Frame index (0-based).
        frame: usize,
        /// The previous frame's time.
        previous_s: f64,
        /// This frame's time.
        t_s: f64,
    },
    /// Every frame's palm landmarks collapsed (no palm frame could be built).
    #[error("the palm frame collapsed in all {frames} frames (first: {first})")]
    AllPalmsCollapsed {
        /// How many frames there were.
        frames: usize,
        /// The first frame's reason.
        first: String,
    },
    /// The trial is shorter than one segment.
    #[error("it lasts {duration_s:.3} s, shorter than one {segment_s} s segment")]
    TooShort {
        /// The time the trial covers (last frame − first frame + one frame interval).
        duration_s: f64,
        /// The segment length.
        segment_s: f64,
    },
    /// Every complete window had too few usable frames.
    #[error(
        "none of its {windows} complete {segment_s} s windows has at least {min_frames} usable \
         frames (most: {most})"
    )]
    TooFewFrames {
        /// Complete windows in the trial.
        windows: usize,
        /// The segment length.
        segment_s: f64,
        /// The minimum frames per segment.
        min_frames: usize,
        /// The most usable frames any window had.
        most: usize,
    },
}

/// A trial the analysis left out.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SkippedTrial {
    /// Participant label.
    pub participant: String,
    /// Task label.
    pub task: String,
    /// Trial label.
    pub trial: String,
    /// Why.
    pub reason: SkipReason,
}

impl fmt::Display for SkippedTrial {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "participant '{}', task '{}', trial '{}' skipped: {}",
            self.participant, self.task, self.trial, self.reason
        )
    }
}
