//! `pomdar baseline` and `pomdar score` as the operator runs them (the built binary), on
//! real MCAP trial files written the way the station writes them (keypoints, joint targets,
//! the metadata record, hand-made events), plus malformed ones: each bad file is named with
//! its reason, the others are scored with the expected values, and every report file and
//! figure is written and sane.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Output;
use std::sync::OnceLock;

use pomdar_tests::pomdar_binary::run_pomdar as pomdar;
use serde_json::{Value, json};
use teleop::score::synthetic_trial::{SyntheticTrial, write_synthetic_trial};

const T0_NS: i64 = 1_732_100_000_000_000_000;

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pomdar-score-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Writes a 3 s-or-longer trial (keypoints at 100 Hz, joint targets at 25 Hz) with `events`
/// (seconds after the first message).
fn write(
    path: &Path,
    task: &str,
    embodiment: &str,
    practice: bool,
    user: &str,
    events: &[(f64, Value)],
) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    let last = events.iter().map(|(t, _)| *t).fold(3.0, f64::max);
    let trial = SyntheticTrial {
        metadata: BTreeMap::from([
            ("task".into(), task.into()),
            ("embodiment".into(), embodiment.into()),
            ("practice".into(), practice.to_string()),
            ("user".into(), user.into()),
            ("operator".into(), "op".into()),
            ("trial_index".into(), "1".into()),
        ]),
        t0_ns: T0_NS,
        duration_s: last,
        events: events.to_vec(),
        keypoint_rate_hz: 100.0,
        joint_rate_hz: 25.0,
        seed: 3,
    };
    write_synthetic_trial(path, &trial).unwrap();
}

fn start(t: f64) -> (f64, Value) {
    (t, json!({"event": "start"}))
}
fn stop(t: f64) -> (f64, Value) {
    (t, json!({"event": "stop", "summary": {"frames": 1}}))
}
fn progress(t: f64, v: f64) -> (f64, Value) {
    (t, json!({"event": "progress", "value": v}))
}

struct Set {
    dir: PathBuf,
    baseline: PathBuf,
    baseline_run: Output,
}

/// Human: V1 in 10 s and 12 s, C1 in 20 s, G2 in 8 s; one practice trial (left out).
fn write_human_trials(h: &Path) {
    write(
        &h.join("v1_a.mcap"),
        "V1",
        "human",
        false,
        "ann",
        &[start(0.5), progress(5.0, 6.0), stop(10.5)],
    );
    write(
        &h.join("v1_b.mcap"),
        "V1",
        "human",
        false,
        "bob",
        &[start(0.5), progress(5.0, 6.0), stop(12.5)],
    );
    write(
        &h.join("v1_p.mcap"),
        "V1",
        "human",
        true,
        "bob",
        &[start(0.5), stop(30.5)],
    );
    write(
        &h.join("c1.mcap"),
        "C1",
        "human",
        false,
        "ann",
        &[start(1.0), progress(9.0, 360.0), stop(21.0)],
    );
    write(
        &h.join("g2.mcap"),
        "G2",
        "human",
        false,
        "bob",
        &[
            start(1.0),
            progress(3.0, 0.5),
            progress(6.0, 1.0),
            stop(9.0),
        ],
    );
}

