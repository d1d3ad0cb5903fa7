//! The benchmark without a teleoperator, through the command a lab runs (`pomdar sim-bench`):
//! what the physics must show whatever the practice finds, that `pomdar score` reads its trial
//! logs to the same numbers, that a seed repeats and shards merge to the one run's report,
//! and that a hand imported from a URDF runs the grasp tasks. The hand is the manufacturer's
//! MJCF where the reference data is present (as in CI), else the project's.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

fn pomdar() -> Command {
    Command::new(env!("CARGO_BIN_EXE_pomdar"))
}

fn reference() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/reference")
}

/// The manufacturer's MJCF of the hand, where the reference data is present.
fn manufacturers_hand() -> Option<PathBuf> {
    let hand = reference().join("orcahand_v1_mjcf/orcahand_right.mjcf");
    hand.is_file().then_some(hand)
}

fn fresh_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pomdar-sim-bench-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    dir
}

/// Runs `pomdar` with `args`; its stdout, or a panic with both streams.
fn run(args: &[&str], extra: &[&Path]) -> String {
    let output = pomdar().args(args).args(extra).output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout).to_string();
    assert!(
        output.status.success(),
        "pomdar {args:?}: {stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    stdout
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap())
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The recorded runs of an item that completed its task (stopped without an abort).
fn completed(out: &Path, embodiment: &str, task: &str) -> usize {
    let item = json(&out.join(format!("items/{embodiment}__{task}.json")));
    item["recorded"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|run| {
            let events = run["trial"]["events"].as_array().unwrap();
            !events.iter().any(|e| e[1]["event"] == "abort")
        })
        .count()
}

#[test]
fn a_small_budget_shows_what_the_physics_must_and_score_reads_the_same_numbers() {
    let out = fresh_dir("small");
    let mut args = vec![
        "sim-bench",
        "--embodiment",
        "orca_2,orca_full",
        "--tasks",
        "G4,H2,H5",
        "--budget",
        "12",
        "--runs",
        "20",
        "--seed",
        "1",
        "--trial-logs",
        "--example-baseline",
        "--out",
    ];
    let hand = manufacturers_hand();
    let out_arg = out.display().to_string();
    args.push(&out_arg);
    let hand_arg = hand.as_ref().map(|h| h.display().to_string());
    if let Some(h) = &hand_arg {
        args.extend(["--hand", h.as_str()]);
    }
    let stdout = run(&args, &[]);
    println!("{stdout}");
    // H2 (chopsticks) is worked by spreading the fingers: orca_2 has no abduction joint.
    let without = completed(&out, "orca_2", "H2");
    assert_eq!(
        without, 0,
        "orca_2 completed H2 {without} times without abduction"
    );
    let grasps = completed(&out, "orca_full", "G4");
    assert!(
        grasps >= 19,
        "orca_full completed G4 in {grasps} of 20 runs"
    );
    for file in [
        "report.md",
        "scores.csv",
        "overall.csv",
        "trials.csv",
        "scores.json",
        "radar_manipulation.svg",
        "radar_grasp.png",
        "overall_vs_dof.svg",
        "overall_vs_dof_all_tasks.png",
        "strategies.md",
        "strategies.json",
        "findings.md",
        "findings.json",
        "example_baseline.toml",
        "sim_bench.json",
    ] {
        assert!(out.join(file).is_file(), "{file} missing");
    }
    let logs = out.join("trials");
    let baseline = out.join("example_baseline.toml");
    let scored = pomdar()
        .arg("score")
        .arg(&logs)
        .arg("--baseline")
        .arg(&baseline)
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        scored.status.success(),
        "{}",
        String::from_utf8_lossy(&scored.stderr)
    );
    let from_logs: Value = serde_json::from_slice(&scored.stdout).unwrap();
    let from_bench = json(&out.join("scores.json"));
    assert_eq!(from_logs["trials"].as_array().unwrap().len(), 120);
    for key in ["tasks", "embodiments"] {
        assert_eq!(from_logs[key], from_bench[key], "{key} differ");
    }
    std::fs::remove_dir_all(&out).ok();
}

