//! The invariant checker: after every step it follows the input in its own models (drive
//! state, pending frame, clutch) and checks every output against them (see
//! [`hand_checks`](super::hand_checks) and [`arm_checks`](super::arm_checks)), plus
//! `drive_state`: the station is disengaged exactly when the model of docs/FAULTS.md says so.

use super::arm_checks::ArmTrack;
use super::drive_model::DriveModel;
use super::hand_checks::HandTrack;
use super::tally::Tally;
use crate::frame_gate::GateDecision;
use crate::station::Station;
use crate::station_config::StationConfig;
use crate::station_input::{ControlInput, Notice, StationInput, StationOutputs};
use crate::watchdog::DriveState;

/// Checks every step of one station.
#[derive(Debug, Clone)]
pub struct Checker {
    step: u64,
    model: DriveModel,
    hand: HandTrack,
    arm: ArmTrack,
    seen_clock_jumps: u64,
    previous_state: DriveState,
}

impl Checker {
    /// A checker for `station`, built from `config` and not stepped yet.
    pub fn new(config: &StationConfig, station: &Station) -> Checker {
        Checker {
            step: 0,
            model: DriveModel::new(config),
            hand: HandTrack::new(config, station),
            arm: ArmTrack::new(&config.arm, &config.output.arm_frame_id),
            seen_clock_jumps: station.counters().source_clock_jumps,
            previous_state: station.state(),
        }
    }

    /// `station` took `input` at `now_ns` and gave `outputs`: follow and check.
    pub fn after_step(
        &mut self,
        input: &StationInput,
        now_ns: i64,
        outputs: &StationOutputs,
        station: &Station,
        tally: &mut Tally,
    ) {
        self.step += 1;
        let step = self.step;
        self.arm.input(input);
        let transition = self.model.follow(input, now_ns, outputs);
        if transition.disengaged {
            self.arm.disengaged();
        }
        if transition.engaged {
            tally.count("state.engage_granted");
            self.hand.engaged();
            self.arm.engaged();
        }
        let jumps = station.counters().source_clock_jumps;
        let jumped = jumps > self.seen_clock_jumps;
        self.seen_clock_jumps = jumps;
        self.count_verdict(input, now_ns, outputs, (jumps, jumped), tally);
        let state = station.state();
        self.count_state(state, outputs, tally);
        if matches!(input, StationInput::Control(ControlInput::Tick))
            && state == DriveState::Engaged
        {
            self.arm.engaged_tick(outputs);
        }
        let disengaged = self.model.disengaged();
        tally.check(
            step,
            "drive_state",
            (state == DriveState::Disengaged) == disengaged,
            || format!("station {state:?}, model disengaged: {disengaged}"),
        );
        let ctx = (step, now_ns, disengaged);
        self.hand.check(outputs, ctx, station, tally);
        self.arm.check(outputs, ctx, tally);
    }

    fn count_verdict(
        &mut self,
        input: &StationInput,
        now_ns: i64,
        outputs: &StationOutputs,
        (jumps, jumped): (u64, bool),
        tally: &mut Tally,
    ) {
        let StationInput::Keypoints(frame) = input else {
            return;
        };
        match outputs.verdict {
            Some(verdict @ (GateDecision::New | GateDecision::Repaired)) => {
                tally.count(if verdict == GateDecision::New {
                    "verdict.new"
                } else {
                    "verdict.repaired"
                });
                self.hand
                    .new_frame(frame.source_ns, now_ns, (jumps, jumped));
            }
            Some(GateDecision::Repeat) => tally.count("verdict.repeat"),
            Some(GateDecision::Rejected(reason)) => tally.count(match reason.name() {
                "wrong_size" => "rejected.wrong_size",
                "non_finite" => "rejected.non_finite",
                "bone_length" => "rejected.bone_length",
                "jump" => "rejected.jump",
                "out_of_order" => "rejected.out_of_order",
                _ => "rejected.other",
            }),
            None => tally.count("verdict.missing"),
        }
        if jumped {
            tally.count("verdict.sender_clock_jump_followed");
        }
    }

    fn count_state(&mut self, state: DriveState, outputs: &StationOutputs, tally: &mut Tally) {
        if state != self.previous_state {
            tally.count(match state {
                DriveState::Engaged => "state.to_engaged",
                DriveState::Held => "state.to_held",
                DriveState::Disengaged => "state.to_disengaged",
            });
            self.previous_state = state;
        }
        for notice in &outputs.notices {
            tally.count(match notice {
                Notice::ArmNotEngaged(_) => "notice.arm_not_engaged",
                Notice::ArmBlocked => "notice.arm_blocked",
            });
        }
    }
}