/// Good: V1 4/6 notches in 22 s; C1 270° in 40 s; G2 relocated in 16 s; H2 (no baseline)
/// 2/3 curves; a practice V1.
fn write_good_robot_trials(t: &Path) {
    write(
        &t.join("orca_full/v1.mcap"),
        "V1",
        "orca_full",
        false,
        "ann",
        &[
            start(1.0),
            progress(4.0, 1.0),
            progress(8.0, 1.0),
            progress(12.0, 1.0),
            progress(16.0, 1.0),
            (18.0, json!({"event": "note", "text": "glove re-seated"})),
            stop(23.0),
        ],
    );
    write(
        &t.join("orca_full/c1.mcap"),
        "C1",
        "orca_full",
        false,
        "ann",
        &[
            start(2.0),
            progress(10.0, 180.0),
            progress(30.0, 90.0),
            stop(42.0),
        ],
    );
    write(
        &t.join("orca_5/g2.mcap"),
        "G2",
        "orca_5",
        false,
        "ann",
        &[
            start(1.0),
            progress(5.0, 0.5),
            (7.0, json!({"event": "drop"})),
            progress(10.0, 0.5),
            progress(14.0, 1.0),
            stop(17.0),
        ],
    );
    write(
        &t.join("orca_5/h2.mcap"),
        "H2",
        "orca_5",
        false,
        "ann",
        &[
            start(1.0),
            progress(3.0, 1.0),
            progress(6.0, 1.0),
            stop(9.0),
        ],
    );
    write(
        &t.join("orca_full/v1_practice.mcap"),
        "V1",
        "orca_full",
        true,
        "ann",
        &[start(1.0), stop(4.0)],
    );
}

/// Bad: no start; no stop; out of order; unknown task; a finished file cut short; an
/// unfinished recording (.part).
fn write_bad_robot_trials(t: &Path) {
    let bad = t.join("bad");
    write(
        &bad.join("missing_start.mcap"),
        "V2",
        "orca_full",
        false,
        "ann",
        &[progress(1.0, 1.0), stop(5.0)],
    );
    write(
        &bad.join("missing_stop.mcap"),
        "V2",
        "orca_full",
        false,
        "ann",
        &[start(1.0), progress(2.0, 1.0)],
    );
    write(
        &bad.join("out_of_order.mcap"),
        "V2",
        "orca_full",
        false,
        "ann",
        &[
            start(1.0),
            progress(5.0, 1.0),
            progress(3.0, 1.0),
            stop(9.0),
        ],
    );
    write(
        &bad.join("unknown_task.mcap"),
        "Z9",
        "orca_full",
        false,
        "ann",
        &[start(1.0), stop(5.0)],
    );
    let whole = bad.join("whole.mcap");
    write(
        &whole,
        "V3",
        "orca_full",
        false,
        "ann",
        &[start(1.0), stop(5.0)],
    );
    let bytes = std::fs::read(&whole).unwrap();
    std::fs::write(bad.join("truncated.mcap"), &bytes[..bytes.len() * 3 / 5]).unwrap();
    // A decompression bomb: every chunk declares 1 GiB uncompressed.
    let mut bomb = bytes.clone();
    let summary = mcap::Summary::read(&bytes).unwrap().unwrap();
    for chunk in &summary.chunk_indexes {
        let at = chunk.chunk_start_offset as usize + 9 + 16;
        bomb[at..at + 8].copy_from_slice(&(1u64 << 30).to_le_bytes());
    }
    std::fs::write(bad.join("bomb.mcap"), &bomb).unwrap();
    std::fs::remove_file(&whole).unwrap();
    std::fs::write(
        t.join("orca_5/interrupted.mcap.part"),
        &bytes[..bytes.len() / 2],
    )
    .unwrap();
}

/// The human trials, the baseline computed from them, and the robot trials (once per test
/// process).
fn set() -> &'static Set {
    static SET: OnceLock<Set> = OnceLock::new();
    SET.get_or_init(|| {
        let dir = scratch();
        let _ = std::fs::remove_dir_all(dir.join("human"));
        let _ = std::fs::remove_dir_all(dir.join("trials"));
        let h = dir.join("human");
        write_human_trials(&h);
        let baseline = dir.join("baseline.toml");
        let _ = std::fs::remove_file(&baseline);
        let baseline_run = pomdar(&[
            "baseline",
            s(&h),
            "--source",
            "score_cli test: hand-made human trials",
            "--out",
            s(&baseline),
        ]);

        let t = dir.join("trials");
        write_good_robot_trials(&t);
        write_bad_robot_trials(&t);
        Set {
            dir,
            baseline,
            baseline_run,
        }
    })
}

