//! `cargo bench -p calibration --bench calibration -- fit_check`: the check of the fitted poses
//! ([`calibration::FitCheck`]) on synthetic users.
//!
//! - **Well-held sessions**: the largest per-pose error after the fit (joint RMS, pinch gap)
//!   of each user; how many users the check names a pose of (a false alarm).
//! - **One pose held wrongly**: the user stays in the previous pose (the first pose: in the
//!   open hand) while pose k is captured; how often the check names pose k first.
//!
//! Two sets of users, uniform and non-uniform hands each: the one the limits were chosen on
//! (seeds from 0) and a held-out one (seeds from 3000).

use calibration::{
    BuiltinInputs, CalibrationProfile, CapturedPose, FitCheck, POSE_NAMES, ProfileHeader, Study,
    SyntheticUser, calibrate, poses_that_do_not_fit, wrongly_held_pose,
};

/// Users per set and kind of hand for the well-held sessions.
const USERS: u64 = 20;
/// Users per set and kind of hand for each wrongly held pose.
const WRONG_USERS: u64 = 6;

/// The profile of a fit of `captures` with the built-in settings.
fn profile(builtin: &BuiltinInputs, captures: &[CapturedPose]) -> CalibrationProfile {
    let calibration = calibrate(builtin.inputs(), captures, &mut |_| {}, &|| false).unwrap();
    let header = ProfileHeader {
        user: "bench".into(),
        date: String::new(),
        glove: String::new(),
        source: String::new(),
    };
    CalibrationProfile::new(header, &builtin.model, builtin.config.layout, &calibration)
}

fn user(uniform: bool, seed: u64) -> SyntheticUser {
    if uniform {
        SyntheticUser::random(seed)
    } else {
        SyntheticUser::random_non_uniform(seed)
    }
}

/// Well-held sessions of one set: (largest joint RMS after, largest pinch gap after, users
/// with a pose named).
fn well_held(
    builtin: &BuiltinInputs,
    study: &Study,
    first_seed: u64,
    uniform: bool,
) -> (Vec<f64>, Vec<f64>, usize) {
    let check = builtin.settings.fit_check;
    let (mut rms, mut gap, mut named) = (Vec::new(), Vec::new(), 0);
    for seed in first_seed..first_seed + USERS {
        let Ok(captures) = study.captures(&user(uniform, seed)) else {
            continue;
        };
        let p = profile(builtin, &captures);
        rms.push(
            p.poses
                .iter()
                .map(|r| r.joint_rms_after_rad)
                .fold(0.0, f64::max),
        );
        gap.push(
            p.poses
                .iter()
                .filter_map(|r| r.pinch_gap_after_mm)
                .fold(0.0, f64::max),
        );
        let misfits = poses_that_do_not_fit(&p.poses, &builtin.poses, &check);
        if let Some(m) = misfits.first() {
            named += 1;
            eprintln!("  false alarm, seed {seed}: {}", m.sentence());
        }
    }
    (rms, gap, named)
}

/// One pose held wrongly, per pose: (sessions, sessions whose first named pose is it).
fn wrongly_held(
    builtin: &BuiltinInputs,
    study: &Study,
    first_seed: u64,
    uniform: bool,
) -> Vec<(usize, usize)> {
    let check: FitCheck = builtin.settings.fit_check;
    (0..POSE_NAMES.len())
        .map(|k| {
            let (mut sessions, mut found) = (0, 0);
            for seed in first_seed..first_seed + WRONG_USERS {
                let Ok(mut captures) = study.captures(&user(uniform, seed)) else {
                    continue;
                };
                captures[k].keypoints = captures[wrongly_held_pose(k)].keypoints.clone();
                let p = profile(builtin, &captures);
                let misfits = poses_that_do_not_fit(&p.poses, &builtin.poses, &check);
                sessions += 1;
                let first = misfits.first();
                if first.is_some_and(|m| m.index == k) {
                    found += 1;
                } else {
                    eprintln!(
                        "  {} held as {}, seed {seed}: {}",
                        POSE_NAMES[k],
                        POSE_NAMES[wrongly_held_pose(k)],
                        first.map_or("nothing named".to_string(), |m| m.sentence())
                    );
                }
            }
            (sessions, found)
        })
        .collect()
}

fn quantile(mut v: Vec<f64>, q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

/// Runs the measurement and prints one JSON line per set and kind of hand.
pub fn run() {
    let builtin = BuiltinInputs::orca_v1();
    let study = Study::new(builtin.inputs()).unwrap();
    for (set, first_seed) in [("chosen_on", 0), ("held_out", 3000)] {
        for uniform in [true, false] {
            let hands = if uniform { "uniform" } else { "non_uniform" };
            eprintln!("{set} {hands}: well-held sessions");
            let (rms, gap, named) = well_held(&builtin, &study, first_seed, uniform);
            eprintln!("{set} {hands}: one pose held wrongly");
            let per_pose = wrongly_held(&builtin, &study, first_seed, uniform);
            let found: Vec<String> = POSE_NAMES
                .iter()
                .zip(&per_pose)
                .map(|(name, (n, f))| format!("\"{name}\":\"{f}/{n}\""))
                .collect();
            println!(
                "{{\"bench\":\"fit_check\",\"users\":\"{set}\",\"hands\":\"{hands}\",\"well_held\":{},\"false_alarms\":{named},\"joint_rms_after_max_p50_rad\":{:.3},\"joint_rms_after_max_max_rad\":{:.3},\"pinch_gap_after_max_p50_mm\":{:.1},\"pinch_gap_after_max_max_mm\":{:.1},\"wrong_pose_named_first\":{{{}}}}}",
                rms.len(),
                quantile(rms.clone(), 0.5),
                quantile(rms, 1.0),
                quantile(gap.clone(), 0.5),
                quantile(gap, 1.0),
                found.join(",")
            );
        }
    }
}
