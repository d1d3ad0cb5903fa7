//! Benchmark: the calibration on users it never saw, through the live path.
//!
//! `cargo bench -p teleop --bench calibrated_users [-- --first-seed N --users N]` takes
//! synthetic users with hands of their own proportions (`SyntheticUser::random_non_uniform`:
//! thumb ±15 %, index and middle ±10 %, palm breadth ±10 %, the thumb's base moved, tip
//! markers ±5 mm; sizes 0.8–1.25×, the glove turned up to ±20° about each palm axis, 2 mm
//! capture noise), seeds 5000 on by default, which no setting was chosen on. For each user:
//! 1. the seven poses are captured and fitted with the global model and the per-digit one
//!    (`calibration::Study`, the fit `pomdar calibrate` runs), and each profile is written as
//!    `pomdar calibrate` writes it;
//! 2. the user's held-out motion (the four pinches in turn for 30 s at 25 Hz, 1 mm jitter;
//!    `calibration::held_out_pinches`) is written as a recording;
//! 3. the recording is re-simulated through the station as `pomdar eval --profile P` runs its
//!    live path, with no profile, the global one and the per-digit one, and each command is
//!    scored against the hand as held (and, for comparison, against the glove's report).
//!
//! Prints a line per user on stderr, then one JSON line per model: sustained pinch frames
//! closed (all and thumb–index), the fingertip error as held and as reported, how many users
//! each model served best, below the global model and below no calibration, and how many were
//! worse than uncalibrated on both tip error and pinches. A first line gives the floor: the
//! average hand in an aligned glove under the reference calibration.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a benchmark fails loudly

use std::path::{Path, PathBuf};

use calibration::{
    BuiltinInputs, Calibration, CalibrationModel, CalibrationProfile, CalibrationSettings,
    ProfileHeader, Study, SyntheticUser, held_out_pinches,
};
use retarget::{HandModel, QualityReport};
use teleop::eval::eval_set::write_recording;
use teleop::eval::live_path::{HandAsHeld, live_path_against};
use teleop::eval::variants::TimedFrame;
use teleop::mcap_log::TrialReader;
use teleop::station_driver::setup::load_station_config;

/// The first user's seed: users from here on were never looked at while choosing a setting.
const FIRST_SEED: u64 = 5000;
/// Users by default.
const USERS: u64 = 24;
/// The models compared, in the order of the reports: no profile, the two fitted models, the
/// global transform that is exact for the user's size and glove (`true_transform`; not a fit:
/// what the global model aims at), and that transform with each digit's length factor undone
/// exactly (thumb, index, middle from the user's hand; not a fit: what the per-digit model
/// aims at).
const MODELS: [&str; 5] = [
    "none",
    "global",
    "per_digit",
    "exact_global",
    "exact_per_digit",
];

fn arg(name: &str, default: u64) -> u64 {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .map_or(default, |v| v.parse().expect("a whole number"))
}

/// The live path's reports of `recording` under `profile`: against the hand as held, and
/// against the glove's report.
fn live(recording: &Path, profile: Option<&Path>, as_held: &HandAsHeld) -> [QualityReport; 2] {
    let config = load_station_config(None, profile).unwrap();
    let reader = TrialReader::open(recording).unwrap();
    let model = HandModel::orca_v1_right();
    let held = live_path_against(&reader, &config, model.clone(), Some(as_held)).unwrap();
    let reported = live_path_against(&reader, &config, model, None).unwrap();
    assert_eq!(
        held.frames_not_measured, 0,
        "a frame without the hand as held"
    );
    [held.quality, reported.quality]
}

/// Writes `calibration` as the profile `pomdar calibrate` would.
fn write_profile(path: &Path, builtin: &BuiltinInputs, user: u64, calibration: &Calibration) {
    let header = ProfileHeader {
        user: format!("synthetic-{user}"),
        date: "2026-11-30".into(),
        glove: "simulated".into(),
        source: "calibrated_users benchmark".into(),
    };
    let profile =
        CalibrationProfile::new(header, &builtin.model, builtin.config.layout, calibration);
    std::fs::write(path, profile.to_toml_string().unwrap()).unwrap();
}

