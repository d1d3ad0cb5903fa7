//! The input watchdog: how fresh the glove stream is decides what the station may drive.
//!
//! ```text
//!            new frame                    age > hold_timeout            age > disengage_timeout
//! Engaged ───────────────▶ Engaged ─────────────────────▶ Held ─────────────────────▶ Disengaged
//!    ▲                                       │ new frame                                   │
//!    │                                       ▼                                             │
//!    └──────────────────────────────── Engaged               explicit engage + fresh input ┘
//! ```
//!
//! Age is measured from the last *new* keypoint frame (repeats do not count: the lab's
//! ingress republishes a dead glove's last frame forever). While Held the station repeats its
//! last command; once Disengaged it stops driving the arm, and only an explicit engage —
//! with fresh input — resumes. Time is a parameter (nanoseconds on the station's clock).

use serde::{Deserialize, Serialize};

use crate::config_error::ConfigError;

/// Timeouts of the watchdog.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WatchdogConfig {
    /// Input older than this holds the last command, milliseconds.
    pub hold_timeout_ms: u64,
    /// Input older than this disengages, milliseconds.
    pub disengage_timeout_ms: u64,
}

impl Default for WatchdogConfig {
    fn default() -> Self {
        WatchdogConfig {
            hold_timeout_ms: 150,
            disengage_timeout_ms: 500,
        }
    }
}

impl WatchdogConfig {
    /// Check the ranges; errors name the key.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if !(10..=10_000).contains(&self.hold_timeout_ms) {
            return Err(ConfigError::out_of_range(
                "watchdog.hold_timeout_ms",
                self.hold_timeout_ms,
                "in 10..=10000",
            ));
        }
        if self.disengage_timeout_ms <= self.hold_timeout_ms || self.disengage_timeout_ms > 60_000 {
            return Err(ConfigError::out_of_range(
                "watchdog.disengage_timeout_ms",
                self.disengage_timeout_ms,
                format!(
                    "greater than hold_timeout_ms ({}) and at most 60000",
                    self.hold_timeout_ms
                ),
            ));
        }
        Ok(())
    }
}

/// What the station may do.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DriveState {
    /// Fresh input: retarget and drive.
    Engaged,
    /// Stale input: repeat the last command.
    Held,
    /// Long-stale input or operator disengage: do not drive the arm until engaged again.
    Disengaged,
}

/// The watchdog.
#[derive(Debug, Clone)]
pub struct Watchdog {
    config: WatchdogConfig,
    state: DriveState,
    last_frame_ns: Option<i64>,
}

impl Watchdog {
    /// Starts disengaged: the operator engages once input flows.
    pub fn new(config: WatchdogConfig) -> Watchdog {
        Watchdog {
            config,
            state: DriveState::Disengaged,
            last_frame_ns: None,
        }
    }

    /// The current state.
    pub fn state(&self) -> DriveState {
        self.state
    }

    /// Age of the last new frame at `now_ns`, if any arrived.
    pub fn age_ns(&self, now_ns: i64) -> Option<i64> {
        self.last_frame_ns.map(|t| now_ns - t)
    }

    /// A new (not repeated, accepted) frame arrived at `now_ns`.
    pub fn frame(&mut self, now_ns: i64) {
        self.last_frame_ns = Some(now_ns);
        if self.state == DriveState::Held {
            self.state = DriveState::Engaged;
        }
    }

    /// The operator asks to engage; granted only with fresh input. Returns whether engaged.
    pub fn engage(&mut self, now_ns: i64) -> bool {
        if self.fresh(now_ns) {
            self.state = DriveState::Engaged;
        }
        self.state == DriveState::Engaged
    }

    /// The operator disengages.
    pub fn disengage(&mut self) {
        self.state = DriveState::Disengaged;
    }

    /// Advance the state to `now_ns`; returns the state.
    pub fn update(&mut self, now_ns: i64) -> DriveState {
        let age_ms = self.age_ns(now_ns).map(|a| a / 1_000_000);
        match (self.state, age_ms) {
            (DriveState::Disengaged, _) => {}
            (_, None) => self.state = DriveState::Disengaged,
            (_, Some(age)) if age > self.config.disengage_timeout_ms as i64 => {
                self.state = DriveState::Disengaged;
            }
            (_, Some(age)) if age > self.config.hold_timeout_ms as i64 => {
                self.state = DriveState::Held;
            }
            _ => {}
        }
        self.state
    }

    fn fresh(&self, now_ns: i64) -> bool {
        self.age_ns(now_ns)
            .is_some_and(|a| a / 1_000_000 <= self.config.hold_timeout_ms as i64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: i64 = 1_000_000;

    #[test]
    fn stale_input_holds_then_disengages_and_only_engage_resumes() {
        let mut w = Watchdog::new(WatchdogConfig::default());
        assert_eq!(w.update(0), DriveState::Disengaged);
        assert!(!w.engage(0), "no input yet");
        w.frame(10 * MS);
        assert!(w.engage(20 * MS));
        assert_eq!(w.update(100 * MS), DriveState::Engaged);
        assert_eq!(w.update(170 * MS), DriveState::Held);
        w.frame(180 * MS);
        assert_eq!(
            w.update(181 * MS),
            DriveState::Engaged,
            "a new frame ends a hold"
        );
        assert_eq!(w.update(1200 * MS), DriveState::Disengaged);
        w.frame(1300 * MS);
        assert_eq!(
            w.update(1301 * MS),
            DriveState::Disengaged,
            "fresh input alone does not resume"
        );
        assert!(w.engage(1302 * MS));
        assert_eq!(w.update(1303 * MS), DriveState::Engaged);
        w.disengage();
        assert_eq!(w.update(1304 * MS), DriveState::Disengaged);
    }

    #[test]
    fn config_ranges_are_named() {
        let bad = WatchdogConfig {
            hold_timeout_ms: 500,
            disengage_timeout_ms: 400,
        };
        assert!(
            bad.validate()
                .unwrap_err()
                .to_string()
                .contains("disengage_timeout_ms")
        );
    }
}
