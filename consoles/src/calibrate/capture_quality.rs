//! How good one capture of one pose is: the console's meter, and the decision between
//! accepting the capture and retrying the pose.
//!
//! Three measures of the frames received inside the capture window:
//!
//! - **jitter**: every valid frame is expressed in its own palm frame (so a moving wrist does
//!   not count) and, for each keypoint but the forearm, the RMS distance from its mean over
//!   the window is taken; the jitter is the largest of these, in millimetres (the same
//!   quantity [`calibration::capture_pose`] checks). The palm frame is built from keypoints
//!   too, so their noise is amplified at the fingertips: a still hand in a glove with 2 mm
//!   of noise per axis measures 6–9.5 mm, one with 4 mm already over 12 mm;
//! - **invalid frames**: frames with the wrong keypoint count, a non-finite value or a palm
//!   that cannot be built;
//! - **frames received vs expected**: the glove's rate measured while the hand settled, times
//!   the capture's length.
//!
//! | level | when |
//! |---|---|
//! | **bad** | [`calibration::capture_pose`] refuses the capture (fewer than `min_frames` valid frames, more than `max_invalid_fraction` invalid, or jitter above `max_point_sd_m`; defaults 20, 20 %, 12 mm): the fit cannot use it, the pose must be captured again |
//! | **poor** | accepted by the fit, but jitter above 85 % of its limit (10.2 mm by default), any invalid frame, or fewer than 80 % of the expected frames |
//! | **good** | otherwise |

use calibration::{CaptureThresholds, capture_pose};
use nalgebra::{Point3, Vector3};
use retarget::{KeypointLayout, PalmFrame};
use serde_json::{Value, json};

/// Jitter above this fraction of the limit makes a capture poor.
pub const POOR_JITTER_FRACTION: f64 = 0.85;
/// Fewer frames than this fraction of the expected count makes a capture poor.
pub const POOR_FRAMES_FRACTION: f64 = 0.8;

/// A capture's verdict.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QualityLevel {
    /// Accepted without a question.
    Good,
    /// Usable, but worth a look: the operator may accept it or retry.
    Poor,
    /// Not usable: the pose is captured again.
    Bad,
}

impl QualityLevel {
    /// `good`, `poor`, `bad`: the word in the log and on screen.
    pub fn name(self) -> &'static str {
        match self {
            QualityLevel::Good => "good",
            QualityLevel::Poor => "poor",
            QualityLevel::Bad => "bad",
        }
    }
}

/// The measures of one capture and its verdict.
#[derive(Debug, Clone, PartialEq)]
pub struct CaptureQuality {
    /// The verdict.
    pub level: QualityLevel,
    /// Frames received in the window.
    pub frames: usize,
    /// Frames expected from the glove's rate before the capture (None: rate unknown).
    pub expected_frames: Option<usize>,
    /// Frames that were invalid.
    pub invalid: usize,
    /// The largest keypoint RMS deviation in the palm frame, mm (None: no valid frame).
    pub jitter_mm: Option<f64>,
    /// The keypoint with that deviation.
    pub worst_point: Option<String>,
    /// The limit on the jitter, mm.
    pub jitter_limit_mm: f64,
    /// Why the capture is not good (empty when it is).
    pub reasons: Vec<String>,
}

