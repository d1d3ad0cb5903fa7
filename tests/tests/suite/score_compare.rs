//! `pomdar score --compare keypoint_source` as the operator runs it (the built binary), on real
//! MCAP trial files written the way the station writes them: two groups (`rokoko`, `avp`)
//! for two tasks (V1 notches, C1 rotation) on two embodiments, with known times and
//! progress, and a hand-written baseline. Every number the comparison reports (means, sample
//! stds, differences, Welch intervals) is worked out here from the inputs, with this file's
//! own Student-t quantile (numeric integration, not the crate's incomplete beta); the figures
//! are decoded and their bars measured.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Output;
use std::sync::OnceLock;

use pomdar_tests::pomdar_binary::run_pomdar as pomdar;
use scoring::plot::SERIES_COLORS;
use serde_json::{Value, json};
use teleop::score::synthetic_trial::{SyntheticTrial, write_synthetic_trial};

const T0_NS: i64 = 1_732_200_000_000_000_000;
/// The baseline's mean times, seconds.
const BASELINE_V1_S: f64 = 12.0;
const BASELINE_C1_S: f64 = 20.0;

/// One trial: task, embodiment, keypoint source, time (s), progress (notches or degrees).
type Spec = (&'static str, &'static str, &'static str, f64, f64);

/// Three trials per task × embodiment × source; AVP slower and less correct, as in the paper.
const TRIALS: [Spec; 24] = [
    ("V1", "orca_full", "rokoko", 10.0, 6.0),
    ("V1", "orca_full", "rokoko", 12.0, 6.0),
    ("V1", "orca_full", "rokoko", 14.0, 5.0),
    ("V1", "orca_full", "avp", 13.0, 5.0),
    ("V1", "orca_full", "avp", 16.0, 4.0),
    ("V1", "orca_full", "avp", 19.0, 6.0),
    ("V1", "orca_5", "rokoko", 15.0, 4.0),
    ("V1", "orca_5", "rokoko", 18.0, 5.0),
    ("V1", "orca_5", "rokoko", 16.0, 4.0),
    ("V1", "orca_5", "avp", 20.0, 3.0),
    ("V1", "orca_5", "avp", 22.0, 4.0),
    ("V1", "orca_5", "avp", 27.0, 3.0),
    ("C1", "orca_full", "rokoko", 20.0, 360.0),
    ("C1", "orca_full", "rokoko", 24.0, 360.0),
    ("C1", "orca_full", "rokoko", 22.0, 300.0),
    ("C1", "orca_full", "avp", 25.0, 270.0),
    ("C1", "orca_full", "avp", 30.0, 330.0),
    ("C1", "orca_full", "avp", 28.0, 360.0),
    ("C1", "orca_5", "rokoko", 30.0, 300.0),
    ("C1", "orca_5", "rokoko", 26.0, 270.0),
    ("C1", "orca_5", "rokoko", 33.0, 360.0),
    ("C1", "orca_5", "avp", 35.0, 180.0),
    ("C1", "orca_5", "avp", 40.0, 240.0),
    ("C1", "orca_5", "avp", 38.0, 270.0),
];

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Writes a trial: start at 1 s, the progress in equal steps, stop after `time_s`.
fn write(path: &Path, spec: Spec, practice: bool, source: Option<&str>) {
    let (task, embodiment, _, time_s, progress) = spec;
    let mut metadata = BTreeMap::from([
        ("task".to_string(), task.to_string()),
        ("embodiment".to_string(), embodiment.to_string()),
        ("practice".to_string(), practice.to_string()),
        ("user".to_string(), "ann".to_string()),
    ]);
    if let Some(source) = source {
        metadata.insert("keypoint_source".to_string(), source.to_string());
    }
    let steps = if task == "V1" { progress as usize } else { 2 };
    let mut events = vec![(1.0, json!({"event": "start"}))];
    for k in 0..steps {
        let at = 1.0 + time_s * (k as f64 + 1.0) / (steps as f64 + 1.0);
        let value = progress / steps as f64;
        events.push((at, json!({"event": "progress", "value": value})));
    }
    events.push((1.0 + time_s, json!({"event": "stop"})));
    let trial = SyntheticTrial {
        metadata,
        t0_ns: T0_NS,
        duration_s: 1.5 + time_s,
        events,
        keypoint_rate_hz: 20.0,
        joint_rate_hz: 10.0,
        seed: 7,
    };
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    write_synthetic_trial(path, &trial).unwrap();
}

struct Set {
    trials: PathBuf,
    extra: PathBuf,
    baseline: PathBuf,
    out: PathBuf,
    run: Output,
}

/// The trials (plus an AVP practice trial that must not count), the baseline, and the run
/// of the brief's command line (once per test process).
fn set() -> &'static Set {
    static SET: OnceLock<Set> = OnceLock::new();
    SET.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("pomdar-score-compare-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let trials = dir.join("trials");
        for (i, spec) in TRIALS.iter().enumerate() {
            let name = format!("{}/{}/{}-{i:02}.mcap", spec.2, spec.1, spec.0);
            write(&trials.join(name), *spec, false, Some(spec.2));
        }
        let practice = ("V1", "orca_full", "avp", 5.0, 6.0);
        write(
            &trials.join("avp/practice.mcap"),
            practice,
            true,
            Some("avp"),
        );
        // A trial without the entry, for the run that shows the missing group.
        let extra = dir.join("extra");
        let unnamed = ("V1", "orca_full", "", 11.0, 6.0);
        write(&extra.join("no_source.mcap"), unnamed, false, None);
        let baseline = dir.join("baseline.toml");
        let table = format!(
            "[baseline]\nexample = false\nsource = \"score_compare test: hand-written\"\n\n\
             [[task]]\nid = \"V1\"\nmean_s = {BASELINE_V1_S}\nn = 6\n\n\
             [[task]]\nid = \"C1\"\nmean_s = {BASELINE_C1_S}\nn = 6\n"
        );
        std::fs::write(&baseline, table).unwrap();
        let out = dir.join("out");
        let run = pomdar(&[
            "score",
            s(&trials),
            "--baseline",
            s(&baseline),
            "--compare",
            "keypoint_source",
            "--out",
            s(&out),
            "--json",
        ]);
        Set {
            trials,
            extra,
            baseline,
            out,
            run,
        }
    })
}

