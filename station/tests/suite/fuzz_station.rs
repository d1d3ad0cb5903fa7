//! The whole station fuzzed (docs/FAULTS.md, "Hostile frames"): seeded runs of hostile frames,
//! wrist poses, arm feedback, clock jumps and operator commands in any order, every output
//! checked against the invariants of `station::fuzz`; the run must find no violation and must
//! reach every case it is meant to exercise.

use retarget::HandModel;
use station::StationConfig;
use station::fuzz::{FuzzOptions, Tally, config_for_seed, run};

/// The ETH lab's preset, as shipped.
const ETH_LAB: &str = include_str!("../../../launch_configs/station/eth_lab.toml");
/// Seeds: every constraint, both control modes, with and without auto-engage.
const SEEDS: std::ops::Range<u64> = 0..8;
/// Keypoint frames per seed.
const FRAMES: u64 = 5_000;

/// Events the runs must reach, with the least count over all seeds (about half of what the
/// seeds reach: a change that stops the driver reaching a case fails here).
const REACHED: [(&str, u64); 30] = [
    ("out.hand.fresh", 5_000),
    ("out.hand.repeated_or_held", 3_000),
    ("out.arm", 3_000),
    ("state.engage_granted", 250),
    ("state.to_held", 100),
    ("state.to_disengaged", 250),
    ("verdict.new", 10_000),
    ("verdict.repeat", 1_000),
    // A frame with one point off its digit (a tracker's outlier): the point put back.
    ("verdict.repaired", 150),
    ("verdict.sender_clock_jump_followed", 400),
    ("rejected.out_of_order", 2_500),
    ("rejected.non_finite", 400),
    ("rejected.wrong_size", 300),
    ("rejected.bone_length", 1_000),
    ("rejected.jump", 1_300),
    ("station.rejected.retargeter", 1),
    // New frames after three in a row whose stamps did not advance: timed by receipt.
    ("station.frames_timed_by_receipt", 1_000),
    ("station.arm_refused.implausible_position", 20),
    ("clock.sender_jump_ahead", 30),
    ("clock.sender_jump_back", 30),
    ("clock.sender_step_back", 30),
    ("clock.sender_wild", 15),
    ("clock.station_gap_1s_to_5s", 80),
    ("frame.burst", 3_000),
    ("in.disengage", 300),
    ("in.arm_blocked", 50),
    ("in.wrist.hostile", 400),
    ("in.arm_feedback.hostile", 200),
    ("notice.arm_not_engaged", 20),
    ("notice.arm_blocked", 50),
];

/// Every invariant, with the least number of checks over all seeds.
const CHECKED: [(&str, u64); 15] = [
    ("drive_state", 30_000),
    ("hand_finite", 8_000),
    ("hand_limits", 8_000),
    ("hand_rate", 5_000),
    ("hand_newest_frame", 5_000),
    ("hand_held_is_last", 3_000),
    ("hand_held_after_disengage", 2_000),
    ("hand_stamp_order", 10_000),
    ("arm_finite", 3_000),
    ("arm_stamp", 3_000),
    ("arm_engaged", 3_000),
    ("arm_clutched", 3_000),
    ("arm_workspace", 3_000),
    ("arm_constraint", 2_000),
    ("arm_step", 3_000),
];

#[test]
fn the_whole_station_fuzzed_breaks_no_invariant_and_reaches_every_case() {
    let base = StationConfig::from_toml_str(ETH_LAB).unwrap();
    let mut total = Tally::default();
    for seed in SEEDS {
        let config = config_for_seed(&base, seed);
        let options = FuzzOptions {
            seed,
            frames: FRAMES,
        };
        let tally = run(&config, HandModel::orca_v1_right(), options).unwrap();
        total.merge(&tally);
    }
    println!("{total}");
    assert_eq!(total.violations(), 0, "{total}");
    for (kind, least) in REACHED {
        assert!(
            total.event(kind) >= least,
            "the runs reached {kind} {} times, fewer than {least}:\n{total}",
            total.event(kind)
        );
    }
    assert_eq!(total.invariants.len(), CHECKED.len(), "{total}");
    for (name, least) in CHECKED {
        let checks = total.invariants.get(name).map_or(0, |c| c.checks);
        assert!(
            checks >= least,
            "{name} checked {checks} times, fewer than {least}"
        );
    }
}
