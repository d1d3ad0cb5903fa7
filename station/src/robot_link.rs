//! The link from the station to the robot's computer, and the age check at its far end.
//!
//! A reliable DDS writer (RustDDS 0.15) keeps every sample a matched reader has not
//! acknowledged, whatever its history depth, and resends all of them when a cut link returns:
//! seconds-old commands, at once, ahead of the current ones. With a relay, the station sends
//! its robot commands best effort (nothing is kept or resent) on relay topics
//! (`relay_prefix` + the robot's topic), and `pomdar relay` on the robot's computer republishes
//! them on the robot's own topics with the reliability the robot's drivers ask for (on that
//! computer's loopback, which no cable cut interrupts), dropping any command older than
//! `max_age_ms` on arrival ([`CommandAgeGate`]).
//!
//! A command's age is judged from the older of its two times: when the station sent it (the
//! DDS source timestamp) and its header stamp, the time its data refers to (a hand command's
//! glove frame, an arm target's control tick). The robot's drivers judge a command by its
//! header stamp, so a command that left the station fresh but computed from a glove frame
//! that was already old (a glove or a station that stalled) is as old to them as one the
//! link delayed; the counts say which of the two it was.

use serde::{Deserialize, Serialize};

use crate::config_error::ConfigError;
use crate::network_config::QosConfig;

/// `[robot_link]`: how commands reach the robot's computer.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RobotLinkConfig {
    /// Prefix of the relay topics the station publishes its robot commands on (best effort),
    /// e.g. `/pomdar/link`: the joint targets then go out on
    /// `/pomdar/link/pomdar/hand/joint_targets`. Empty: publish straight to the robot's topics
    /// with `output.qos` (one computer, or a link that is never cut).
    pub relay_prefix: String,
    /// `pomdar relay` drops a command whose age on arrival exceeds this, milliseconds: its
    /// receive time minus the older of the time the station sent it and its header stamp (the
    /// time its data refers to), on clocks the lab keeps in step.
    pub max_age_ms: u64,
}

impl Default for RobotLinkConfig {
    fn default() -> Self {
        RobotLinkConfig {
            relay_prefix: String::new(),
            max_age_ms: 100,
        }
    }
}

impl RobotLinkConfig {
    /// Check the ranges; errors name the key.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let prefix = &self.relay_prefix;
        let valid_prefix = prefix.is_empty()
            || (prefix.starts_with('/')
                && !prefix.ends_with('/')
                && !prefix.contains("//")
                && prefix
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '/'));
        if !valid_prefix {
            return Err(ConfigError::out_of_range(
                "robot_link.relay_prefix",
                format!("'{prefix}'"),
                "empty, or a topic prefix such as /pomdar/link (letters, digits, _ and /, no trailing /)",
            ));
        }
        if !(1..=10_000).contains(&self.max_age_ms) {
            return Err(ConfigError::out_of_range(
                "robot_link.max_age_ms",
                self.max_age_ms,
                "in [1, 10000]",
            ));
        }
        Ok(())
    }

    /// Whether commands go through `pomdar relay`.
    pub fn relayed(&self) -> bool {
        !self.relay_prefix.is_empty()
    }

    /// The topic `pomdar relay` publishes its status on for the station
    /// ([`crate::link_clock::RelayStatus`]): `relay_prefix` + `/relay_status`; empty when not
    /// relayed.
    pub fn relay_status_topic(&self) -> String {
        match self.relayed() {
            true => format!("{}/relay_status", self.relay_prefix),
            false => String::new(),
        }
    }

    /// The topic and QoS a command for `robot_topic` goes out with, from the station or any
    /// other tool that commands the robot (calibration, the hand check): best effort on the
    /// relay topic when relayed, otherwise `output_qos` on the robot's own topic.
    pub fn command_wire(&self, robot_topic: &str, output_qos: QosConfig) -> (String, QosConfig) {
        (self.wire_topic(robot_topic), self.command_qos(output_qos))
    }

    /// The QoS of commands: best effort when relayed (nothing old kept or resent after a cut),
    /// otherwise `output_qos`.
    pub fn command_qos(&self, output_qos: QosConfig) -> QosConfig {
        match self.relayed() {
            true => QosConfig::best_effort(output_qos.depth),
            false => output_qos,
        }
    }

    /// The topic the station publishes `robot_topic` on: the relay topic when relayed.
    pub fn wire_topic(&self, robot_topic: &str) -> String {
        match self.relayed() {
            true => format!("{}{}", self.relay_prefix, robot_topic),
            false => robot_topic.to_string(),
        }
    }
}