/// The user's held-out motion written to `recording`; the hand as held by frame stamp.
fn write_motion(recording: &Path, user: &SyntheticUser, builtin: &BuiltinInputs) -> HandAsHeld {
    let frames = held_out_pinches(user, builtin.config.layout).unwrap();
    let reported: Vec<TimedFrame> = frames
        .iter()
        .map(|f| TimedFrame {
            t_ns: f.t_ns,
            points: f.reported.clone(),
        })
        .collect();
    let topic = load_station_config(None, None)
        .unwrap()
        .input
        .keypoints_topic;
    write_recording(recording, &topic, &reported).unwrap();
    frames.into_iter().map(|f| (f.t_ns, f.as_held)).collect()
}

/// One model's held-out motion over the users.
#[derive(Debug, Clone, Copy, Default)]
struct Tally {
    pinch_frames: usize,
    pinch_closed: usize,
    index_frames: usize,
    index_closed: usize,
    tip_held_mm: f64,
    tip_reported_mm: f64,
    best: usize,
    below_global: usize,
    below_none: usize,
    worse_than_none_on_both: usize,
}

/// Share of sustained pinch frames closed, all and thumb–index.
fn closed(report: &QualityReport) -> (usize, usize, usize, usize) {
    let index = report.pinch_pairs.iter().find(|p| p.finger == "index");
    (
        report.sustained_pinch_frames,
        report.sustained_pinch_closed_frames,
        index.map_or(0, |p| p.sustained_frames),
        index.map_or(0, |p| p.sustained_closed_frames),
    )
}

fn pct(part: usize, whole: usize) -> f64 {
    100.0 * part as f64 / whole.max(1) as f64
}

impl Tally {
    /// Adds model `k`'s reports of one user; `held` holds every model's report as held.
    fn add(&mut self, k: usize, held: &[QualityReport; 5], reported: &QualityReport) {
        let (frames, shut, index_frames, index_shut) = closed(&held[k]);
        self.pinch_frames += frames;
        self.pinch_closed += shut;
        self.index_frames += index_frames;
        self.index_closed += index_shut;
        let tips = held.each_ref().map(|r| r.tip_error_mean_mm);
        self.tip_held_mm += tips[k];
        self.tip_reported_mm += reported.tip_error_mean_mm;
        self.best += usize::from(tips[..3].iter().all(|&t| tips[k] <= t));
        self.below_global += usize::from(tips[k] < tips[1]);
        self.below_none += usize::from(tips[k] < tips[0]);
        let (none_frames, none_shut, _, _) = closed(&held[0]);
        let fewer_pinches = pct(shut, frames) < pct(none_shut, none_frames);
        self.worse_than_none_on_both += usize::from(k > 0 && tips[k] > tips[0] && fewer_pinches);
    }

    fn json(&self, model: &str, users: usize) -> String {
        let n = users.max(1) as f64;
        format!(
            "{{\"bench\":\"calibrated_users_live_path\",\"model\":\"{model}\",\"users\":{users},\"sustained_pinches_closed_pct\":{:.1},\"thumb_index_closed_pct\":{:.1},\"tip_error_as_held_mm\":{:.1},\"tip_error_as_reported_mm\":{:.1},\"users_best_of_the_three\":{},\"users_below_global\":{},\"users_below_none\":{},\"users_worse_than_none_on_both\":{}}}",
            pct(self.pinch_closed, self.pinch_frames),
            pct(self.index_closed, self.index_frames),
            self.tip_held_mm / n,
            self.tip_reported_mm / n,
            self.best,
            self.below_global,
            self.below_none,
            self.worse_than_none_on_both
        )
    }
}