fn close(a: f64, b: f64, what: &str) {
    assert!((a - b).abs() < 1e-6, "{what}: {a} != {b}");
}

#[test]
fn the_baseline_is_computed_from_human_trials() {
    let set = set();
    assert!(set.baseline_run.status.success(), "pomdar baseline failed");
    let text = std::fs::read_to_string(&set.baseline).unwrap();
    let table: toml::Value = toml::from_str(&text).unwrap();
    assert_eq!(table["baseline"]["example"].as_bool(), Some(false));
    let source = table["baseline"]["source"].as_str().unwrap();
    assert!(source.starts_with("score_cli test: hand-made human trials; pomdar baseline over 4 recorded human trials (users: ann, bob)"), "{source}");
    let rows = table["task"].as_array().unwrap();
    let order: Vec<&str> = rows.iter().map(|t| t["id"].as_str().unwrap()).collect();
    assert_eq!(
        order,
        ["V1", "C1", "G2"],
        "catalog order, tasks without human trials absent"
    );
    let tasks: BTreeMap<&str, &toml::Value> = rows
        .iter()
        .map(|t| (t["id"].as_str().unwrap(), t))
        .collect();
    assert_eq!(tasks["V1"]["mean_s"].as_float(), Some(11.0));
    assert_eq!(tasks["V1"]["n"].as_integer(), Some(2));
    assert_eq!(tasks["V1"]["std_s"].as_float(), Some(1.414));
    assert_eq!(tasks["C1"]["mean_s"].as_float(), Some(20.0));
    assert_eq!(tasks["G2"]["mean_s"].as_float(), Some(8.0));
    assert!(tasks["G2"].get("std_s").is_none());
    let stderr = String::from_utf8_lossy(&set.baseline_run.stderr);
    assert!(stderr.contains("v1_p.mcap: practice trial"), "{stderr}");
}

#[test]
fn a_robot_trial_is_refused_for_the_baseline_by_name() {
    let set = set();
    let out = set.dir.join("refused_baseline.toml");
    let _ = std::fs::remove_file(&out);
    let robot = set.dir.join("trials/orca_full/v1.mcap");
    let output = pomdar(&[
        "baseline",
        s(&set.dir.join("human")),
        s(&robot),
        "--out",
        s(&out),
    ]);
    assert_eq!(output.status.code(), Some(3));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains(&format!(
            "error: refused {}: embodiment \"orca_full\", not \"human\"",
            robot.display()
        )),
        "{stderr}"
    );
    // The table is still written from the human trials; an existing file is not replaced.
    assert!(out.exists());
    let again = pomdar(&["baseline", s(&set.dir.join("human")), "--out", s(&out)]);
    assert_eq!(again.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&again.stderr).contains("give --overwrite"));
}

