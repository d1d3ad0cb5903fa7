//! Benchmark: the calibration on the 50 seeded synthetic users of the acceptance test.
//!
//! `cargo bench -p calibration --bench calibration` prints, one JSON line each:
//! - the wall time of one calibration (seven captures already taken: objective, 60 Bayesian
//!   + 2 × 40 polish evaluations), p50 and max over the users;
//! - recovery: the share of users whose scale is within 3 % and rotation within 3° of the
//!   truth, and the held-out joint RMS error without and with calibration (see
//!   `calibration::Study`);
//! - the same on users whose hands also have their own proportions
//!   (`SyntheticUser::random_non_uniform`: thumb ±15 %, index and middle ±10 %, palm breadth
//!   ±10 %, thumb base moved, tip markers ±5 mm), for which the global scale and rotation
//!   cannot be exact (the truth is the one for the user's size and glove);
//! - Bayesian optimisation against random search with the same 60 evaluations: the median
//!   over users of the best objective each found, and how many users each won.
//!
//! `-- models` compares the global and the per-digit model instead (their held-out motion
//! through the station: `cargo bench -p teleop --bench calibrated_users`); `-- fit_check` measures
//! the check of the fitted poses (see `fit_check/mod.rs`).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a benchmark fails loudly

use std::time::Instant;

use calibration::{
    BuiltinInputs, CalibrationModel, CalibrationSettings, Study, SyntheticUser, calibrate,
};

mod fit_check;

const USERS: u64 = 50;
/// Users of the model comparison.
const COMPARED_USERS: u64 = 24;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Recovery and held-out error on the users with hands of their own proportions.
fn non_uniform_recovery() {
    let builtin = BuiltinInputs::orca_v1();
    let study = Study::new(builtin.inputs()).unwrap();
    let (mut recovered, mut before, mut after, mut scale_errors) = (0usize, 0.0, 0.0, Vec::new());
    for seed in 0..USERS {
        let outcome = study
            .run_user(&SyntheticUser::random_non_uniform(seed))
            .unwrap();
        if outcome.scale_error.abs() <= 0.03 && outcome.rotation_error_deg <= 3.0 {
            recovered += 1;
        }
        scale_errors.push(outcome.scale_error.abs());
        before += outcome.held_out_before_rad.powi(2);
        after += outcome.held_out_after_rad.powi(2);
        eprint!("\rnon-uniform user {}/{USERS}", seed + 1);
    }
    eprintln!();
    let n = USERS as f64;
    println!(
        "{{\"bench\":\"calibration_recovery_non_uniform\",\"users\":{USERS},\"within_3pct_3deg\":{:.2},\"median_scale_error\":{:.3},\"held_out_before_rad\":{:.3},\"held_out_after_rad\":{:.3},\"cut\":{:.2}}}",
        recovered as f64 / n,
        median(scale_errors),
        (before / n).sqrt(),
        (after / n).sqrt(),
        1.0 - (after / before).sqrt()
    );
}

