//! Where the libraries' log records go: errors on stderr, one line each,
//! `[ERROR target] message` (the `log` crate's records: RustDDS, ros2-client, ...).
//!
//! The station's own messages are printed by its commands; this is for what the libraries
//! report. `pomdar` installs it first thing: without a logger their errors would be lost. The
//! level is fixed (no environment variable): errors only, because RustDDS warns in normal
//! running (a reader proxy without locators before discovery completes, no multicast
//! membership on loopback, datagrams larger than it likes), and ros2-client warns when
//! `ROS_DISTRO` is unset.
//!
//! One RustDDS record is left out: the benign `leave_multicast_group` error of a participant
//! teardown, and only during one ([`crate::ros::teardown`] says why it is benign).

use std::io::Write as _;

use log::{Level, LevelFilter, Log, Metadata, Record};

use crate::ros::teardown::{is_benign_teardown_record, tearing_down};

/// The most verbose level shown.
const SHOWN: Level = Level::Error;

/// The logger: writes records at [`SHOWN`] or above to stderr.
struct StderrLog;

static LOGGER: StderrLog = StderrLog;

/// Install the logger for this process (once; a later call, or a logger installed before,
/// leaves the one in place).
pub fn install() {
    if log::set_logger(&LOGGER).is_ok() {
        log::set_max_level(LevelFilter::Error);
    }
}

/// The line a record is written as (with its newline), or `None` when it is not shown.
fn line_of(level: Level, target: &str, message: &str, tearing_down: bool) -> Option<String> {
    if level > SHOWN || is_benign_teardown_record(level, target, message, tearing_down) {
        return None;
    }
    Some(format!("[{level:<5} {target}] {message}\n"))
}

impl Log for StderrLog {
    fn enabled(&self, metadata: &Metadata<'_>) -> bool {
        metadata.level() <= SHOWN
    }

    fn log(&self, record: &Record<'_>) {
        if !self.enabled(record.metadata()) {
            return;
        }
        let message = record.args().to_string();
        if let Some(line) = line_of(record.level(), record.target(), &message, tearing_down()) {
            // Nowhere to report a failing stderr.
            std::io::stderr().lock().write_all(line.as_bytes()).ok();
        }
    }

    fn flush(&self) {
        std::io::stderr().flush().ok();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_are_shown_with_their_target_and_nothing_less() {
        assert_eq!(
            line_of(Level::Error, "rustdds::dds::pubsub", "Cannot remove", true).as_deref(),
            Some("[ERROR rustdds::dds::pubsub] Cannot remove\n")
        );
        assert_eq!(line_of(Level::Warn, "rustdds", "no locators", false), None);
        assert_eq!(line_of(Level::Info, "rustdds", "started", false), None);
    }

    #[test]
    fn the_multicast_leave_error_is_left_out_only_during_a_teardown() {
        let (target, message) = (
            "rustdds::network::udp_listener",
            "leave_multicast_group: Os { code: 99 }",
        );
        assert_eq!(line_of(Level::Error, target, message, true), None);
        assert!(line_of(Level::Error, target, message, false).is_some());
    }
}
