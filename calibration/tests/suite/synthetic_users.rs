//! Acceptance of the calibration on 50 seeded synthetic users (hand sizes 0.8–1.25×, glove
//! misaligned up to ±20° about each axis, 2 mm keypoint noise): see `calibration::Study` for
//! the definitions. Split in two halves so the two test threads share the work.

use calibration::{BuiltinInputs, Study, SyntheticUser, UserOutcome};

const USERS: u64 = 50;

fn outcomes(seeds: std::ops::Range<u64>) -> Vec<UserOutcome> {
    let builtin = BuiltinInputs::orca_v1();
    let study = Study::new(builtin.inputs()).unwrap();
    seeds
        .map(|seed| {
            let outcome = study.run_user(&SyntheticUser::random(seed)).unwrap();
            println!(
                "user {seed:2}: hand {:.3} scale {:.3} vs {:.3} ({:+.1} %), rotation off {:.2}°, \
                 held-out {:.3} -> {:.3} rad",
                outcome.user.hand_scale,
                outcome.calibration.transform.scale,
                outcome.truth.scale,
                outcome.scale_error * 100.0,
                outcome.rotation_error_deg,
                outcome.held_out_before_rad,
                outcome.held_out_after_rad
            );
            outcome
        })
        .collect()
}

fn check(outcomes: &[UserOutcome]) {
    let n = outcomes.len() as f64;
    let scale_ok = outcomes
        .iter()
        .filter(|o| o.scale_error.abs() <= 0.03)
        .count() as f64;
    let both_ok = outcomes
        .iter()
        .filter(|o| o.scale_error.abs() <= 0.03 && o.rotation_error_deg <= 3.0)
        .count() as f64;
    let before: f64 = outcomes
        .iter()
        .map(|o| o.held_out_before_rad.powi(2))
        .sum::<f64>()
        / n;
    let after: f64 = outcomes
        .iter()
        .map(|o| o.held_out_after_rad.powi(2))
        .sum::<f64>()
        / n;
    let cut = 1.0 - after.sqrt() / before.sqrt();
    println!(
        "scale within 3 %: {:.0} %; scale and rotation within 3 % / 3°: {:.0} %; held-out RMS \
         {:.3} -> {:.3} rad (cut {:.0} %)",
        100.0 * scale_ok / n,
        100.0 * both_ok / n,
        before.sqrt(),
        after.sqrt(),
        100.0 * cut
    );
    assert!(scale_ok / n >= 0.9, "scale recovered for too few users");
    assert!(
        both_ok / n >= 0.9,
        "scale and rotation recovered for too few users"
    );
    assert!(
        cut >= 0.5,
        "held-out error cut by only {:.0} %",
        100.0 * cut
    );
    for o in outcomes {
        assert!(
            o.calibration.after.value <= o.calibration.before.value,
            "the fit never ends worse than no calibration"
        );
    }
}

#[test]
fn first_half_of_the_users() {
    check(&outcomes(0..USERS / 2));
}

#[test]
fn second_half_of_the_users() {
    check(&outcomes(USERS / 2..USERS));
}
