//! The hand check's state machine, stepped with explicit times: no DDS, no clock.

use retarget::HandModel;
use station::StationConfig;
use station::policy_output::PolicyOutput;

use super::session::{Answer, CheckPhase, HandCheck, MAX_STEP_RAD, Motion};

const ETH_LAB: &str = include_str!("../../../launch_configs/station/eth_lab.toml");
const ORCA_CORE: &str = include_str!("../../../launch_configs/station/orca_core.toml");

fn check(text: &str) -> HandCheck {
    let config = StationConfig::from_toml_str(text).unwrap().policy_output;
    HandCheck::new(HandModel::orca_v1_right(), config, Motion::default(), 0.0).unwrap()
}

const M: Motion = Motion {
    step_rad: MAX_STEP_RAD,
    move_s: 1.5,
    hold_s: 0.5,
    settle_s: 2.0,
};

/// Step the check from `t` until it asks, at 25 Hz; returns the time it asked.
fn until_asking(c: &mut HandCheck, mut t: f64) -> f64 {
    for _ in 0..1000 {
        c.tick(t);
        if c.phase() == CheckPhase::Asking {
            return t;
        }
        t += 0.04;
    }
    panic!("never asked: {:?}", c.phase());
}

#[test]
fn the_neutral_pose_is_inside_every_range() {
    let model = HandModel::orca_v1_right();
    for text in [ETH_LAB, ORCA_CORE] {
        let c = check(text);
        let config = StationConfig::from_toml_str(text).unwrap().policy_output;
        let output = PolicyOutput::new(&model, &config).unwrap();
        for slot in 0..17 {
            let (lo, hi) = output.urdf_range(&model, slot).unwrap();
            let q = c.neutral()[output.dofs()[slot]];
            assert!(q > lo && q < hi, "slot {slot}: {q} not in ({lo}, {hi})");
        }
        // The command at neutral is inside the consumer's ranges, unclamped.
        let sent = c.command(0.0);
        for (row, value) in config.joints.iter().zip(&sent) {
            let deg = match config.units {
                station::hand_convention::Units::Rad => f64::from(*value).to_degrees(),
                station::hand_convention::Units::Deg => f64::from(*value),
            };
            assert!(
                deg > row.lower_deg && deg < row.upper_deg,
                "{}: {deg}",
                row.joint
            );
        }
    }
}

#[test]
fn each_joint_moves_alone_a_small_step_slowly_and_back() {
    let mut c = check(ETH_LAB);
    assert_eq!(c.phase(), CheckPhase::Settling);
    c.tick(M.settle_s);
    assert_eq!(c.phase(), CheckPhase::Moving);
    assert_eq!(c.progress(), "joint 1 of 17: wrist");
    let neutral = c.neutral().to_vec();
    let wrist = c.joints()[0].dof;
    let mut largest: f64 = 0.0;
    let mut t = M.settle_s;
    while t < M.settle_s + 2.0 * M.move_s + M.hold_s {
        let q = c.pose(t);
        for (i, (a, b)) in q.iter().zip(&neutral).enumerate() {
            if i != wrist {
                assert_eq!(a, b, "joint {i} moved while the wrist was checked");
            }
        }
        largest = largest.max((q[wrist] - neutral[wrist]).abs());
        // After 0.5 s the step is at most half done: slow.
        if t - M.settle_s <= 0.5 {
            assert!((q[wrist] - neutral[wrist]).abs() <= MAX_STEP_RAD / 2.0 + 1e-9);
        }
        t += 0.04;
    }
    assert!((largest - MAX_STEP_RAD).abs() < 1e-9, "{largest}");
    let lines = c.take_lines().join("\n");
    assert!(
        lines.contains("joint 1 of 17: wrist: watch: the hand tilts back at the wrist"),
        "{lines}"
    );
    until_asking(&mut c, t);
    assert_eq!(c.pose(t + 10.0), neutral, "held at neutral while asking");
}