fn json_of(output: &Output) -> Value {
    assert!(
        output.status.success(),
        "pomdar failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).unwrap()
}

/// The t quantile by this file's own method: with x = √ν tan θ the t density becomes
/// ∝ cos^(ν−1) θ on (−π/2, π/2), so F(t) = ½ + ∫₀^atan(t/√ν) cos^(ν−1) θ dθ / (2 ∫₀^π/2 …),
/// integrated by Simpson's rule and inverted by bisection.
fn t_quantile(p: f64, df: f64) -> f64 {
    let integral = |upper: f64| {
        let n = 20_000;
        let h = upper / n as f64;
        let f = |theta: f64| theta.cos().powf(df - 1.0);
        let inner: f64 = (1..n)
            .map(|k| f(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 })
            .sum();
        (f(0.0) + inner + f(upper)) * h / 3.0
    };
    let whole = integral(std::f64::consts::FRAC_PI_2);
    let cdf = |t: f64| 0.5 + integral((t / df.sqrt()).atan()) / (2.0 * whole);
    let (mut lo, mut hi) = (0.0, 1_000.0);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if cdf(mid) < p { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

/// Mean and sample standard deviation.
fn mean_std(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

/// Correctness, time and score of each trial of a task × embodiment × source, from the
/// inputs: V1 notches / 6, C1 degrees / 360; score = 0.8 c + 0.2 baseline / time.
fn expected(task: &str, embodiment: &str, source: &str) -> [Vec<f64>; 3] {
    let mine = TRIALS
        .iter()
        .filter(|t| t.0 == task && t.1 == embodiment && t.2 == source);
    let (full, baseline) = if task == "V1" {
        (6.0, BASELINE_V1_S)
    } else {
        (360.0, BASELINE_C1_S)
    };
    let c: Vec<f64> = mine.clone().map(|t| (t.4 / full).min(1.0)).collect();
    let time: Vec<f64> = mine.map(|t| t.3).collect();
    let score = c
        .iter()
        .zip(&time)
        .map(|(c, t)| 0.8 * c + 0.2 * baseline / t)
        .collect();
    [c, time, score]
}

fn close(a: f64, b: f64, tolerance: f64, what: &str) {
    assert!((a - b).abs() <= tolerance, "{what}: {a} != {b}");
}

/// Checks one measure's statistics and the rokoko − avp difference with its Welch interval.
fn check_measure(row: &Value, name: &str, rokoko: &[f64], avp: &[f64], what: &str) {
    let group = |g: &str| {
        row["groups"]
            .as_array()
            .unwrap()
            .iter()
            .find(|x| x["group"] == g)
            .unwrap()
            .clone()
    };
    let (r, a) = (group("rokoko"), group("avp"));
    let (mr, sr) = mean_std(rokoko);
    let (ma, sa) = mean_std(avp);
    close(
        r[name]["mean"].as_f64().unwrap(),
        mr,
        1e-9,
        &format!("{what} rokoko mean"),
    );
    close(
        r[name]["std"].as_f64().unwrap(),
        sr,
        1e-9,
        &format!("{what} rokoko std"),
    );
    close(
        a[name]["mean"].as_f64().unwrap(),
        ma,
        1e-9,
        &format!("{what} avp mean"),
    );
    close(
        a[name]["std"].as_f64().unwrap(),
        sa,
        1e-9,
        &format!("{what} avp std"),
    );
    assert!(
        a["versus_reference"].is_null(),
        "avp is the reference (first in sorted order)"
    );
    let d = &r["versus_reference"][name];
    close(
        d["estimate"].as_f64().unwrap(),
        mr - ma,
        1e-9,
        &format!("{what} difference"),
    );
    let (vr, va) = (sr * sr / 3.0, sa * sa / 3.0);
    let se = (vr + va).sqrt();
    let df = (vr + va).powi(2) / (vr * vr / 2.0 + va * va / 2.0);
    let t = t_quantile(0.975, df);
    assert_eq!(d["ci"]["status"], "defined", "{what}: {d}");
    close(
        d["ci"]["df"].as_f64().unwrap(),
        df,
        1e-9,
        &format!("{what} df"),
    );
    let tol = 1e-6 * se.max(1.0);
    close(
        d["ci"]["low"].as_f64().unwrap(),
        mr - ma - t * se,
        tol,
        &format!("{what} low"),
    );
    close(
        d["ci"]["high"].as_f64().unwrap(),
        mr - ma + t * se,
        tol,
        &format!("{what} high"),
    );
}

#[test]
fn the_test_quantile_matches_the_printed_table() {
    close(t_quantile(0.975, 1.0), 12.706, 5e-4, "t(0.975, 1)");
    close(t_quantile(0.975, 5.0), 2.5706, 5e-5, "t(0.975, 5)");
    close(t_quantile(0.975, 30.0), 2.0423, 5e-5, "t(0.975, 30)");
}

#[test]
fn the_comparison_reports_each_group_per_task_and_embodiment() {
    let set = set();
    let json = json_of(&set.run);
    assert_eq!(json["field"], "keypoint_source");
    assert_eq!(json["reference"], "avp");
    let groups: Vec<(String, u64)> = (json["groups"].as_array().unwrap().iter())
        .map(|g| {
            (
                g["name"].as_str().unwrap().to_string(),
                g["trials"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        groups,
        [("avp".to_string(), 12), ("rokoko".to_string(), 12)],
        "practice left out"
    );
    assert_eq!(json["missing_trials"], 0);
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 4);
    for row in rows {
        let (task, embodiment) = (
            row["task"].as_str().unwrap(),
            row["embodiment"].as_str().unwrap(),
        );
        assert_eq!(row["has_baseline"], true);
        for g in row["groups"].as_array().unwrap() {
            assert_eq!(g["n"], 3, "{task} {embodiment} {}", g["group"]);
        }
        let [rc, rt, rs] = expected(task, embodiment, "rokoko");
        let [ac, at, asc] = expected(task, embodiment, "avp");
        let what = format!("{task} {embodiment}");
        check_measure(row, "correctness", &rc, &ac, &format!("{what} correctness"));
        check_measure(row, "time_s", &rt, &at, &format!("{what} time"));
        check_measure(row, "score", &rs, &asc, &format!("{what} score"));
    }
    let stderr = String::from_utf8_lossy(&set.run.stderr);
    assert!(stderr.contains("scored 25 of 25 trial files"), "{stderr}");
}

#[test]
fn the_comparison_agrees_with_the_normal_report() {
    let set = set();
    let compare = json_of(&set.run);
    let report = json_of(&pomdar(&[
        "score",
        s(&set.trials),
        "--baseline",
        s(&set.baseline),
        "--json",
    ]));
    for row in compare["rows"].as_array().unwrap() {
        let result = (report["tasks"].as_array().unwrap().iter())
            .find(|t| t["task"] == row["task"] && t["embodiment"] == row["embodiment"])
            .unwrap();
        let groups = row["groups"].as_array().unwrap();
        let n: u64 = groups.iter().map(|g| g["n"].as_u64().unwrap()).sum();
        assert_eq!(Some(n), result["counted"].as_u64());
        // Equal group sizes: the report's mean is the mean of the group means.
        for measure in ["score", "correctness", "time_s"] {
            let mean = groups
                .iter()
                .map(|g| g[measure]["mean"].as_f64().unwrap())
                .sum::<f64>()
                / 2.0;
            close(
                mean,
                result[measure]["mean"].as_f64().unwrap(),
                1e-9,
                measure,
            );
        }
    }
}

/// Every `class="bar"` polygon of an SVG as (top y, bottom y), in document order.
fn svg_bars(svg: &str) -> Vec<(f64, f64)> {
    svg.lines()
        .filter(|l| l.contains("class=\"bar\""))
        .map(|l| {
            let points = l
                .split("points=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap();
            let ys: Vec<f64> = points
                .split(' ')
                .map(|p| p.split(',').nth(1).unwrap().parse().unwrap())
                .collect();
            (
                ys.iter().copied().fold(f64::INFINITY, f64::min),
                ys.iter().copied().fold(0.0, f64::max),
            )
        })
        .collect()
}

fn svg_size(svg: &str) -> (u32, u32) {
    let attr = |name: &str| -> u32 {
        let key = format!(" {name}=\"");
        svg.split(&key)
            .nth(1)
            .unwrap()
            .split('"')
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    (attr("width"), attr("height"))
}

#[test]
fn the_figures_have_a_bar_per_group_per_task_and_embodiment() {
    let set = set();
    let json = json_of(&set.run);
    let rows = json["rows"].as_array().unwrap();
    for (stem, measure) in [
        ("compare_score", "score"),
        ("compare_correctness", "correctness"),
    ] {
        let svg = std::fs::read_to_string(set.out.join(format!("{stem}.svg"))).unwrap();
        assert!(
            svg.contains("keypoint_source"),
            "{stem}: the title names the field"
        );
        assert!(
            svg.contains(">avp (12 trials, reference)</text>"),
            "{stem}: legend"
        );
        assert!(svg.contains(">rokoko (12 trials)</text>"), "{stem}: legend");
        // Series by series (avp, then rokoko), categories in the rows' order; heights ∝ means.
        let bars = svg_bars(&svg);
        assert_eq!(bars.len(), 2 * rows.len(), "{stem}");
        let bottom = bars[0].1;
        let means: Vec<f64> = ["avp", "rokoko"]
            .iter()
            .flat_map(|g| {
                rows.iter().map(move |r| {
                    let group = r["groups"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .find(|x| x["group"] == *g)
                        .unwrap();
                    group[measure]["mean"].as_f64().unwrap()
                })
            })
            .collect();
        let px_per_unit = (bottom - bars[0].0) / means[0];
        for ((top, b), mean) in bars.iter().zip(&means) {
            close(*b, bottom, 0.011, &format!("{stem}: bars stand on 0"));
            close(
                bottom - top,
                mean * px_per_unit,
                0.05,
                &format!("{stem}: bar height"),
            );
        }
        let png = std::fs::read(set.out.join(format!("{stem}.png"))).unwrap();
        let pixmap = tiny_skia::Pixmap::decode_png(&png).unwrap();
        assert_eq!((pixmap.width(), pixmap.height()), svg_size(&svg), "{stem}");
        assert!(pixmap.width() >= 800 && pixmap.height() >= 500, "{stem}");
        for (group, color) in [("avp", SERIES_COLORS[0]), ("rokoko", SERIES_COLORS[1])] {
            let found = (pixmap.pixels().iter())
                .filter(|p| {
                    (p.red(), p.green(), p.blue(), p.alpha()) == (color.r, color.g, color.b, 255)
                })
                .count();
            assert!(found > 2_000, "{stem}: {found} pixels of {group}'s colour");
        }
    }
    assert_eq!(
        json["figures"].as_array().map(Vec::len),
        Some(4),
        "{}",
        json["figures"]
    );
}

#[test]
fn the_files_say_the_same_as_stdout() {
    let set = set();
    let stdout = json_of(&set.run);
    let file: Value =
        serde_json::from_str(&std::fs::read_to_string(set.out.join("compare.json")).unwrap())
            .unwrap();
    assert_eq!(file["rows"], stdout["rows"]);
    let figures: Vec<&str> = file["figures"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    assert_eq!(
        figures,
        [
            "compare_score.svg",
            "compare_score.png",
            "compare_correctness.svg",
            "compare_correctness.png"
        ]
    );
    let md = std::fs::read_to_string(set.out.join("compare.md")).unwrap();
    assert!(
        md.starts_with("# POMDAR comparison by `keypoint_source`"),
        "{md}"
    );
    assert!(md.contains("![compare_score](compare_score.png)"), "{md}");
    assert!(md.contains("| V1 | orca_full | avp (ref) | 3 |"), "{md}");
    let csv = std::fs::read_to_string(set.out.join("compare.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 8, "4 task × embodiment rows × 2 groups");
    let v1 = rows
        .iter()
        .find(|r| {
            r[col("task")] == "V1"
                && r[col("embodiment")] == "orca_full"
                && r[col("group")] == "rokoko"
        })
        .unwrap();
    let [rc, ..] = expected("V1", "orca_full", "rokoko");
    let [ac, ..] = expected("V1", "orca_full", "avp");
    let diff: f64 = v1[col("correctness_diff")].parse().unwrap();
    close(
        diff,
        mean_std(&rc).0 - mean_std(&ac).0,
        1e-12,
        "csv correctness_diff",
    );
}

#[test]
fn the_table_and_the_missing_group_and_no_baseline() {
    let set = set();
    // Terminal table, with one trial that has no keypoint_source entry.
    let output = pomdar(&[
        "score",
        s(&set.trials),
        s(&set.extra),
        "--baseline",
        s(&set.baseline),
        "--compare",
        "keypoint_source",
    ]);
    assert!(output.status.success(), "{output:?}");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.starts_with("POMDAR comparison by metadata entry \"keypoint_source\""),
        "{stdout}"
    );
    assert!(
        stdout.contains("avp (12 trials, reference), rokoko (12 trials), (missing) (1 trial)"),
        "{stdout}"
    );
    assert!(
        stdout.contains("1 recorded trial(s) have no \"keypoint_source\" entry"),
        "{stdout}"
    );
    assert!(
        stdout.contains("(missing)          1  1.00 ± –"),
        "{stdout}"
    );
    assert!(stdout.contains("no CI (n < 2)"), "{stdout}");
    // Without a baseline: no score anywhere, the score figure is not drawn.
    let out = set.out.with_file_name("out_no_baseline");
    let output = pomdar(&[
        "score",
        s(&set.trials),
        "--compare",
        "keypoint_source",
        "--out",
        s(&out),
        "--json",
    ]);
    let json = json_of(&output);
    for row in json["rows"].as_array().unwrap() {
        assert_eq!(row["has_baseline"], false);
        assert!(
            row["groups"]
                .as_array()
                .unwrap()
                .iter()
                .all(|g| g["score"].is_null())
        );
    }
    assert!(!out.join("compare_score.png").exists());
    assert!(out.join("compare_correctness.png").exists());
    let md = std::fs::read_to_string(out.join("compare.md")).unwrap();
    assert!(md.contains("NO BASELINE"), "{md}");
    assert!(
        md.contains("compare_score: no task has a baseline, not drawn"),
        "{md}"
    );
}

#[test]
fn one_group_or_an_unknown_reference_stops_the_run() {
    let set = set();
    let output = pomdar(&["score", s(&set.trials), "--compare", "station_version"]);
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("none of the 24 recorded trials has this metadata entry"),
        "{stderr}"
    );
    let output = pomdar(&[
        "score",
        s(&set.trials),
        "--compare",
        "keypoint_source",
        "--compare-reference",
        "mediapipe",
    ]);
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr
            .contains("reference group \"mediapipe\" has no recorded trial (groups: avp, rokoko)"),
        "{stderr}"
    );
}
