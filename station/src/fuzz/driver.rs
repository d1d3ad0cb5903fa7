//! The fuzz driver: one station, one hostile world, a checker on every step.

use retarget::HandModel;
use retarget::human_hand::MotionKind;

use super::checker::Checker;
use super::plausible_hand::PlausibleHand;
use super::tally::Tally;
use super::world::World;
use crate::arm::Constraint;
use crate::station::Station;
use crate::station_config::{ControlMode, StationConfig};
use crate::station_error::StationError;

/// The station clock at the start of a run: 2026-01-01, nanoseconds since the epoch.
pub const START_NS: i64 = 1_767_225_600_000_000_000;

/// What to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FuzzOptions {
    /// Seed of the world (and of the configuration's variant, see [`config_for_seed`]).
    pub seed: u64,
    /// Keypoint frames to feed (the other inputs come between them).
    pub frames: u64,
}

/// `base` varied by `seed`: the task constraint (fixed, vertical, horizontal, free in turn),
/// the control mode (on arrival, rate) and auto-engage (every third seed).
pub fn config_for_seed(base: &StationConfig, seed: u64) -> StationConfig {
    let mut config = base.clone();
    config.arm.constraint = [
        Constraint::Fixed,
        Constraint::VerticalAxis,
        Constraint::HorizontalAxis,
        Constraint::Free,
    ][(seed % 4) as usize];
    config.control.mode = if (seed / 4).is_multiple_of(2) {
        ControlMode::OnArrival
    } else {
        ControlMode::Rate
    };
    config.control.auto_engage = seed.is_multiple_of(3);
    config
}

/// Feed a station built from `config` (driving `model`) `options.frames` keypoint frames of a
/// hostile world, checking every output; the counts of what happened and was found.
pub fn run(
    config: &StationConfig,
    model: HandModel,
    options: FuzzOptions,
) -> Result<Tally, StationError> {
    let mut station = Station::new(config, model, None)?;
    let kind = MotionKind::ALL[(options.seed % MotionKind::ALL.len() as u64) as usize];
    let hand = PlausibleHand::new(config.retarget.layout, kind, kind.default_period_s())?;
    let mut world = World::new(options.seed, hand, config.arm.workspace(), START_NS);
    let mut checker = Checker::new(config, &station);
    let mut tally = Tally::default();
    while tally.event("in.frame") < options.frames {
        let (input, now_ns) = world.next(&mut tally);
        let outputs = station.step(input.clone(), now_ns);
        checker.after_step(&input, now_ns, &outputs, &station, &mut tally);
        tally.count("steps");
    }
    let totals = station.totals();
    tally.add("station.hand_commands", totals.hand_commands);
    tally.add("station.arm_targets", totals.arm_targets);
    tally.add("station.wrist_rejected", totals.wrist_rejected);
    tally.add("station.arm_engage_failed", totals.arm_engage_failed);
    for (reason, n) in &totals.arm_refused {
        tally.add(&format!("station.arm_refused.{reason}"), *n);
    }
    let counters = station.counters();
    tally.add("station.solves", counters.solves);
    tally.add("station.frames_superseded", counters.frames_superseded);
    tally.add("station.source_clock_jumps", counters.source_clock_jumps);
    tally.add(
        "station.frames_timed_by_receipt",
        counters.frames_timed_by_receipt,
    );
    tally.add(
        "station.rejected.retargeter",
        counters.rejected.get("retargeter").copied().unwrap_or(0),
    );
    Ok(tally)
}
