//! [`continue_finished`]: a finished log opened again to add to it (a calibration pose captured
//! once more after the fit).
//!
//! MCAP has no append: the log's channels, metadata and messages are copied, in log-time
//! order, into a new `NAME.part`, which goes on being written like any log. Its
//! [`TrialWriter::finish`] replaces the finished file in one rename, so until then the old
//! log stays complete beside the `.part`, and a crash keeps both.

use std::path::Path;

use super::{LogError, TrialReader, TrialWriter, TrialWriterOptions};

/// The finished log at `path`, copied into a writer that will replace it (`options` with
/// `overwrite` set). On an error nothing is left beside the finished log.
pub fn continue_finished(
    path: &Path,
    options: TrialWriterOptions,
) -> Result<TrialWriter, LogError> {
    let reader = TrialReader::open(path)?;
    let options = TrialWriterOptions {
        overwrite: true,
        ..options
    };
    let mut writer = TrialWriter::create(path, options)?;
    let part = writer.part_path().to_path_buf();
    match copy_into(&reader, &mut writer) {
        Ok(()) => Ok(writer),
        Err(e) => {
            drop(writer);
            std::fs::remove_file(&part).ok();
            Err(e)
        }
    }
}

/// Every channel (with its offered QoS), metadata record and message of `reader`, then a
/// flush.
fn copy_into(reader: &TrialReader, writer: &mut TrialWriter) -> Result<(), LogError> {
    for topic in reader.topics() {
        let qos = topic.offered_qos().transpose()?.unwrap_or_default();
        writer.add_channel_raw(&topic.topic, &topic.type_name, &topic.schema_text, &qos)?;
    }
    for (name, entries) in reader.metadata() {
        writer.write_metadata_unflushed(name, entries.clone())?;
    }
    for message in reader.messages() {
        let schema = reader
            .topic(&message.topic)
            .map(|t| t.schema_text.as_str())
            .unwrap_or_default();
        writer.write_raw(
            &message.topic,
            &message.type_name,
            schema,
            message.log_time_ns,
            message.publish_time_ns,
            &message.data,
        )?;
    }
    writer.flush()
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use msgs::JointState;

    use super::*;
    use crate::mcap_log::{OfferedQos, TRIAL_EVENTS_TOPIC};

    #[test]
    fn a_continued_log_keeps_everything_and_adds_the_new_messages() {
        let dir = std::env::temp_dir().join(format!("mcap-continue-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("session.mcap");
        std::fs::remove_file(&path).ok();
        let joints = |p: f64| JointState {
            position: vec![p],
            ..JointState::default()
        };
        let mut first = TrialWriter::create(&path, TrialWriterOptions::default()).unwrap();
        first
            .write_metadata("session", BTreeMap::from([("user".into(), "a".into())]))
            .unwrap();
        first
            .add_channel::<JointState>("/hand", &[OfferedQos::reliable(7)])
            .unwrap();
        first.write("/hand", 10, 9, &joints(1.0)).unwrap();
        first
            .write_event(20, &serde_json::json!({"event": "stop"}))
            .unwrap();
        first.finish().unwrap();

        let mut more = continue_finished(&path, TrialWriterOptions::default()).unwrap();
        // Until it is finished the old log is there, complete.
        assert_eq!(TrialReader::open(&path).unwrap().message_count(), 2);
        more.write("/hand", 30, 29, &joints(2.0)).unwrap();
        more.write_event(40, &serde_json::json!({"event": "redo"}))
            .unwrap();
        more.finish().unwrap();
        assert!(!crate::mcap_log::part_path_for(&path).exists());

        let log = TrialReader::open(&path).unwrap();
        let positions: Vec<f64> = log
            .decode_topic::<JointState>("/hand")
            .unwrap()
            .iter()
            .map(|j| j.position[0])
            .collect();
        assert_eq!(positions, [1.0, 2.0]);
        let times: Vec<(i64, i64)> = log
            .messages()
            .map(|m| (m.log_time_ns, m.publish_time_ns))
            .collect();
        assert_eq!(times, [(10, 9), (20, 20), (30, 29), (40, 40)]);
        assert_eq!(log.messages_on(TRIAL_EVENTS_TOPIC).count(), 2);
        assert_eq!(log.metadata_named("session").unwrap()["user"], "a");
        let qos = log.topic("/hand").unwrap().offered_qos().unwrap().unwrap();
        assert_eq!(qos, [OfferedQos::reliable(7)]);
        std::fs::remove_dir_all(&dir).ok();
    }
}
