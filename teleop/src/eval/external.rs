//! Another retargeter's commands, scored like the station's (`pomdar eval --commands TOPIC`):
//! a recording holding the glove's keypoints and the `sensor_msgs/JointState` commands some
//! other retargeter computed from them (dex-retargeting, a lab's own). At each distinct
//! keypoint frame the command in force is the last one logged at or before it (what a robot
//! would hold), mapped onto the model's degrees of freedom by joint name, a `right_` or
//! `left_` prefix dropped; joints the message lacks stay at zero.

use msgs::JointState;
use retarget::{HandModel, QualityRecorder, QualityReport};
use serde::Serialize;
use station::StationConfig;

use super::{EvalError, distinct_frames};
use crate::mcap_log::TrialReader;
use crate::resim::layout_for;

/// What `pomdar eval --commands` reports.
#[derive(Debug, Clone, Serialize)]
pub struct ExternalOutput {
    /// The recording.
    pub input: String,
    /// The topic of the commands scored.
    pub commands_topic: String,
    /// Commands read.
    pub commands: usize,
    /// Distinct keypoint frames.
    pub distinct_frames: usize,
    /// Distinct frames before the first command (not measured).
    pub frames_without_command: usize,
    /// Frames the metrics could not measure (a collapsed palm).
    pub frames_not_measured: usize,
    /// The keypoint layout used.
    pub layout: String,
    /// The metrics (definitions in `retarget::quality`).
    #[serde(flatten)]
    pub quality: QualityReport,
}

/// The model's command vector from a `JointState`; `Err` names a joint the model lacks.
fn command_of(model: &HandModel, state: &JointState) -> Result<Vec<f64>, EvalError> {
    let mut q = vec![0.0; model.dof()];
    for (name, value) in state.name.iter().zip(&state.position) {
        let bare = name
            .strip_prefix("right_")
            .or_else(|| name.strip_prefix("left_"))
            .unwrap_or(name);
        let index = model
            .dof_index(bare)
            .ok_or_else(|| EvalError::UnknownJoint {
                name: name.clone(),
                known: model.dof_names().collect::<Vec<_>>().join(", "),
            })?;
        q[index] = *value;
    }
    Ok(q)
}

/// Scores the commands on `topic` in `reader` against its keypoints.
pub fn evaluate_commands(
    reader: &TrialReader,
    config: &StationConfig,
    model: HandModel,
    topic: &str,
) -> Result<ExternalOutput, EvalError> {
    let (frames, _) = distinct_frames(reader, config)?;
    let mut commands: Vec<(i64, Vec<f64>)> = Vec::new();
    for message in reader.messages_on(topic) {
        let state: JointState = message.decode().map_err(|source| EvalError::Keypoints {
            log_time_ns: message.log_time_ns,
            source,
        })?;
        commands.push((message.log_time_ns, command_of(&model, &state)?));
    }
    if commands.is_empty() {
        return Err(EvalError::NoKeypoints {
            path: reader.path().to_path_buf(),
            topic: topic.to_string(),
        });
    }
    commands.sort_by_key(|(t, _)| *t);
    let layout = layout_for(config, frames.first().map(|f| f.points.len()));
    let mut recorder = QualityRecorder::new(model, layout);
    let (mut without, mut not_measured) = (0, 0);
    let origin_ns = frames.first().map_or(0, |f| f.t_ns);
    for frame in &frames {
        let in_force = commands.partition_point(|(t, _)| *t <= frame.t_ns);
        let Some((_, q)) = in_force.checked_sub(1).map(|i| &commands[i]) else {
            without += 1;
            continue;
        };
        let t_s = (frame.t_ns - origin_ns) as f64 * 1e-9;
        if recorder.push_at(t_s, &frame.points, q).is_err() {
            not_measured += 1;
        }
    }
    Ok(ExternalOutput {
        input: reader.path().display().to_string(),
        commands_topic: topic.to_string(),
        commands: commands.len(),
        distinct_frames: frames.len(),
        frames_without_command: without,
        frames_not_measured: not_measured,
        layout: layout.name().into(),
        quality: recorder.report(),
    })
}

/// The report as a terminal table.
pub fn external_table(o: &ExternalOutput) -> String {
    format!(
        "retargeting quality of the commands on {} in {}\n  {} frames measured ({} distinct, {} \
         before the first of {} commands, {} not measured), layout {}\n  global scale s* = {:.3} \
         (robot ≈ s*·human)\n\n{}",
        o.commands_topic,
        o.input,
        o.quality.frames,
        o.distinct_frames,
        o.frames_without_command,
        o.commands,
        o.frames_not_measured,
        o.layout,
        o.quality.tip_scale,
        super::quality_lines(&o.quality)
    )
}