/// Measures a capture of `pose`: `frames` as received (metres, glove frame),
/// `expected_frames` from the glove's rate.
pub fn measure(
    pose: &str,
    layout: KeypointLayout,
    frames: &[Vec<Point3<f64>>],
    thresholds: &CaptureThresholds,
    expected_frames: Option<usize>,
) -> CaptureQuality {
    let mut palm_frames: Vec<Vec<Vector3<f64>>> = Vec::new();
    for frame in frames {
        if let Some(points) = in_palm(layout, frame) {
            palm_frames.push(points);
        }
    }
    let invalid = frames.len() - palm_frames.len();
    let jitter = worst_deviation(layout, &palm_frames);
    let jitter_limit_mm = thresholds.max_point_sd_m * 1e3;
    let mut reasons = Vec::new();
    let level = match capture_pose(pose, layout, frames.iter().map(Vec::as_slice), thresholds) {
        Err(calibration::Error::Capture { problem, .. }) => {
            reasons.push(problem);
            QualityLevel::Bad
        }
        Err(other) => {
            reasons.push(other.to_string());
            QualityLevel::Bad
        }
        Ok(_) => {
            if let Some((_, sd_m)) = jitter
                && sd_m * 1e3 > POOR_JITTER_FRACTION * jitter_limit_mm
            {
                reasons.push(format!(
                    "jitter {:.1} mm is over {:.0} % of the limit ({jitter_limit_mm:.1} mm)",
                    sd_m * 1e3,
                    100.0 * POOR_JITTER_FRACTION
                ));
            }
            if invalid > 0 {
                reasons.push(format!("{invalid} invalid frames"));
            }
            if let Some(expected) = expected_frames
                && (frames.len() as f64) < POOR_FRAMES_FRACTION * expected as f64
            {
                reasons.push(format!(
                    "{} frames of the {expected} expected from the glove's rate",
                    frames.len()
                ));
            }
            if reasons.is_empty() {
                QualityLevel::Good
            } else {
                QualityLevel::Poor
            }
        }
    };
    CaptureQuality {
        level,
        frames: frames.len(),
        expected_frames,
        invalid,
        jitter_mm: jitter.map(|(_, sd)| sd * 1e3),
        worst_point: jitter.and_then(|(i, _)| layout.point_name(i).map(|n| n.to_string())),
        jitter_limit_mm,
        reasons,
    }
}

fn in_palm(layout: KeypointLayout, frame: &[Point3<f64>]) -> Option<Vec<Vector3<f64>>> {
    retarget::validate_keypoints(layout, frame).ok()?;
    let palm = PalmFrame::from_landmarks(&layout.palm_landmarks(frame)).ok()?;
    Some(frame.iter().map(|p| palm.point_to_palm(p)).collect())
}

