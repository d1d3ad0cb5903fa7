//! `pomdar eval-set`: an evaluation set from real recordings. Each source's distinct keypoint
//! frames go through the [`standard_variants`] (other hand sizes with a turned glove, a noisy
//! glove dropping frames, other rates, the 21-point layout), each written as a recording of
//! its own (`/ingress/mano`-style `Float32MultiArray`, one message per frame at its capture
//! time) that `pomdar eval` reads like any other. The sources themselves are not copied:
//! evaluate them beside the set.

use std::path::{Path, PathBuf};

use msgs::Float32MultiArray;
use serde::Serialize;
use station::StationConfig;

use super::synthetic_users::{self, synthetic_user};
use super::variants::{TimedFrame, Variant, standard_variants};
use super::{EvalError, distinct_frames};
use crate::mcap_log::{LogError, TrialReader, TrialWriter, TrialWriterOptions};
use crate::resim::layout_for;

/// One recording of the set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SetRecording {
    /// The file written.
    pub path: PathBuf,
    /// The real recording it comes from.
    pub source: PathBuf,
    /// The variants applied, in order.
    pub variants: Vec<String>,
    /// Its layout.
    pub layout: String,
    /// Its frames.
    pub frames: usize,
}

/// Why the set cannot be built.
#[derive(Debug, thiserror::Error)]
pub enum SetError {
    /// A source cannot be read.
    #[error("{path}: {source}")]
    Source {
        /// The source recording.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: Box<EvalError>,
    },
    /// A source cannot be opened as an MCAP recording.
    #[error("{path}: {source}")]
    Open {
        /// The source recording.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: Box<LogError>,
    },
    /// A frame cannot be put in a message (more points than a ROS array holds).
    #[error("{path}: {source}")]
    Message {
        /// The file being written.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: msgs::Error,
    },
    /// A synthetic user cannot be simulated.
    #[error("synthetic user {user}: {source}")]
    Synthetic {
        /// The user's number.
        user: u64,
        /// What went wrong.
        #[source]
        source: retarget::Error,
    },
    /// A recording of the set cannot be written.
    #[error("{path}: {source}")]
    Write {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: Box<LogError>,
    },
}

/// Writes `frames` as a recording at `path`: one `Float32MultiArray` per frame on `topic`,
/// logged and published at the frame's time.
pub fn write_recording(path: &Path, topic: &str, frames: &[TimedFrame]) -> Result<(), SetError> {
    let write = |source: LogError| SetError::Write {
        path: path.to_path_buf(),
        source: Box::new(source),
    };
    let mut writer = TrialWriter::create(path, TrialWriterOptions::default()).map_err(write)?;
    for frame in frames {
        let rows: Vec<[f32; 3]> = frame
            .points
            .iter()
            .map(|p| [p.x as f32, p.y as f32, p.z as f32])
            .collect();
        let message =
            Float32MultiArray::from_points(&rows).map_err(|source| SetError::Message {
                path: path.to_path_buf(),
                source,
            })?;
        writer
            .write(topic, frame.t_ns, frame.t_ns, &message)
            .map_err(write)?;
    }
    writer.finish().map_err(write)?;
    Ok(())
}

/// Builds the set from `sources` into `out` (created if needed), with `synthetic` simulated
/// users besides; `seed` makes the noise and the users.
pub fn build_set(
    sources: &[PathBuf],
    config: &StationConfig,
    out: &Path,
    seed: u64,
    synthetic: u64,
) -> Result<Vec<SetRecording>, SetError> {
    let mut written = Vec::new();
    for (n, source) in sources.iter().enumerate() {
        let read = |e: EvalError| SetError::Source {
            path: source.clone(),
            source: Box::new(e),
        };
        let reader = TrialReader::open(source).map_err(|e| SetError::Open {
            path: source.clone(),
            source: Box::new(e),
        })?;
        let (frames, _) = distinct_frames(&reader, config).map_err(read)?;
        let layout = layout_for(config, frames.first().map(|f| f.points.len()));
        let stem = source
            .file_stem()
            .map_or_else(|| format!("source{n}"), |s| s.to_string_lossy().into());
        for chain in standard_variants(layout, seed.wrapping_add(n as u64)) {
            let (mut set_frames, mut set_layout) = (frames.clone(), layout);
            for variant in &chain {
                set_frames = variant.apply(&set_frames, set_layout);
                set_layout = variant.layout_after(set_layout);
            }
            let labels: Vec<String> = chain.iter().map(Variant::label).collect();
            let path = out.join(format!("{stem}-{}.mcap", labels.join("-")));
            write_recording(&path, &config.input.keypoints_topic, &set_frames)?;
            written.push(SetRecording {
                path,
                source: source.clone(),
                variants: labels,
                layout: set_layout.name().into(),
                frames: set_frames.len(),
            });
        }
    }
    for k in 1..=synthetic {
        written.push(write_synthetic_user(config, out, seed, k)?);
    }
    Ok(written)
}

/// Simulates synthetic user `k` and writes their recording into `out`.
fn write_synthetic_user(
    config: &StationConfig,
    out: &Path,
    seed: u64,
    k: u64,
) -> Result<SetRecording, SetError> {
    let user = synthetic_user(seed, k).map_err(|source| SetError::Synthetic { user: k, source })?;
    let path = out.join(format!("{}.mcap", user.name));
    write_recording(&path, &config.input.keypoints_topic, &user.frames)?;
    Ok(SetRecording {
        path,
        source: PathBuf::from("synthetic"),
        variants: vec![format!(
            "hand {:.2}x {}, glove turned {:+.1} deg, {:.0} mm jitter, {:.0} Hz",
            user.scale,
            user.variation.label(),
            user.turn_deg,
            synthetic_users::JITTER_M * 1e3,
            synthetic_users::RATE_HZ
        )],
        layout: synthetic_users::LAYOUT.name().into(),
        frames: user.frames.len(),
    })
}