#[test]
fn every_joint_confirmed_gives_a_verified_table() {
    let mut c = check(ETH_LAB);
    let mut t = 0.0;
    for k in 0..17 {
        t = until_asking(&mut c, t);
        assert!(c.verified_table("ana", "now").is_err());
        c.answer(Answer::Yes, t);
        assert_eq!(c.phase() == CheckPhase::Complete, k == 16);
    }
    let table = c.verified_table("ana", "2026-11-26T10:00:00Z").unwrap();
    assert!(table.joints.iter().all(|r| r.verified));
    assert_eq!(table.verified_by, "ana");
    assert_eq!(
        table.verification().line(),
        "eth_hand_control — verified by ana on 2026-11-26T10:00:00Z"
    );
    assert_eq!(c.progress(), "17 of 17 joints confirmed");
}

#[test]
fn no_then_flip_flips_the_sign_and_the_joint_must_be_confirmed_again() {
    let mut c = check(ETH_LAB);
    let t = until_asking(&mut c, 0.0);
    c.answer(Answer::Yes, t); // wrist
    let t = until_asking(&mut c, t); // thumb_mcp
    let before = c.command(t)[1];
    c.answer(Answer::No, t);
    assert_eq!(c.phase(), CheckPhase::OfferFlip);
    c.answer(Answer::Yes, t);
    assert_eq!(c.phase(), CheckPhase::OfferFlip, "yes does not flip");
    c.answer(Answer::Flip, t);
    assert_eq!(c.phase(), CheckPhase::Settling);
    assert!(c.joints()[1].flipped && !c.joints()[1].confirmed);
    let t = until_asking(&mut c, t);
    // thumb_mcp at neutral 0: the same value is sent; its step now goes the other way.
    assert_eq!(c.command(t)[1], before);
    c.answer(Answer::Repeat, t);
    assert_eq!(c.phase(), CheckPhase::Moving);
    let t = until_asking(&mut c, t);
    c.answer(Answer::Yes, t);
    assert_eq!(c.progress(), "joint 3 of 17: thumb_abd");
    c.answer(Answer::Quit, t);
    assert_eq!(c.phase(), CheckPhase::Quit);
    let e = c.verified_table("ana", "now").unwrap_err().to_string();
    assert!(
        e.starts_with("no table written: not confirmed: thumb_abd, thumb_pip, "),
        "{e}"
    );
    assert!(e.ends_with("pinky_pip"), "{e}");
}

#[test]
fn a_flipped_joint_is_written_with_its_new_sign_and_a_note() {
    let mut c = check(ORCA_CORE);
    let mut t = until_asking(&mut c, 0.0);
    c.answer(Answer::No, t);
    c.answer(Answer::Flip, t);
    for _ in 0..17 {
        t = until_asking(&mut c, t);
        c.answer(Answer::Yes, t);
    }
    assert_eq!(c.phase(), CheckPhase::Complete);
    let table = c.verified_table("ana", "T").unwrap();
    assert_eq!(table.joints[0].joint, "thumb_mcp");
    assert_eq!(table.joints[0].sign, -1);
    assert!(
        table.joints[0]
            .note
            .ends_with("sign flipped by pomdar hand-check (ana, T)")
    );
    assert_eq!(table.joints[1].sign, 1);
}

#[test]
fn options_outside_their_ranges_are_refused() {
    let config = StationConfig::from_toml_str(ETH_LAB).unwrap().policy_output;
    let model = HandModel::orca_v1_right();
    let refused = |motion: Motion| {
        HandCheck::new(model.clone(), config.clone(), motion, 0.0)
            .unwrap_err()
            .to_string()
    };
    assert_eq!(
        refused(Motion { step_rad: 0.3, ..M }),
        "--step-rad = 0.3 must be in (0, 0.15]"
    );
    assert_eq!(
        refused(Motion { move_s: 0.5, ..M }),
        "--move-s = 0.5 must be in [1, 10]"
    );
    let e = HandCheck::new(model, StationConfig::default().policy_output, M, 0.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("no joints table"), "{e}");
}