/// The parts of a report that must repeat: per task and embodiment, per embodiment, and the
/// strategies chosen.
fn results(out: &Path) -> (Value, Value, Value) {
    let scores = json(&out.join("scores.json"));
    (
        scores["tasks"].clone(),
        scores["embodiments"].clone(),
        json(&out.join("strategies.json")),
    )
}

#[test]
fn a_seed_repeats_and_two_shards_merge_to_the_one_run_report() {
    let (whole, one, two, merged) = (
        fresh_dir("whole"),
        fresh_dir("one"),
        fresh_dir("two"),
        fresh_dir("merged"),
    );
    let common = [
        "sim-bench",
        "--embodiment",
        "orca_full",
        "--tasks",
        "G4,H5",
        "--budget",
        "6",
        "--runs",
        "4",
        "--seed",
        "7",
        "--example-baseline",
        "--out",
    ];
    run(&common, &[&whole]);
    for (dir, shard) in [(&one, "1/2"), (&two, "2/2")] {
        run(
            &[&common[..], &[&dir.display().to_string(), "--shard", shard]].concat(),
            &[],
        );
    }
    // Items go in catalog order (H5 before G4), dealt out in turn.
    assert!(
        one.join("items/orca_full__H5.json").is_file()
            && !one.join("items/orca_full__G4.json").exists()
    );
    let merged_arg = merged.display().to_string();
    run(
        &[
            "sim-bench",
            "--example-baseline",
            "--out",
            &merged_arg,
            "--merge",
        ],
        &[&one, &two],
    );
    // The shards ran the items again in other processes: the same strategies and scores.
    assert_eq!(results(&whole), results(&merged));
    for item in ["orca_full__G4.json", "orca_full__H5.json"] {
        let shard = if one.join("items").join(item).is_file() {
            &one
        } else {
            &two
        };
        assert_eq!(
            json(&whole.join("items").join(item)),
            json(&shard.join("items").join(item)),
            "{item}"
        );
    }
    for dir in [whole, one, two, merged] {
        std::fs::remove_dir_all(dir).ok();
    }
}

#[test]
fn a_hand_imported_from_a_urdf_runs_the_grasp_tasks() {
    let urdf = reference().join("orcahand_v1_right.urdf");
    if !urdf.is_file() {
        println!(
            "skipped: {} is absent (the reference data beside the checkout)",
            urdf.display()
        );
        return;
    }
    let import = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../launch_configs/hands/orca_v1_right_urdf.toml");
    let out = fresh_dir("urdf");
    let out_arg = out.display().to_string();
    run(
        &[
            "sim-bench",
            "--embodiment",
            "orca_full",
            "--tasks",
            "G1,G2,G3,G4,G5,G6",
            "--budget",
            "1",
            "--runs",
            "2",
            "--out",
            &out_arg,
            "--urdf",
        ],
        &[&urdf, Path::new("--import"), &import],
    );
    let settings = json(&out.join("sim_bench.json"));
    assert!(
        settings["hand"]
            .as_str()
            .unwrap()
            .contains("orcahand_v1_right.urdf"),
        "{settings}"
    );
    let trials = json(&out.join("scores.json"))["trials"]
        .as_array()
        .unwrap()
        .len();
    assert_eq!(trials, 12, "two recorded runs of each grasp task");
    let done: usize = ["G1", "G2", "G3", "G4", "G5", "G6"]
        .iter()
        .map(|t| completed(&out, "orca_full", t))
        .sum();
    println!(
        "the hand imported from {} relocated {done} of 12 objects",
        urdf.display()
    );
    assert!(
        done >= 11,
        "the imported hand relocated {done} of 12 objects"
    );
    std::fs::remove_dir_all(&out).ok();
}
