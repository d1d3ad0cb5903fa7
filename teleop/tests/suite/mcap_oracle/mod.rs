//! What must hold for any bytes handed to the trial-log readers, valid MCAP or not: no panic,
//! failures are `Err`, and what succeeds is consistent.
//!
//! - [`TrialReader::from_bytes`]: messages in log-time order, per-topic counts adding up to
//!   the total (and to the summary's statistics when there are some), every message decodes
//!   as its recorded type or gives an error.
//! - [`recover`]: its output is a complete log that [`TrialReader`] reads, holding exactly the
//!   messages the report counts plus the recovery metadata record.
//! - [`read_trial_events`] (scoring's reader, through the summary's indexes): decompresses no
//!   more chunks than the file has; on a file that also reads whole, finds the same metadata.
//!
//! Shared by the stable proptest fuzzing (`tests/fuzz_mcap_reader.rs`) and the cargo-fuzz
//! targets (`fuzz/fuzz_targets/mcap_*.rs`).

use std::path::Path;

use msgs::{Float32MultiArray, JointState, PoseArray, PoseStamped, StringMsg};
use teleop::mcap_log::{
    LoggedMessage, RECOVERY_METADATA_NAME, TrialReader, read_trial_events, recover,
};

/// Read `bytes` as a complete log; check what comes back. Returns the log when it reads.
pub fn check_trial_reader(bytes: &[u8]) -> Option<TrialReader> {
    let log = match TrialReader::from_bytes(bytes, Path::new("fuzz.mcap")) {
        Ok(log) => log,
        Err(error) => {
            assert!(error.to_string().contains("fuzz.mcap"), "{error}");
            return None;
        }
    };
    let messages: Vec<&LoggedMessage> = log.messages().collect();
    assert_eq!(messages.len(), log.message_count());
    assert!(
        messages
            .windows(2)
            .all(|w| w[0].log_time_ns <= w[1].log_time_ns),
        "messages out of log-time order"
    );
    let per_topic: u64 = log.topics().iter().map(|t| t.message_count).sum();
    assert_eq!(per_topic, log.message_count() as u64, "per-topic counts");
    if let Some(stats) = log.statistics() {
        assert_eq!(stats.message_count, log.message_count() as u64);
    }
    for message in messages {
        decode_as_recorded(message);
    }
    for topic in log.topics() {
        let _ = topic.offered_qos();
    }
    Some(log)
}

/// Decode a message as each station type (only its own type can succeed); a panic fails.
fn decode_as_recorded(message: &LoggedMessage) {
    let decoded = [
        message.decode::<JointState>().is_ok(),
        message.decode::<Float32MultiArray>().is_ok(),
        message.decode::<PoseStamped>().is_ok(),
        message.decode::<PoseArray>().is_ok(),
        message.decode::<StringMsg>().is_ok(),
    ];
    assert!(
        decoded.iter().filter(|ok| **ok).count() <= 1,
        "a message decoded as two types"
    );
}

/// Write `bytes` to `scratch/NAME.mcap.part`; read its trial events, then recover it into
/// `scratch/NAME.mcap` and check that a recovery that succeeds wrote a readable, complete
/// log. Removes both files.
pub fn check_files(bytes: &[u8], scratch: &Path, name: &str) {
    let part = scratch.join(format!("{name}.mcap.part"));
    let out = scratch.join(format!("{name}.mcap"));
    std::fs::write(&part, bytes).expect("writing the scratch file");
    match read_trial_events(&part) {
        Ok(events) => {
            assert!(events.read_whole_file || events.chunks_read <= events.chunks_total);
            if let Ok(whole) = TrialReader::from_bytes(bytes, &part) {
                assert_eq!(events.metadata, whole.metadata(), "metadata differs");
            }
        }
        Err(error) => assert!(!error.to_string().is_empty()),
    }
    let result = recover(&part, &out);
    if let Ok(report) = &result {
        let log = TrialReader::open(&out)
            .unwrap_or_else(|e| panic!("recovery wrote a log that does not read: {e}"));
        assert_eq!(log.message_count() as u64, report.message_count);
        assert!(log.metadata_named(RECOVERY_METADATA_NAME).is_some());
        assert_eq!(
            report.messages_per_topic.values().sum::<u64>(),
            report.message_count
        );
        assert!(report.unrecoverable_bytes <= report.input_bytes);
    }
    std::fs::remove_file(&part).ok();
    std::fs::remove_file(&out).ok();
    if let Err(error) = result {
        assert!(!error.to_string().is_empty());
    }
}