#[test]
fn the_baseline_reports_the_study_per_participant_and_flags_tasks_with_few_trials() {
    let set = set();
    // The default minimum is the POMDAR study's 18 trials per task: every task is flagged,
    // with a warning, and the run still succeeds.
    assert!(set.baseline_run.status.success(), "pomdar baseline failed");
    let stderr = String::from_utf8_lossy(&set.baseline_run.stderr);
    assert!(
        stderr.contains("warning: task V1: 2 trials < --min-trials 18"),
        "{stderr}"
    );
    let stdout = String::from_utf8_lossy(&set.baseline_run.stdout);
    assert!(stdout.contains("FEW: 2 trials < minimum 18"), "{stdout}");
    let text = std::fs::read_to_string(&set.baseline).unwrap();
    let table: toml::Value = toml::from_str(&text).unwrap();
    let v1 = &table["task"].as_array().unwrap()[0];
    assert_eq!(v1["participants"].as_integer(), Some(2), "{text}");

    let out = set.dir.join("study_baseline.toml");
    let report = set.dir.join("study.md");
    let _ = std::fs::remove_file(&out);
    let _ = std::fs::remove_file(&report);
    let human = set.dir.join("human");
    let args = [
        "baseline",
        s(&human),
        "--out",
        s(&out),
        "--min-trials",
        "2",
        "--report",
        s(&report),
    ];
    let output = pomdar(&args);
    assert!(output.status.success(), "{output:?}");
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    let row = |id: &str| {
        stdout
            .lines()
            .find(|l| l.starts_with(id))
            .unwrap()
            .to_string()
    };
    assert!(
        row("V1 ").contains("  11.000    1.414   10.000   12.000"),
        "{stdout}"
    );
    assert!(!row("V1 ").contains("FEW"), "{stdout}");
    assert!(
        row("C1 ").ends_with("FEW: 1 trials < minimum 2"),
        "{stdout}"
    );
    assert!(
        stderr.contains("warning: task C1: 1 trials < --min-trials 2"),
        "{stderr}"
    );
    assert!(!stderr.contains("warning: task V1"), "{stderr}");
    let listing = stdout
        .split("trial times per participant × task")
        .nth(1)
        .unwrap();
    assert!(
        listing.contains("\nV1    ann        #1 10.000\n      bob        #1 12.000\n"),
        "{stdout}"
    );
    let md = std::fs::read_to_string(&report).unwrap();
    assert!(md.contains("| V1 | bob | 1 | #1 12.000 |"), "{md}");
    assert!(md.contains("| **FEW: 1 trials < minimum 2** |"), "{md}");
    assert!(md.contains("v1_p.mcap | practice trial |"), "{md}");

    // An existing report is not replaced without --overwrite; a bad minimum is refused.
    std::fs::remove_file(&out).unwrap();
    let again = pomdar(&args);
    assert_eq!(again.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&again.stderr);
    assert!(
        stderr.contains(&format!("{} exists: give --overwrite", report.display())),
        "{stderr}"
    );
    assert!(
        !out.exists(),
        "nothing is written when the report would be replaced"
    );
    let zero = pomdar(&["baseline", s(&human), "--out", s(&out), "--min-trials", "0"]);
    assert_eq!(zero.status.code(), Some(2), "{zero:?}");
    assert!(!out.exists());
}

fn png_is_sane(path: &Path) {
    let bytes = std::fs::read(path).unwrap();
    assert!(
        bytes.len() > 5_000,
        "{} is only {} bytes",
        path.display(),
        bytes.len()
    );
    let pixmap = tiny_skia::Pixmap::decode_png(&bytes).unwrap();
    assert!(
        pixmap.width() >= 400 && pixmap.height() >= 300,
        "{}",
        path.display()
    );
    let first = pixmap.pixels()[0];
    let inked = pixmap.pixels().iter().filter(|p| **p != first).count();
    assert!(
        inked * 100 > pixmap.pixels().len(),
        "{} is blank",
        path.display()
    );
    let colours: std::collections::BTreeSet<(u8, u8, u8)> = pixmap
        .pixels()
        .iter()
        .map(|p| (p.red(), p.green(), p.blue()))
        .collect();
    assert!(
        colours.len() > 10,
        "{}: {} colours",
        path.display(),
        colours.len()
    );
}

/// Each bad file is named on stderr with its reason; the interrupted recording is skipped
/// with a note; the totals line counts them.
fn assert_bad_files_named(stderr: &str, trials: &Path) {
    let bad = trials.join("bad");
    for (file, reason) in [
        ("missing_start.mcap", "missing start event"),
        ("missing_stop.mcap", "missing stop event"),
        (
            "out_of_order.mcap",
            "events out of order: event 3 (progress, +2.000 s) is earlier than event 2 (progress, +4.000 s)",
        ),
        ("unknown_task.mcap", "unknown task \"Z9\""),
        ("truncated.mcap", "truncated file"),
        (
            "bomb.mcap",
            "declares 1073741824 bytes uncompressed, over the limit of 67108864 bytes (64 MiB) per chunk",
        ),
    ] {
        let line = format!("error: {}: ", bad.join(file).display());
        let found = stderr.lines().find(|l| l.starts_with(&line));
        assert!(
            found.is_some_and(|l| l.contains(reason)),
            "{file}: expected {reason:?} in\n{stderr}"
        );
    }
    assert!(stderr.contains("truncated file") && stderr.contains("pomdar recover"));
    assert!(stderr.contains("note: skipped") && stderr.contains("interrupted.mcap.part"));
    assert!(
        stderr.contains("scored 5 of 11 trial files (6 rejected, 1 skipped)"),
        "{stderr}"
    );
}

