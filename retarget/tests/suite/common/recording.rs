//! The reference glove recording (`../shared/reference/rokoko_orca_2024-11-20.mcap`, the lab's
//! `/ingress/mano` 22-point keypoints), reduced to its distinct frames.

use std::path::Path;

use msgs::{Float32MultiArray, from_cdr};
use nalgebra::Point3;

/// File name of the reference recording.
pub const RECORDING: &str = "rokoko_orca_2024-11-20.mcap";

/// One distinct keypoint frame.
pub struct Frame {
    /// Receive time of the first message carrying it, seconds from the recording's start.
    pub t_s: f64,
    /// The 22 keypoints, metres.
    pub points: Vec<Point3<f64>>,
}

/// The recording's `/ingress/mano` frames whose keypoints changed (the ingress republishes
/// each glove frame at 200 Hz), and the number of messages read.
pub fn distinct_mano_frames(path: &Path) -> (Vec<Frame>, usize) {
    let bytes = std::fs::read(path).unwrap();
    let mut frames: Vec<Frame> = Vec::new();
    let mut messages = 0;
    let mut start_ns = None;
    let mut last: Option<Vec<[f32; 3]>> = None;
    for message in mcap::MessageStream::new(&bytes).unwrap() {
        let message = message.unwrap();
        if message.channel.topic != "/ingress/mano" {
            continue;
        }
        messages += 1;
        let array: Float32MultiArray = from_cdr(&message.data).unwrap();
        let rows = array.points().unwrap();
        if last.as_ref() == Some(&rows) {
            continue;
        }
        let start = *start_ns.get_or_insert(message.log_time);
        frames.push(Frame {
            t_s: (message.log_time - start) as f64 * 1e-9,
            points: rows
                .iter()
                .map(|p| Point3::new(p[0].into(), p[1].into(), p[2].into()))
                .collect(),
        });
        last = Some(rows);
    }
    (frames, messages)
}