/// What the relay does with one command.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AgeVerdict {
    /// Fresh enough: republish it.
    Forward,
    /// Older than the limit on arrival: drop it.
    TooOld {
        /// Its age, nanoseconds.
        age_ns: i64,
        /// Whether it is too old by its header stamp only, the link having delivered it within
        /// the limit of its send time: its input was late (the glove or the station stalled),
        /// not the link.
        by_stamp: bool,
    },
    /// Sent or stamped later than it was received by more than the limit: the computers'
    /// clocks disagree (or the sender's is wrong); dropped, since its age cannot be known.
    FromTheFuture {
        /// How far ahead, nanoseconds.
        ahead_ns: i64,
    },
    /// Neither a send time nor a header stamp: its age cannot be known; dropped.
    Unstamped,
}

impl AgeVerdict {
    /// Whether the command is republished.
    pub fn forwards(&self) -> bool {
        matches!(self, AgeVerdict::Forward)
    }
}

/// Counts of what the gate decided.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize)]
pub struct AgeCounts {
    /// Commands republished.
    pub forwarded: u64,
    /// Commands dropped as older than the limit.
    pub too_old: u64,
    /// Of those, the commands too old by their header stamp only (the link delivered them
    /// within the limit of their send time): late input, not the link.
    pub too_old_by_stamp: u64,
    /// Commands dropped as sent in the future (clocks out of step).
    pub from_the_future: u64,
    /// Commands dropped without a send time.
    pub unstamped: u64,
    /// The oldest command dropped, nanoseconds.
    pub oldest_dropped_ns: i64,
}

impl AgeCounts {
    /// Commands dropped, for any reason.
    pub fn dropped(&self) -> u64 {
        self.too_old + self.from_the_future + self.unstamped
    }
}

/// The times a command carries, as the relay reads them.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CommandTimes {
    /// When the station sent it (the DDS source timestamp), nanoseconds since the epoch.
    pub sent_ns: Option<i64>,
    /// Its header stamp, nanoseconds since the epoch; None for a type without a header or a
    /// stamp left at zero.
    pub stamp_ns: Option<i64>,
}

impl CommandTimes {
    /// The times of a command sent at `sent_ns` with header stamp `stamp_ns` (zero: unset).
    pub fn new(sent_ns: Option<i64>, stamp_ns: Option<i64>) -> CommandTimes {
        CommandTimes {
            sent_ns,
            stamp_ns: stamp_ns.filter(|s| *s != 0),
        }
    }

    /// Whether a command received at `received_ns` is too old by its stamp only: its send
    /// time, if any, within `max_age_ns`.
    fn old_by_stamp_only(&self, received_ns: i64, max_age_ns: i64) -> bool {
        self.stamp_ns
            .is_some_and(|stamp| received_ns.saturating_sub(stamp) > max_age_ns)
            && self
                .sent_ns
                .is_none_or(|sent| received_ns.saturating_sub(sent) <= max_age_ns)
    }
}

/// The relay's check of each command's age: its receive time minus the older of its send
/// time and header stamp, all wall clocks.
#[derive(Debug, Clone)]
pub struct CommandAgeGate {
    max_age_ns: i64,
    counts: AgeCounts,
}