/// The trial in `scores.json` whose file name ends with `name`.
fn scored_trial(json: &Value, name: &str) -> Value {
    json["trials"]
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["file"].as_str().unwrap().ends_with(name))
        .unwrap_or_else(|| panic!("{name} not scored"))
        .clone()
}

/// Each good trial's time, correctness and score in `scores.json`, as worked out by hand
/// from its events and the human baseline.
fn assert_trial_scores(json: &Value) {
    let v1 = scored_trial(json, "orca_full/v1.mcap");
    close(v1["time_s"].as_f64().unwrap(), 22.0, "V1 time");
    close(
        v1["correctness"].as_f64().unwrap(),
        4.0 / 6.0,
        "V1 correctness",
    );
    close(
        v1["score"].as_f64().unwrap(),
        0.8 * 4.0 / 6.0 + 0.2 * 11.0 / 22.0,
        "V1 score",
    );
    let c1 = scored_trial(json, "orca_full/c1.mcap");
    close(c1["correctness"].as_f64().unwrap(), 0.75, "C1 correctness");
    close(
        c1["score"].as_f64().unwrap(),
        0.8 * 0.75 + 0.2 * 20.0 / 40.0,
        "C1 score",
    );
    let g2 = scored_trial(json, "orca_5/g2.mcap");
    close(
        g2["correctness"].as_f64().unwrap(),
        1.0,
        "G2 relocated after a drop",
    );
    close(
        g2["score"].as_f64().unwrap(),
        0.8 + 0.2 * 8.0 / 16.0,
        "G2 score",
    );
    let h2 = scored_trial(json, "orca_5/h2.mcap");
    assert!(
        h2["score"].is_null(),
        "H2 has no baseline: correctness only"
    );
    close(
        h2["correctness"].as_f64().unwrap(),
        2.0 / 3.0,
        "H2 correctness",
    );
    let practice = scored_trial(json, "v1_practice.mcap");
    assert_eq!(practice["counted"].as_bool(), Some(false));
}

/// The per-task and per-embodiment aggregates in `scores.json`: the practice trial counted
/// apart, orca_full's overall scores over the attempted tasks and over all 18; and the five
/// rejected files.
fn assert_aggregates(json: &Value) {
    let v1_task = json["tasks"]
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["task"] == "V1" && t["embodiment"] == "orca_full")
        .unwrap();
    assert_eq!(
        (v1_task["counted"].as_u64(), v1_task["practice"].as_u64()),
        (Some(1), Some(1))
    );
    let full = json["embodiments"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["embodiment"] == "orca_full")
        .unwrap();
    assert_eq!(full["dof"].as_u64(), Some(16));
    let v1_score = 0.8 * 4.0 / 6.0 + 0.1;
    close(
        full["overall_attempted"].as_f64().unwrap(),
        (v1_score + 0.7) / 2.0,
        "overall attempted",
    );
    close(
        full["overall_all"].as_f64().unwrap(),
        (v1_score + 0.7) / 18.0,
        "overall all 18",
    );
    assert_eq!(json["rejected"].as_array().unwrap().len(), 6);
}