/// The floor: the average hand in an aligned glove, calibrated as the reference user is.
fn floor(dir: &Path, builtin: &BuiltinInputs, study: &Study) {
    let user = SyntheticUser::reference();
    let recording = dir.join("reference.mcap");
    let as_held = write_motion(&recording, &user, builtin);
    let calibration = study.run_user(&user).unwrap().calibration;
    let profile = dir.join("reference.toml");
    write_profile(&profile, builtin, 0, &calibration);
    let [held, _] = live(&recording, Some(&profile), &as_held);
    println!(
        "{{\"bench\":\"calibrated_users_floor\",\"tip_error_as_held_mm\":{:.1},\"sustained_pinches_closed_pct\":{:.1}}}",
        held.tip_error_mean_mm,
        held.sustained_pinches_closed_pct.unwrap_or(f64::NAN)
    );
}

fn main() {
    let (first, count) = (arg("--first-seed", FIRST_SEED), arg("--users", USERS));
    let dir: PathBuf =
        std::env::temp_dir().join(format!("calibrated-users-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let builtin = BuiltinInputs::orca_v1();
    let study = Study::new(builtin.inputs()).unwrap();
    let per_digit = CalibrationSettings {
        model: CalibrationModel::PerDigit,
        ..builtin.settings.clone()
    };
    floor(&dir, &builtin, &study);
    let mut tally = [Tally::default(); 5];
    let mut users = 0usize;
    for seed in first..first + count {
        let user = SyntheticUser::random_non_uniform(seed);
        let Ok(global) = study.run_user(&user) else {
            eprintln!("user {seed}: a capture was refused (too much jitter): left out");
            continue;
        };
        let digits = study.run_user_with(&user, &per_digit).unwrap();
        let recording = dir.join(format!("user-{seed}.mcap"));
        let as_held = write_motion(&recording, &user, &builtin);
        let exact = Calibration {
            transform: global.truth,
            ..global.calibration.clone()
        };
        let v = &user.variation;
        let mut exact_digits = exact.clone();
        exact_digits.transform.digit_scale = [
            1.0 / v.thumb_length,
            1.0 / v.index_length,
            1.0 / v.middle_length,
            1.0,
            1.0,
        ];
        let profiles = [
            ("global", &global.calibration),
            ("per_digit", &digits.calibration),
            ("exact_global", &exact),
            ("exact_per_digit", &exact_digits),
        ]
        .map(|(name, calibration)| {
            let path = dir.join(format!("user-{seed}-{name}.toml"));
            write_profile(&path, &builtin, seed, calibration);
            Some(path)
        });
        let reports = [
            &None,
            &profiles[0],
            &profiles[1],
            &profiles[2],
            &profiles[3],
        ]
        .map(|p| live(&recording, p.as_deref(), &as_held));
        let held = reports.each_ref().map(|[held, _]| held.clone());
        for (k, [_, reported]) in reports.iter().enumerate() {
            tally[k].add(k, &held, reported);
        }
        users += 1;
        eprintln!(
            "user {seed} ({}, {:.2}x): tip error as held none {:.1} global {:.1} per-digit {:.1} exact global {:.1} exact per-digit {:.1} mm; sustained pinches closed {:.1} / {:.1} / {:.1} / {:.1} / {:.1} %",
            user.variation.label(),
            user.hand_scale,
            held[0].tip_error_mean_mm,
            held[1].tip_error_mean_mm,
            held[2].tip_error_mean_mm,
            held[3].tip_error_mean_mm,
            held[4].tip_error_mean_mm,
            held[0].sustained_pinches_closed_pct.unwrap_or(f64::NAN),
            held[1].sustained_pinches_closed_pct.unwrap_or(f64::NAN),
            held[2].sustained_pinches_closed_pct.unwrap_or(f64::NAN),
            held[3].sustained_pinches_closed_pct.unwrap_or(f64::NAN),
            held[4].sustained_pinches_closed_pct.unwrap_or(f64::NAN),
        );
    }
    for (k, model) in MODELS.iter().enumerate() {
        println!("{}", tally[k].json(model, users));
    }
    std::fs::remove_dir_all(&dir).ok();
}
