//! Reading a recorded calibration session: its metadata (layout, keypoint topic, model) and,
//! for each of the seven poses, the keypoint frames received inside the pose's capture window.
//! A message that does not decode is kept as an empty frame, so the capture check counts it
//! as invalid rather than silently dropping it.

use calibration::POSE_NAMES;
use nalgebra::Point3;
use retarget::KeypointLayout;

use crate::calibrate::CalibrateError;
use crate::calibrate::session_events::{SESSION_METADATA, capture_windows};
use crate::mcap_log::{LoggedMessage, TrialReader};

/// What a session log says about itself.
#[derive(Debug, Clone, PartialEq)]
pub struct SessionInfo {
    /// Keypoint layout of the glove stream.
    pub layout: KeypointLayout,
    /// Topic the keypoints were recorded on.
    pub keypoints_topic: String,
    /// The robot hand model the poses were shown on.
    pub model: String,
}

/// The frames of one pose's capture window.
#[derive(Debug, Clone, PartialEq)]
pub struct PoseFrames {
    /// The pose.
    pub pose: String,
    /// Keypoints per frame (metres), in log-time order; empty for a message that did not
    /// decode.
    pub frames: Vec<Vec<Point3<f64>>>,
}

fn points(message: &LoggedMessage) -> Vec<Point3<f64>> {
    message.keypoints().map(|m| m.points()).unwrap_or_default()
}

/// The session's description and the frames of each pose, in capture order. Errors name the
/// file, and the pose when a capture window is missing.
pub fn read_session(
    reader: &TrialReader,
) -> Result<(SessionInfo, Vec<PoseFrames>), CalibrateError> {
    let file = reader.path();
    let meta =
        reader
            .metadata_named(SESSION_METADATA)
            .ok_or_else(|| CalibrateError::NotASession {
                file: file.to_path_buf(),
                record: SESSION_METADATA,
            })?;
    let get = |key: &str| {
        meta.get(key)
            .cloned()
            .ok_or_else(|| CalibrateError::MissingMetadata {
                file: file.to_path_buf(),
                record: SESSION_METADATA,
                key: key.to_string(),
            })
    };
    let layout_name = get("layout")?;
    let layout: KeypointLayout = serde_json::from_value(serde_json::Value::String(
        layout_name.clone(),
    ))
    .map_err(|source| CalibrateError::UnknownLayout {
        file: file.to_path_buf(),
        layout: layout_name,
        source,
    })?;
    let info = SessionInfo {
        layout,
        keypoints_topic: get("keypoints_topic")?,
        model: get("model")?,
    };
    let windows = capture_windows(reader)?;
    let mut out = Vec::with_capacity(POSE_NAMES.len());
    for pose in POSE_NAMES {
        let Some(&(start, end)) = windows.get(pose) else {
            return Err(CalibrateError::NoCaptureWindow {
                file: file.to_path_buf(),
                pose,
            });
        };
        let frames = reader
            .messages_on(&info.keypoints_topic)
            .filter(|m| m.log_time_ns >= start && m.log_time_ns < end)
            .map(points)
            .collect();
        out.push(PoseFrames {
            pose: pose.to_string(),
            frames,
        });
    }
    Ok((info, out))
}
