//! Acceptance of the calibration on 50 seeded synthetic users (hand sizes 0.8–1.25×, glove
//! misaligned up to ±20° about each axis, 2 mm keypoint noise): see `calibration::Study` for
//! the definitions. Split in two halves so the two test threads share the work.

use calibration::{
    BuiltinInputs, CalibrationModel, CalibrationSettings, Study, SyntheticUser, UserOutcome,
};
use retarget::human_hand::HandVariation;

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

/// The per-digit model on hands whose thumb and index differ from the average hand's in
/// proportion (named hands, not the bench's random ones): it finds each digit's length
/// relative to the palm (a long thumb gets a factor below 1, a short index one above) and
/// lowers the held-out error the global model leaves. The global part is the same fit.
#[test]
fn the_per_digit_model_finds_a_long_thumb_and_a_short_index() {
    let builtin = BuiltinInputs::orca_v1();
    let study = Study::new(builtin.inputs()).unwrap();
    let per_digit = CalibrationSettings {
        model: CalibrationModel::PerDigit,
        ..builtin.settings.clone()
    };
    for (seed, thumb, index) in [(3, 1.12, 0.93), (4, 0.88, 1.08)] {
        let user = SyntheticUser {
            variation: HandVariation {
                thumb_length: thumb,
                index_length: index,
                ..HandVariation::NONE
            },
            ..SyntheticUser::random(seed)
        };
        let global = study.run_user(&user).unwrap();
        let digits = study.run_user_with(&user, &per_digit).unwrap();
        let factors = digits.calibration.transform.digit_scale;
        println!(
            "thumb {thumb} index {index}: factors {factors:.2?}; held-out global {:.3}, per digit {:.3} rad",
            global.held_out_after_rad, digits.held_out_after_rad
        );
        // A digit longer than the average maps shorter: the factor's side of 1 is the hand's.
        assert!((factors[0] - 1.0) * (thumb - 1.0) < 0.0, "{factors:?}");
        assert!((factors[1] - 1.0) * (index - 1.0) < 0.0, "{factors:?}");
        assert_eq!(digits.calibration.model, CalibrationModel::PerDigit);
        assert!(digits.calibration.after.value < global.calibration.after.value);
        assert!(
            digits.held_out_after_rad < global.held_out_after_rad,
            "held-out {:.3} per digit against {:.3} global",
            digits.held_out_after_rad,
            global.held_out_after_rad
        );
    }
}
