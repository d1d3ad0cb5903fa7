//! Capturing one pose: about a second of glove frames reduced to one averaged frame, or a
//! refusal that says what to do.
//!
//! Every frame is checked (keypoint count, finite values, a palm frame that can be built) and
//! expressed in its own palm frame, so wrist motion during the capture does not count as
//! instability and the average is taken where the retargeter looks. The capture is refused
//! when too few frames are valid, too many are invalid, or any keypoint's RMS deviation from
//! its mean exceeds the threshold (the hand moved). The forearm point, which the retargeter
//! does not use and which sits far enough from the palm to amplify every wobble of the palm
//! frame, is averaged but not checked.

use nalgebra::{Point3, Vector3};
use retarget::{KeypointLayout, PalmFrame};

use crate::error::Error;
use crate::settings::CaptureThresholds;

/// One pose's accepted capture.
#[derive(Debug, Clone, PartialEq)]
pub struct CapturedPose {
    /// The pose's name.
    pub pose: String,
    /// The averaged keypoints, in the capture's palm frame (layout order, metres): a valid
    /// frame for the retargeter.
    pub keypoints: Vec<Point3<f64>>,
    /// Frames averaged.
    pub frames_used: usize,
    /// Frames refused (wrong count, non-finite, collapsed palm).
    pub frames_invalid: usize,
    /// The largest RMS deviation of a keypoint from its mean, metres.
    pub max_point_sd_m: f64,
}

/// Reduce the frames of one pose's capture to an averaged frame, or refuse the capture with
/// an [`Error::Capture`] saying what was wrong and what to do.
pub fn capture_pose<'a>(
    pose: &str,
    layout: KeypointLayout,
    frames: impl IntoIterator<Item = &'a [Point3<f64>]>,
    thresholds: &CaptureThresholds,
) -> Result<CapturedPose, Error> {
    let refuse = |problem: String, advice: &str| Error::Capture {
        pose: pose.to_string(),
        problem,
        advice: advice.to_string(),
    };
    let mut palm_frames: Vec<Vec<Vector3<f64>>> = Vec::new();
    let mut invalid = 0usize;
    let mut first_problem: Option<String> = None;
    for frame in frames {
        match to_palm(layout, frame) {
            Ok(points) => palm_frames.push(points),
            Err(e) => {
                invalid += 1;
                first_problem.get_or_insert_with(|| e.to_string());
            }
        }
    }
    let total = palm_frames.len() + invalid;
    if total > 0 && invalid as f64 > thresholds.max_invalid_fraction * total as f64 {
        return Err(refuse(
            format!(
                "{invalid} of {total} frames were invalid (first: {})",
                first_problem.unwrap_or_default()
            ),
            "Check that the glove is tracking every finger, then retry the pose.",
        ));
    }
    if palm_frames.len() < thresholds.min_frames {
        return Err(refuse(
            format!(
                "only {} valid frames (needs at least {})",
                palm_frames.len(),
                thresholds.min_frames
            ),
            "Check that the glove is streaming and hold the pose for the whole capture.",
        ));
    }
    let n = palm_frames.len() as f64;
    let mean: Vec<Vector3<f64>> = (0..layout.len())
        .map(|i| palm_frames.iter().map(|f| f[i]).sum::<Vector3<f64>>() / n)
        .collect();
    let (worst, worst_sd) = (0..layout.len())
        .filter(|&i| Some(i) != layout.forearm())
        .map(|i| {
            let var = palm_frames
                .iter()
                .map(|f| (f[i] - mean[i]).norm_squared())
                .sum::<f64>()
                / n;
            (i, var.sqrt())
        })
        .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    if worst_sd > thresholds.max_point_sd_m {
        return Err(refuse(
            format!(
                "keypoint '{}' moved {:.1} mm RMS during the capture (limit {:.1} mm)",
                layout.point_name(worst).unwrap_or_default(),
                worst_sd * 1e3,
                thresholds.max_point_sd_m * 1e3
            ),
            "Hold the pose still for the whole second, then retry.",
        ));
    }
    Ok(CapturedPose {
        pose: pose.to_string(),
        keypoints: mean.into_iter().map(Point3::from).collect(),
        frames_used: palm_frames.len(),
        frames_invalid: invalid,
        max_point_sd_m: worst_sd,
    })
}

/// One frame's keypoints in its own palm frame, or why the frame is invalid.
fn to_palm(layout: KeypointLayout, frame: &[Point3<f64>]) -> Result<Vec<Vector3<f64>>, Error> {
    retarget::validate_keypoints(layout, frame)?;
    let palm = PalmFrame::from_landmarks(&layout.palm_landmarks(frame))?;
    Ok(frame.iter().map(|p| palm.point_to_palm(p)).collect())
}