/// The keypoint (not the forearm) with the largest RMS deviation from its mean, and that
/// deviation in metres.
fn worst_deviation(layout: KeypointLayout, frames: &[Vec<Vector3<f64>>]) -> Option<(usize, f64)> {
    if frames.is_empty() {
        return None;
    }
    let n = frames.len() as f64;
    (0..layout.len())
        .filter(|&i| Some(i) != layout.forearm())
        .map(|i| {
            let mean = frames.iter().map(|f| f[i]).sum::<Vector3<f64>>() / n;
            let var = frames
                .iter()
                .map(|f| (f[i] - mean).norm_squared())
                .sum::<f64>()
                / n;
            (i, var.sqrt())
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

impl CaptureQuality {
    /// The meter's fill in [0, 1]: how much of the jitter limit is left (0 for a bad capture).
    pub fn meter_fill(&self) -> f64 {
        if self.level == QualityLevel::Bad {
            return 0.0;
        }
        let used = self.jitter_mm.unwrap_or(self.jitter_limit_mm) / self.jitter_limit_mm;
        (1.0 - used).clamp(0.0, 1.0)
    }

    /// `[########..] good · jitter 3.1 mm (limit 12.0) · 100/100 frames · 0 invalid`.
    pub fn meter(&self) -> String {
        const WIDTH: usize = 10;
        let filled = (self.meter_fill() * WIDTH as f64).round() as usize;
        format!(
            "[{}{}] {} · {}",
            "#".repeat(filled),
            ".".repeat(WIDTH - filled),
            self.level.name().to_uppercase(),
            self.summary()
        )
    }

    /// The measures in a line.
    pub fn summary(&self) -> String {
        let jitter = match (self.jitter_mm, &self.worst_point) {
            (Some(j), Some(p)) => format!(
                "jitter {j:.1} mm at {p} (limit {:.1})",
                self.jitter_limit_mm
            ),
            (Some(j), None) => format!("jitter {j:.1} mm (limit {:.1})", self.jitter_limit_mm),
            _ => "jitter -".to_string(),
        };
        let frames = match self.expected_frames {
            Some(e) => format!("{}/{e} frames", self.frames),
            None => format!("{} frames", self.frames),
        };
        format!("{jitter} · {frames} · {} invalid", self.invalid)
    }

    /// The measures for the session log.
    pub fn to_json(&self) -> Value {
        json!({
            "quality": self.level.name(),
            "frames": self.frames,
            "expected_frames": self.expected_frames,
            "invalid_frames": self.invalid,
            "jitter_mm": self.jitter_mm,
            "worst_point": self.worst_point,
            "jitter_limit_mm": self.jitter_limit_mm,
            "reasons": self.reasons,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use calibration::{CaptureSchedule, PoseSet, SyntheticUser, human_copies};
    use retarget::HandModel;
    use retarget::human_hand::HandVariation;

    fn user_frames(noise_sd_m: f64, k: usize) -> Vec<Vec<Point3<f64>>> {
        let model = HandModel::orca_v1_right();
        let copies = human_copies(&model, &PoseSet::orca_v1()).unwrap_or_else(|e| panic!("{e}"));
        let user = SyntheticUser {
            hand_scale: 1.1,
            glove_rpy_rad: [0.1, -0.05, 0.08],
            noise_sd_m,
            seed: 3,
            variation: HandVariation::NONE,
        };
        user.capture_frames(
            KeypointLayout::Lab22,
            &CaptureSchedule::default(),
            &copies,
            k,
            100.0,
        )
        .unwrap_or_else(|e| panic!("{e}"))
    }

    fn quality(frames: &[Vec<Point3<f64>>], expected: Option<usize>) -> CaptureQuality {
        measure(
            "pinch_ring",
            KeypointLayout::Lab22,
            frames,
            &CaptureThresholds::default(),
            expected,
        )
    }

    #[test]
    fn a_steady_hand_is_good_and_a_shaking_one_bad() {
        let steady = quality(&user_frames(0.002, 2), Some(100));
        assert_eq!(steady.level, QualityLevel::Good, "{steady:?}");
        assert_eq!((steady.frames, steady.invalid), (100, 0));
        let jitter = steady.jitter_mm.unwrap_or(f64::NAN);
        assert!(jitter > 1.0 && jitter < 10.2, "{jitter}");
        assert!(steady.meter().contains("GOOD"), "{}", steady.meter());

        let shaking = quality(&user_frames(0.008, 2), Some(100));
        assert_eq!(shaking.level, QualityLevel::Bad, "{shaking:?}");
        assert!(shaking.jitter_mm.unwrap_or(0.0) > 12.0);
        assert!(
            shaking.reasons[0].contains("moved"),
            "{:?}",
            shaking.reasons
        );
        assert_eq!(shaking.meter_fill(), 0.0);
        assert_eq!(shaking.to_json()["quality"], "bad");
    }

    #[test]
    fn dropped_or_invalid_frames_make_a_capture_poor_then_bad() {
        let frames = user_frames(0.002, 4);
        // Half the expected frames: usable, but poor.
        let few = quality(&frames[..50], Some(100));
        assert_eq!(few.level, QualityLevel::Poor, "{few:?}");
        assert!(
            few.reasons
                .iter()
                .any(|r| r.contains("50 frames of the 100"))
        );
        // A few non-finite frames: poor; too many: bad.
        let mut some_bad = frames.clone();
        for f in some_bad.iter_mut().take(5) {
            f[3].x = f64::NAN;
        }
        let q = quality(&some_bad, Some(100));
        assert_eq!((q.level, q.invalid), (QualityLevel::Poor, 5), "{q:?}");
        for f in some_bad.iter_mut().take(40) {
            f[3].x = f64::NAN;
        }
        assert_eq!(quality(&some_bad, Some(100)).level, QualityLevel::Bad);
        // Too few frames for the fit, and none at all.
        assert_eq!(quality(&frames[..10], Some(100)).level, QualityLevel::Bad);
        let none = quality(&[], None);
        assert_eq!((none.level, none.jitter_mm), (QualityLevel::Bad, None));
    }
}
