//! The drive state as docs/FAULTS.md states it, kept apart from the station's own watchdog:
//! disengaged at start, by the operator, or at a tick that finds the newest new frame older
//! than the disengage timeout; engaged again only by an engage granted with fresh input (an
//! explicit one, or the configured auto-engage at the first new frame).

use crate::frame_gate::GateDecision;
use crate::station_config::StationConfig;
use crate::station_input::{ControlInput, StationInput, StationOutputs};

const MS: i64 = 1_000_000;

/// What one input did to the modelled drive state.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Transition {
    /// An engage was granted while disengaged.
    pub engaged: bool,
    /// The station disengaged (operator or timeout) while not disengaged.
    pub disengaged: bool,
}

/// The modelled drive state.
#[derive(Debug, Clone)]
pub struct DriveModel {
    disengaged: bool,
    last_new_ns: Option<i64>,
    auto_engage_pending: bool,
    drives_robot: bool,
    hold_ms: i64,
    disengage_ms: i64,
}

impl DriveModel {
    /// The model for a station built from `config`.
    pub fn new(config: &StationConfig) -> DriveModel {
        DriveModel {
            disengaged: true,
            last_new_ns: None,
            auto_engage_pending: config.control.auto_engage && config.drives_robot(),
            drives_robot: config.drives_robot(),
            hold_ms: config.watchdog.hold_timeout_ms as i64,
            disengage_ms: config.watchdog.disengage_timeout_ms as i64,
        }
    }

    /// Whether the station must be disengaged now.
    pub fn disengaged(&self) -> bool {
        self.disengaged
    }

    /// Follow `input`, received at `now_ns`, whose step gave `outputs` (the frame gate's
    /// verdict).
    pub fn follow(
        &mut self,
        input: &StationInput,
        now_ns: i64,
        outputs: &StationOutputs,
    ) -> Transition {
        let was = self.disengaged;
        match input {
            StationInput::Keypoints(_)
                if matches!(
                    outputs.verdict,
                    Some(GateDecision::New | GateDecision::Repaired)
                ) =>
            {
                self.last_new_ns = Some(now_ns);
                if self.auto_engage_pending {
                    self.auto_engage_pending = false;
                    self.disengaged = false;
                }
            }
            StationInput::Control(ControlInput::Tick) => {
                let stale = self
                    .age_ms(now_ns)
                    .is_none_or(|age| age > self.disengage_ms);
                if stale {
                    self.disengaged = true;
                }
            }
            StationInput::Control(ControlInput::Engage) => {
                let fresh = self.age_ms(now_ns).is_some_and(|age| age <= self.hold_ms);
                if self.drives_robot && fresh {
                    self.disengaged = false;
                }
            }
            StationInput::Control(ControlInput::Disengage) => self.disengaged = true,
            _ => {}
        }
        Transition {
            engaged: was && !self.disengaged,
            disengaged: !was && self.disengaged,
        }
    }

    /// Age of the newest new frame, whole milliseconds (as the watchdog rounds).
    fn age_ms(&self, now_ns: i64) -> Option<i64> {
        self.last_new_ns.map(|t| (now_ns - t) / MS)
    }
}