/// Every report file, with the warning where a reader will see it.
fn assert_report_files(out: &Path) {
    for name in [
        "report.md",
        "scores.csv",
        "overall.csv",
        "trials.csv",
        "scores.json",
    ] {
        let size = std::fs::metadata(out.join(name)).unwrap().len();
        assert!(size > 100, "{name}: {size} bytes");
    }
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("> **WARNING:** NO BASELINE for H2"));
    assert!(md.contains("truncated.mcap"));
    let csv = std::fs::read_to_string(out.join("scores.csv")).unwrap();
    assert!(
        csv.lines()
            .any(|l| l.starts_with("H2,") && l.ends_with("no baseline: correctness only")),
        "{csv}"
    );
}

/// The figures: both formats, sane sizes, not blank; no `.part` file left behind.
fn assert_figures(out: &Path) {
    for (stem, series) in [
        ("radar_manipulation", "orca_full"),
        ("radar_grasp", "orca_5"),
        ("overall_vs_dof", "orca_full"),
        ("overall_vs_dof_all_tasks", "orca_full"),
    ] {
        png_is_sane(&out.join(format!("{stem}.png")));
        let svg = std::fs::read_to_string(out.join(format!("{stem}.svg"))).unwrap();
        assert!(svg.len() > 2_000 && svg.contains("<svg"), "{stem}.svg");
        assert!(svg.contains(series), "{stem}.svg has no {series} label");
    }
    assert!(
        !out.read_dir()
            .unwrap()
            .any(|e| e.unwrap().path().to_string_lossy().ends_with(".part"))
    );
}

#[test]
fn score_names_every_bad_file_and_scores_the_good_ones() {
    let set = set();
    assert!(set.baseline_run.status.success());
    let out = set.dir.join("report");
    let _ = std::fs::remove_dir_all(&out);
    let trials = set.dir.join("trials");
    let output = pomdar(&[
        "score",
        s(&trials),
        "--baseline",
        s(&set.baseline),
        "--out",
        s(&out),
    ]);
    assert_eq!(
        output.status.code(),
        Some(3),
        "some files are rejected: exit 3"
    );
    assert_bad_files_named(&String::from_utf8_lossy(&output.stderr), &trials);

    // The table on stdout.
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("WARNING: NO BASELINE for H2"), "{stdout}");
    assert!(stdout.contains("Rejected files (6)"), "{stdout}");

    // The values, from scores.json.
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("scores.json")).unwrap()).unwrap();
    assert_trial_scores(&json);
    assert_aggregates(&json);

    assert_report_files(&out);
    assert_figures(&out);
}

#[test]
fn score_prints_json_and_exits_zero_when_every_file_is_good() {
    let set = set();
    assert!(set.baseline_run.status.success());
    let good = set.dir.join("trials/orca_full");
    let output = pomdar(&["score", s(&good), "--baseline", s(&set.baseline), "--json"]);
    assert_eq!(output.status.code(), Some(0));
    let json: Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(json["trials"].as_array().unwrap().len(), 3);
    assert!(
        json["warnings"].as_array().unwrap().is_empty(),
        "{}",
        json["warnings"]
    );
    // Without a baseline: correctness only, said loudly.
    let output = pomdar(&["score", s(&good)]);
    assert_eq!(output.status.code(), Some(0));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("WARNING: NO BASELINE: no baseline table was given"),
        "{stdout}"
    );
}

#[test]
fn bad_configuration_files_stop_the_run_naming_file_and_key() {
    let set = set();
    let rules = set.dir.join("rules.toml");
    std::fs::write(&rules, "correctness_weight = 0.9\nspeed_weight = 0.2\n").unwrap();
    let output = pomdar(&["score", s(&set.dir.join("trials")), "--rules", s(&rules)]);
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains(&format!(
            "{}: correctness_weight + speed_weight",
            rules.display()
        )),
        "{stderr}"
    );
    let output = pomdar(&["score", s(&set.dir.join("nothing_here"))]);
    assert_eq!(
        output.status.code(),
        Some(3),
        "a missing path is a rejected path"
    );
    let empty = set.dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let output = pomdar(&["score", s(&empty)]);
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("no .mcap trial files"));
}