impl CommandAgeGate {
    /// A gate dropping commands older than `max_age_ms`.
    pub fn new(max_age_ms: u64) -> CommandAgeGate {
        CommandAgeGate {
            max_age_ns: i64::try_from(max_age_ms)
                .unwrap_or(i64::MAX / 1_000_000)
                .saturating_mul(1_000_000),
            counts: AgeCounts::default(),
        }
    }

    /// Judge a command with `times` received at `received_ns`.
    pub fn judge(&mut self, times: CommandTimes, received_ns: i64) -> AgeVerdict {
        let verdict = self.verdict(times, received_ns);
        let counts = &mut self.counts;
        match verdict {
            AgeVerdict::Forward => counts.forwarded += 1,
            AgeVerdict::TooOld { age_ns, by_stamp } => {
                counts.too_old += 1;
                counts.too_old_by_stamp += u64::from(by_stamp);
                counts.oldest_dropped_ns = counts.oldest_dropped_ns.max(age_ns);
            }
            AgeVerdict::FromTheFuture { .. } => counts.from_the_future += 1,
            AgeVerdict::Unstamped => counts.unstamped += 1,
        }
        verdict
    }

    fn verdict(&self, times: CommandTimes, received_ns: i64) -> AgeVerdict {
        let known = [times.sent_ns, times.stamp_ns].into_iter().flatten();
        let (Some(oldest), Some(newest)) = (known.clone().min(), known.max()) else {
            return AgeVerdict::Unstamped;
        };
        let age_ns = received_ns.saturating_sub(oldest);
        let ahead_ns = newest.saturating_sub(received_ns);
        if age_ns > self.max_age_ns {
            AgeVerdict::TooOld {
                age_ns,
                by_stamp: times.old_by_stamp_only(received_ns, self.max_age_ns),
            }
        } else if ahead_ns > self.max_age_ns {
            AgeVerdict::FromTheFuture { ahead_ns }
        } else {
            AgeVerdict::Forward
        }
    }

