//! Commanded against measured joint angles of a trial log (`pomdar tracking`): the station's
//! joint targets and the hand's measured state, both `sensor_msgs/JointState` as the station
//! recorded them (log time = when the station sent the command, or received the state, on its
//! one clock), mapped by name onto the model's degrees of freedom
//! ([`dof_of_published_name`]: the model's name, its URDF name, or the configured prefix
//! dropped), then compared by [`scoring::tracking_report`].
//!
//! A name the model lacks is left out and listed; a non-finite value is left out and counted.

use std::collections::BTreeSet;
use std::path::PathBuf;

use msgs::JointState;
use retarget::HandModel;
use scoring::{JointTrack, TrackingReport};
use serde::Serialize;
use station::ros_tools::dof_of_published_name;

use super::EvalError;
use crate::mcap_log::TrialReader;

/// Where the two series are and how their names read.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackingTopics {
    /// The station's joint targets (`[output] joint_targets_topic`).
    pub commanded: String,
    /// The hand's measured state (`[input] hand_state_topic`).
    pub measured: String,
    /// The prefix the station put before the model's names (`[output] joint_name_prefix`).
    pub joint_name_prefix: Option<String>,
}

/// One topic's messages, mapped onto the model.
#[derive(Debug, Clone, Default, PartialEq)]
struct TopicSeries {
    messages: usize,
    ignored_joints: BTreeSet<String>,
    non_finite: usize,
}

/// A log's joint series, per degree of freedom of the model.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackingInput {
    /// The log.
    pub path: PathBuf,
    /// The topics read.
    pub topics: TrackingTopics,
    /// Commands read.
    pub commands: usize,
    /// Measured states read.
    pub states: usize,
    /// Names on either topic that are no joint of the model (left out).
    pub ignored_joints: Vec<String>,
    /// Non-finite values (left out).
    pub non_finite_values: usize,
    /// Per degree of freedom, in the model's order.
    pub tracks: Vec<JointTrack>,
}

/// What `pomdar tracking --json` prints and `tracking.json` holds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrackingOutput {
    /// The log.
    pub input: String,
    /// The commands' topic.
    pub commanded_topic: String,
    /// The measured states' topic.
    pub measured_topic: String,
    /// Commands read.
    pub commands: usize,
    /// Measured states read.
    pub states: usize,
    /// Names on either topic that are no joint of the model (left out).
    pub ignored_joints: Vec<String>,
    /// Non-finite values (left out).
    pub non_finite_values: usize,
    /// The comparison, per joint.
    #[serde(flatten)]
    pub report: TrackingReport,
}

impl TrackingOutput {
    /// The output of `report` on `input`.
    pub fn new(input: &TrackingInput, report: TrackingReport) -> TrackingOutput {
        TrackingOutput {
            input: input.path.display().to_string(),
            commanded_topic: input.topics.commanded.clone(),
            measured_topic: input.topics.measured.clone(),
            commands: input.commands,
            states: input.states,
            ignored_joints: input.ignored_joints.clone(),
            non_finite_values: input.non_finite_values,
            report,
        }
    }
}

/// Reads `topic`'s JointStates into `tracks` (commanded or measured, by `pick`).
fn read_topic(
    reader: &TrialReader,
    model: &HandModel,
    topic: &str,
    prefix: Option<&str>,
    tracks: &mut [JointTrack],
    pick: fn(&mut JointTrack) -> &mut Vec<(i64, f64)>,
) -> Result<TopicSeries, EvalError> {
    let mut series = TopicSeries::default();
    for message in reader.messages_on(topic) {
        let state: JointState = message.decode().map_err(|source| EvalError::JointStates {
            path: reader.path().to_path_buf(),
            source: Box::new(source),
        })?;
        series.messages += 1;
        for (name, value) in state.name.iter().zip(&state.position) {
            let Some(dof) = dof_of_published_name(model, name, prefix) else {
                series.ignored_joints.insert(name.clone());
                continue;
            };
            if !value.is_finite() {
                series.non_finite += 1;
                continue;
            }
            pick(&mut tracks[dof]).push((message.log_time_ns, *value));
        }
    }
    Ok(series)
}

