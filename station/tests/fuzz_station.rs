#![allow(clippy::unwrap_used, clippy::expect_used)]
//! The whole station fuzzed (docs/FAULTS.md, "Hostile frames"): seeded runs of hostile frames,
//! wrist poses, arm feedback, clock jumps and operator commands in any order, every output
//! checked against the invariants of `station::fuzz`; the run must find no violation and must
//! reach every case it is meant to exercise.

use retarget::HandModel;
use station::StationConfig;
use station::fuzz::{FuzzOptions, Tally, config_for_seed, run};

/// The ETH lab's preset, as shipped.
const ETH_LAB: &str = include_str!("../../launch_configs/station/eth_lab.toml");
/// Seeds: every constraint, both control modes, with and without auto-engage.
const SEEDS: std::ops::Range<u64> = 0..8;
/// Keypoint frames per seed.
const FRAMES: u64 = 5_000;

/// Events the runs must reach, with the least count over all seeds.
const REACHED: [(&str, u64); 24] = [
    ("out.hand.fresh", 5_000),
    ("out.hand.repeated_or_held", 1_000),
    ("out.arm", 5_000),
    ("state.engage_granted", 200),
    ("state.to_held", 200),
    ("state.to_disengaged", 200),
    ("verdict.new", 10_000),
    ("verdict.repeat", 1_000),
    ("verdict.sender_clock_jump_followed", 100),
    ("rejected.out_of_order", 200),
    ("rejected.non_finite", 200),
    ("rejected.wrong_size", 200),
    ("rejected.bone_length", 200),
    ("rejected.jump", 200),
    ("clock.sender_jump_ahead", 20),
    ("clock.sender_jump_back", 20),
    ("clock.sender_wild", 10),
    ("clock.station_gap_1s_to_5s", 20),
    ("frame.burst", 1_000),
    ("in.disengage", 100),
    ("in.arm_blocked", 10),
    ("in.wrist.hostile", 100),
    ("in.arm_feedback.hostile", 100),
    ("notice.arm_not_engaged", 1),
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
    for (name, count) in &total.invariants {
        assert!(count.checks > 0, "{name} never checked");
    }
}
