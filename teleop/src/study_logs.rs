//! # The human study's logs (`pomdar study-report`)
//!
//! A human trial log (embodiment `human`, from `pomdar study` or `pomdar trial --embodiment
//! human`) → the hand motion the pure `study` crate analyses: the glove's keypoint frames
//! between the trial's start and its stop, timed by their source stamps (the glove's capture
//! spacing, not the network's delivery), in the layout the metadata names.
//!
//! Practice trials, aborted trials and trials of another embodiment are left out with a
//! reason. Within a used trial, frames of the wrong size, with a non-finite point, or not
//! after the previous frame are dropped and counted, so one bad frame does not cost the whole
//! trial.

use std::path::{Path, PathBuf};

use nalgebra::Point3;
use retarget::KeypointLayout;
use scoring::{Ending, HUMAN_EMBODIMENT, TaskCatalog, TrialRecord};
use study::{MotionFrame, TrialMotion};

use crate::mcap_log::{LogError, TrialReader};
use crate::score::TrialFileError;
use crate::score::load_trial::load_trial_log;

/// Why a human trial log cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum StudyLogError {
    /// The trial's metadata and events (see `pomdar score`).
    #[error("{0}")]
    Trial(#[from] TrialFileError),
    /// The MCAP file.
    #[error("{0}")]
    Log(#[from] LogError),
    /// The metadata's layout is not one the station knows.
    #[error("metadata layout {found:?} is not a keypoint layout ({known})")]
    Layout {
        /// The layout named.
        found: String,
        /// The layouts known.
        known: String,
    },
    /// No channel carries keypoints.
    #[error(
        "no keypoint channel (std_msgs/msg/Float32MultiArray or geometry_msgs/msg/PoseArray) in {file}"
    )]
    NoKeypoints {
        /// The trial file.
        file: PathBuf,
    },
}

/// A trial log read for the study.
#[derive(Debug, Clone, PartialEq)]
pub enum StudyTrial {
    /// A recorded human trial's motion, with the frames dropped from it.
    Used {
        /// The motion.
        motion: TrialMotion,
        /// Frames dropped (wrong size, non-finite, not after the previous frame).
        dropped_frames: usize,
    },
    /// Not part of the analysis, with the reason.
    LeftOut(String),
}

/// Reads the trial at `path` for the strategy analysis; `catalog` checks its task.
pub fn read_study_trial(path: &Path, catalog: &TaskCatalog) -> Result<StudyTrial, StudyLogError> {
    let log = load_trial_log(path)?;
    let record = TrialRecord::from_log(&log, catalog).map_err(TrialFileError::from)?;
    if record.embodiment != HUMAN_EMBODIMENT {
        return Ok(StudyTrial::LeftOut(format!(
            "embodiment {:?}, not {HUMAN_EMBODIMENT:?}",
            record.embodiment
        )));
    }
    if record.practice {
        return Ok(StudyTrial::LeftOut("practice trial".into()));
    }
    if record.ending == Ending::Aborted {
        return Ok(StudyTrial::LeftOut("aborted".into()));
    }
    let layout = layout_of(log.metadata.get("layout").map(String::as_str))?;
    let reader = TrialReader::open(path)?;
    let (frames, dropped_frames) = keypoint_frames(&reader, &record, layout)?;
    Ok(StudyTrial::Used {
        motion: TrialMotion {
            participant: record
                .user
                .clone()
                .unwrap_or_else(|| scoring::UNNAMED_PARTICIPANT.into()),
            task: record.task.clone(),
            trial: file_label(path),
            layout,
            frames,
        },
        dropped_frames,
    })
}

/// The layout a metadata value names (the lab's 22 points when the log names none).
fn layout_of(name: Option<&str>) -> Result<KeypointLayout, StudyLogError> {
    let Some(name) = name else {
        return Ok(KeypointLayout::Lab22);
    };
    KeypointLayout::ALL
        .into_iter()
        .find(|l| l.name() == name)
        .ok_or_else(|| StudyLogError::Layout {
            found: name.to_string(),
            known: KeypointLayout::ALL.map(KeypointLayout::name).join(", "),
        })
}

/// The trial's name in the report: its file name.
fn file_label(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into(),
    )
}

/// The keypoint channel: of the channels with a keypoint type, the first whose messages carry
/// the layout's number of points (the glove's, not another array such as a policy output).
fn keypoint_topic(reader: &TrialReader, layout: KeypointLayout) -> Option<String> {
    reader
        .topics()
        .iter()
        .filter(|t| {
            t.type_name == "std_msgs/msg/Float32MultiArray"
                || t.type_name == "geometry_msgs/msg/PoseArray"
        })
        .find(|t| {
            reader.messages_on(&t.topic).take(20).any(|m| {
                m.keypoints()
                    .is_some_and(|k| k.points().len() == layout.len())
            })
        })
        .map(|t| t.topic.clone())
}

/// The keypoint frames received between the trial's start and end, seconds after the first,
/// and how many were dropped.
fn keypoint_frames(
    reader: &TrialReader,
    record: &TrialRecord,
    layout: KeypointLayout,
) -> Result<(Vec<MotionFrame>, usize), StudyLogError> {
    let topic = keypoint_topic(reader, layout).ok_or_else(|| StudyLogError::NoKeypoints {
        file: reader.path().to_path_buf(),
    })?;
    let mut stamped: Vec<(i64, Option<Vec<Point3<f64>>>)> = reader
        .messages_on(&topic)
        .filter(|m| (record.start_ns..=record.end_ns).contains(&m.log_time_ns))
        .map(|m| (m.publish_time_ns, m.keypoints().map(|k| k.points())))
        .collect();
    stamped.sort_by_key(|(t, _)| *t);
    let first = stamped.first().map_or(0, |(t, _)| *t);
    let mut frames: Vec<MotionFrame> = Vec::with_capacity(stamped.len());
    let mut dropped = 0;
    for (t_ns, points) in stamped {
        let t_s = (t_ns - first) as f64 * 1e-9;
        let usable = points.filter(|p| {
            p.len() == layout.len() && p.iter().all(|q| q.coords.iter().all(|c| c.is_finite()))
        });
        match usable {
            Some(points) if frames.last().is_none_or(|f| t_s > f.t_s) => {
                frames.push(MotionFrame { t_s, points });
            }
            _ => dropped += 1,
        }
    }
    Ok((frames, dropped))
}