/// The commanded and measured series of the log in `reader`. A log without measured states
/// (none recorded, or none naming a joint of the model), or without commands, is an error
/// naming the file and the topic.
pub fn read_tracking(
    reader: &TrialReader,
    model: &HandModel,
    topics: &TrackingTopics,
) -> Result<TrackingInput, EvalError> {
    let mut tracks: Vec<JointTrack> = model
        .dof_names()
        .map(|name| JointTrack {
            joint: name.to_string(),
            ..JointTrack::default()
        })
        .collect();
    let prefix = topics.joint_name_prefix.as_deref();
    let measured = read_topic(reader, model, &topics.measured, prefix, &mut tracks, |t| {
        &mut t.measured
    })?;
    let path = reader.path().to_path_buf();
    if tracks.iter().all(|t| t.measured.is_empty()) {
        return Err(EvalError::NoMeasuredStates {
            path,
            topic: topics.measured.clone(),
            found: describe_found(reader, measured.messages, &measured.ignored_joints),
        });
    }
    let commanded = read_topic(reader, model, &topics.commanded, prefix, &mut tracks, |t| {
        &mut t.commanded
    })?;
    if tracks.iter().all(|t| t.commanded.is_empty()) {
        return Err(EvalError::NoCommands {
            path,
            topic: topics.commanded.clone(),
            found: describe_found(reader, commanded.messages, &commanded.ignored_joints),
        });
    }
    let ignored: BTreeSet<String> = measured
        .ignored_joints
        .union(&commanded.ignored_joints)
        .cloned()
        .collect();
    Ok(TrackingInput {
        path,
        topics: topics.clone(),
        commands: commanded.messages,
        states: measured.messages,
        ignored_joints: ignored.into_iter().collect(),
        non_finite_values: measured.non_finite + commanded.non_finite,
        tracks,
    })
}

/// What the log holds instead: the messages that named no joint of the model, or the
/// topics it has.
fn describe_found(reader: &TrialReader, messages: usize, ignored: &BTreeSet<String>) -> String {
    if messages > 0 {
        let names: Vec<&str> = ignored.iter().map(String::as_str).collect();
        return format!(
            "{messages} messages, naming no joint of the model ({})",
            names.join(", ")
        );
    }
    let topics: Vec<&str> = reader.topics().iter().map(|t| t.topic.as_str()).collect();
    format!("no messages; the log's topics: {}", topics.join(", "))
}