    /// What the gate decided so far.
    pub fn counts(&self) -> &AgeCounts {
        &self.counts
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: i64 = 1_000_000;

    fn sent(sent_ns: i64) -> CommandTimes {
        CommandTimes::new(Some(sent_ns), None)
    }

    #[test]
    fn commands_within_the_age_limit_pass_older_ones_and_unknown_ages_do_not() {
        let mut gate = CommandAgeGate::new(100);
        let t = 1_700_000_000_000 * MS;
        assert_eq!(gate.judge(sent(t - 2 * MS), t), AgeVerdict::Forward);
        assert_eq!(gate.judge(sent(t - 100 * MS), t), AgeVerdict::Forward);
        assert_eq!(
            gate.judge(sent(t - 101 * MS), t),
            AgeVerdict::TooOld {
                age_ns: 101 * MS,
                by_stamp: false
            }
        );
        assert_eq!(
            gate.judge(sent(t - 8_000 * MS), t),
            AgeVerdict::TooOld {
                age_ns: 8_000 * MS,
                by_stamp: false
            }
        );
        // A little ahead (clocks a few ms apart) passes; far ahead cannot be judged.
        assert_eq!(gate.judge(sent(t + 5 * MS), t), AgeVerdict::Forward);
        assert_eq!(
            gate.judge(sent(t + 500 * MS), t),
            AgeVerdict::FromTheFuture { ahead_ns: 500 * MS }
        );
        assert_eq!(
            gate.judge(CommandTimes::default(), t),
            AgeVerdict::Unstamped
        );
        let counts = gate.counts();
        assert_eq!(
            (counts.forwarded, counts.too_old, counts.from_the_future),
            (3, 2, 1)
        );
        assert_eq!((counts.unstamped, counts.dropped()), (1, 4));
        assert_eq!(counts.oldest_dropped_ns, 8_000 * MS);
        assert!(!AgeVerdict::Unstamped.forwards());
    }

    #[test]
    fn a_header_stamp_older_than_its_send_time_ages_the_command() {
        let mut gate = CommandAgeGate::new(100);
        let t = 1_700_000_000_000 * MS;
        // Sent 5 ms ago from a glove frame 40 ms old: fresh.
        let fresh = CommandTimes::new(Some(t - 5 * MS), Some(t - 40 * MS));
        assert_eq!(gate.judge(fresh, t), AgeVerdict::Forward);
        // Sent 5 ms ago from a frame 139 ms old (the glove or the station stalled), or 80 ms
        // ago from a frame 60 ms old: too old by the stamp only, the link on time.
        for (sent, stamp) in [(5, 139), (80, 140)] {
            let late_input = CommandTimes::new(Some(t - sent * MS), Some(t - stamp * MS));
            assert_eq!(
                gate.judge(late_input, t),
                AgeVerdict::TooOld {
                    age_ns: stamp * MS,
                    by_stamp: true
                }
            );
        }
        // Stamped fresh, delayed by the link: old by its send time.
        let late_link = CommandTimes::new(Some(t - 300 * MS), Some(t - 301 * MS));
        assert_eq!(
            gate.judge(late_link, t),
            AgeVerdict::TooOld {
                age_ns: 301 * MS,
                by_stamp: false
            }
        );
        // A zero stamp is no stamp; a stamp alone is judged.
        assert_eq!(
            gate.judge(CommandTimes::new(Some(t - 5 * MS), Some(0)), t),
            AgeVerdict::Forward
        );
        assert_eq!(
            gate.judge(CommandTimes::new(None, Some(t - 2 * MS)), t),
            AgeVerdict::Forward
        );
        // A stamp far ahead of this clock cannot be judged.
        assert_eq!(
            gate.judge(CommandTimes::new(Some(t - 5 * MS), Some(t + 500 * MS)), t),
            AgeVerdict::FromTheFuture { ahead_ns: 500 * MS }
        );
        let counts = gate.counts();
        assert_eq!((counts.too_old, counts.too_old_by_stamp), (3, 2));
        assert_eq!((counts.forwarded, counts.from_the_future), (3, 1));
    }

    #[test]
    fn relay_topics_are_the_prefix_and_the_robot_topic() {
        let mut link = RobotLinkConfig::default();
        assert!(!link.relayed());
        assert_eq!(link.wire_topic("/franka/cmd"), "/franka/cmd");
        link.relay_prefix = "/pomdar/link".into();
        assert!(link.relayed());
        assert_eq!(link.wire_topic("/franka/cmd"), "/pomdar/link/franka/cmd");
        assert_eq!(link.relay_status_topic(), "/pomdar/link/relay_status");
        // Every tool commanding the robot goes through the relay, best effort, once relayed.
        let reliable = QosConfig::reliable(50);
        let (topic, qos) = link.command_wire("/pomdar/hand/joint_targets", reliable);
        assert_eq!(topic, "/pomdar/link/pomdar/hand/joint_targets");
        assert_eq!(qos, QosConfig::best_effort(50));
        let direct = RobotLinkConfig::default().command_wire("/franka/cmd", reliable);
        assert_eq!(direct, ("/franka/cmd".to_string(), reliable));
        link.validate().unwrap();
    }

    #[test]
    fn a_bad_prefix_or_age_names_its_key() {
        for prefix in ["pomdar", "/pomdar/", "/a//b", "/a b", "/ä"] {
            let link = RobotLinkConfig {
                relay_prefix: prefix.into(),
                ..RobotLinkConfig::default()
            };
            let error = link.validate().unwrap_err().to_string();
            assert!(
                error.contains("robot_link.relay_prefix"),
                "{prefix}: {error}"
            );
        }
        for age in [0, 10_001] {
            let link = RobotLinkConfig {
                max_age_ms: age,
                ..RobotLinkConfig::default()
            };
            let error = link.validate().unwrap_err().to_string();
            assert!(error.contains("robot_link.max_age_ms"), "{age}: {error}");
        }
    }
}