/// Global against per-digit on the same non-uniform users: held-out joint error and the
/// calibration poses' pinch-gap error, and how many users each model served better.
fn model_comparison() {
    let builtin = BuiltinInputs::orca_v1();
    let study = Study::new(builtin.inputs()).unwrap();
    let per_digit = CalibrationSettings {
        model: CalibrationModel::PerDigit,
        ..builtin.settings.clone()
    };
    let gap_mm = |o: &calibration::UserOutcome| {
        let gaps: Vec<f64> = o
            .calibration
            .after
            .poses
            .iter()
            .filter_map(|p| p.pinch_gap_error_m)
            .collect();
        1e3 * gaps.iter().sum::<f64>() / gaps.len() as f64
    };
    let (mut g_sq, mut d_sq, mut none_sq, mut d_wins, mut g_gap, mut d_gap) =
        (0.0, 0.0, 0.0, 0, 0.0, 0.0);
    let mut users = 0usize;
    for seed in 0..COMPARED_USERS {
        let user = SyntheticUser::random_non_uniform(1000 + seed);
        let Ok(g) = study.run_user(&user) else {
            eprintln!("user {seed}: a capture was refused (too much jitter): left out");
            continue;
        };
        let d = study.run_user_with(&user, &per_digit).unwrap();
        none_sq += g.held_out_before_rad.powi(2);
        g_sq += g.held_out_after_rad.powi(2);
        d_sq += d.held_out_after_rad.powi(2);
        d_wins += usize::from(d.held_out_after_rad < g.held_out_after_rad);
        g_gap += gap_mm(&g);
        d_gap += gap_mm(&d);
        users += 1;
        eprintln!(
            "user {seed}: {} held-out none {:.3} global {:.3} per-digit {:.3} rad; pinch gap error global {:.1} per-digit {:.1} mm; factors {:?}",
            user.variation.label(),
            g.held_out_before_rad,
            g.held_out_after_rad,
            d.held_out_after_rad,
            gap_mm(&g),
            gap_mm(&d),
            d.calibration
                .transform
                .digit_scale
                .map(|f| (f * 100.0).round() / 100.0)
        );
    }
    let n = users as f64;
    println!(
        "{{\"bench\":\"calibration_models_non_uniform\",\"users\":{users},\"held_out_none_rad\":{:.3},\"held_out_global_rad\":{:.3},\"held_out_per_digit_rad\":{:.3},\"per_digit_better\":{d_wins},\"pinch_gap_error_global_mm\":{:.2},\"pinch_gap_error_per_digit_mm\":{:.2}}}",
        (none_sq / n).sqrt(),
        (g_sq / n).sqrt(),
        (d_sq / n).sqrt(),
        g_gap / n,
        d_gap / n
    );
}

fn main() {
    if std::env::args().any(|a| a == "models") {
        model_comparison();
        return;
    }
    if std::env::args().any(|a| a == "fit_check") {
        fit_check::run();
        return;
    }
    let builtin = BuiltinInputs::orca_v1();
    let (inputs, settings) = (builtin.inputs(), &builtin.settings);
    let study = Study::new(inputs).unwrap();

    let mut times = Vec::new();
    let (mut recovered, mut before, mut after) = (0usize, 0.0, 0.0);
    let (mut bayes, mut random, mut bayes_wins) = (Vec::new(), Vec::new(), 0usize);
    for seed in 0..USERS {
        let user = SyntheticUser::random(seed);
        let captures = study.captures(&user).unwrap();
        let start = Instant::now();
        std::hint::black_box(calibrate(inputs, &captures, &mut |_| {}, &|| false).unwrap());
        times.push(start.elapsed().as_secs_f64());
        let outcome = study.run_user(&user).unwrap();
        if outcome.scale_error.abs() <= 0.03 && outcome.rotation_error_deg <= 3.0 {
            recovered += 1;
        }
        before += outcome.held_out_before_rad.powi(2);
        after += outcome.held_out_after_rad.powi(2);
        let (b, r) = study.bayes_vs_random(&user).unwrap();
        bayes_wins += usize::from(b < r);
        bayes.push(b);
        random.push(r);
        eprint!("\ruser {}/{USERS}", seed + 1);
    }
    eprintln!();
    let n = USERS as f64;
    let max = times.iter().copied().fold(0.0, f64::max);
    println!(
        "{{\"bench\":\"calibration_time\",\"users\":{USERS},\"evaluations\":{},\"p50_s\":{:.3},\"max_s\":{:.3}}}",
        settings.optimiser.evaluations + 2 * settings.optimiser.polish_evaluations,
        median(times),
        max
    );
    println!(
        "{{\"bench\":\"calibration_recovery\",\"users\":{USERS},\"within_3pct_3deg\":{:.2},\"held_out_before_rad\":{:.3},\"held_out_after_rad\":{:.3},\"cut\":{:.2}}}",
        recovered as f64 / n,
        (before / n).sqrt(),
        (after / n).sqrt(),
        1.0 - (after / before).sqrt()
    );
    non_uniform_recovery();
    println!(
        "{{\"bench\":\"bayes_vs_random\",\"users\":{USERS},\"evaluations\":{},\"median_best_bayes_rad\":{:.4},\"median_best_random_rad\":{:.4},\"bayes_wins\":{bayes_wins}}}",
        settings.optimiser.evaluations,
        median(bayes),
        median(random)
    );
}