/// The report as a terminal table, one row per joint.
pub fn tracking_table(output: &TrackingOutput) -> String {
    let opt = |v: Option<f64>, decimals: usize| match v {
        Some(v) => format!("{v:.decimals$}"),
        None => "-".to_string(),
    };
    let s = &output.report.settings;
    let mut out = format!(
        "commanded ({}) vs measured ({}) in {}\n  {} commands, {} measured states; error = \
         |command in force − measured|; lag: best alignment over 0–{} ms\n\n",
        output.commanded_topic,
        output.measured_topic,
        output.input,
        output.commands,
        output.states,
        s.max_lag_ms
    );
    let over = format!("> {} deg", s.threshold_deg);
    out.push_str(&format!(
        "  {:<16} {:>8} {:>8} {:>9} {:>9} {:>8} {:>6} {:>10}\n",
        "joint", "commands", "measured", "RMS deg", "max deg", "lag ms", "corr", over
    ));
    for j in &output.report.joints {
        out.push_str(&format!(
            "  {:<16} {:>8} {:>8} {:>9} {:>9} {:>8} {:>6} {:>10}\n",
            j.joint,
            j.commanded_samples,
            j.measured_samples,
            opt(j.rms_error_deg, 2),
            opt(j.max_error_deg, 2),
            opt(j.lag_ms, 0),
            opt(j.lag_correlation, 3),
            opt(j.over_threshold_share.map(|v| 100.0 * v), 1) + " %",
        ));
    }
    if let Some(worst) = output.report.worst_joint() {
        out.push_str(&format!(
            "\n  worst: {} (RMS {} deg)\n",
            worst.joint,
            opt(worst.rms_error_deg, 2)
        ));
    }
    if !output.ignored_joints.is_empty() {
        out.push_str(&format!(
            "  left out (no joint of the model): {}\n",
            output.ignored_joints.join(", ")
        ));
    }
    if output.non_finite_values > 0 {
        out.push_str(&format!(
            "  left out: {} non-finite values\n",
            output.non_finite_values
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;
    use crate::mcap_log::{TrialWriter, TrialWriterOptions};
    use msgs::Header;

    fn state(names: &[String], position: Vec<f64>) -> JointState {
        JointState {
            header: Header::default(),
            name: names.to_vec(),
            position,
            velocity: vec![],
            effort: vec![],
        }
    }

    fn topics() -> TrackingTopics {
        TrackingTopics {
            commanded: "/pomdar/hand/joint_targets".into(),
            measured: "/pomdar/hand/joint_states".into(),
            joint_name_prefix: None,
        }
    }

    /// A log with commands and (if `with_states`) measured states lagging by one message.
    fn write_log(path: &std::path::Path, with_states: bool) {
        let model = HandModel::orca_v1_right();
        let names = model.ros_dof_names().to_vec();
        let mut writer = TrialWriter::create(path, TrialWriterOptions::default()).unwrap();
        for k in 0..50_i64 {
            let t = 1_000_000_000 + k * 10_000_000;
            let q = vec![0.01 * k as f64; names.len()];
            writer
                .write("/pomdar/hand/joint_targets", t, t, &state(&names, q))
                .unwrap();
            if with_states {
                let mut measured = names.clone();
                measured.push("arm_joint_1".into());
                let mut m = vec![0.01 * (k - 1).max(0) as f64; names.len()];
                m.push(0.0);
                m[0] = f64::NAN;
                let t = t + 5_000_000;
                writer
                    .write("/pomdar/hand/joint_states", t, t, &state(&measured, m))
                    .unwrap();
            }
        }
        writer.finish().unwrap();
    }

    #[test]
    fn a_log_is_read_per_joint_and_a_log_without_states_says_where_it_looked() {
        let dir = std::env::temp_dir().join(format!("pomdar-tracking-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok(); // left by an earlier process with this id
        std::fs::create_dir_all(&dir).unwrap();
        let model = HandModel::orca_v1_right();
        let with = dir.join("with.mcap");
        write_log(&with, true);
        let input = read_tracking(&TrialReader::open(&with).unwrap(), &model, &topics()).unwrap();
        assert_eq!(input.tracks.len(), model.dof());
        assert_eq!((input.commands, input.states), (50, 50));
        assert_eq!(input.ignored_joints, ["arm_joint_1"]);
        assert_eq!(input.non_finite_values, 50);
        assert!(input.tracks[0].measured.is_empty());
        assert_eq!(input.tracks[1].measured.len(), 50);
        assert_eq!(input.tracks[1].commanded.len(), 50);
        let report = scoring::tracking_report(&input.tracks, scoring::TrackingSettings::default());
        let output = TrackingOutput::new(&input, report);
        assert!((output.report.joints[1].max_error_deg.unwrap() - 0.573).abs() < 0.01);
        let table = tracking_table(&output);
        assert!(
            table.contains("index_mcp") || table.contains("thumb"),
            "{table}"
        );

        let without = dir.join("without.mcap");
        write_log(&without, false);
        let error = read_tracking(&TrialReader::open(&without).unwrap(), &model, &topics())
            .unwrap_err()
            .to_string();
        std::fs::remove_dir_all(&dir).ok();
        assert!(
            error.contains("without.mcap") && error.contains("/pomdar/hand/joint_states"),
            "{error}"
        );
        assert!(error.contains("/pomdar/hand/joint_targets"), "{error}");
    }
}
