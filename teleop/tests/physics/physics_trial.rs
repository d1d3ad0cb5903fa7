//! The whole simulated benchmark in one command, over loopback DDS: `pomdar trial --simulate
//! --physics` on G4 (small cylinder) with the simulated glove playing a task script. The
//! station retargets it, the simulated hand lifts and relocates the cylinder, the physics marks
//! the progress, and the trial is scored: correctness 1 for the scripted grasp, 0 for the
//! scripted miss. The same scripts in lock step (no DDS, simulated time) give the same.
//! (`physics` feature.)

use std::path::{Path, PathBuf};
use std::process::Command;

use teleop::ros::domain_lease::{TEST_DOMAINS, lease_domain};
use teleop::score::score_inputs::ScoringInputs;

const BASELINE_G4_S: f64 = 8.0;

fn shipped(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../launch_configs/sim")
        .join(name)
}

/// One recorded G4 trial with the glove playing `script`; its scored log.
fn simulated_trial(root: &Path, script: &str) -> scoring::TrialScore {
    std::fs::create_dir_all(root).unwrap();
    // The console script the README's simulated trial uses.
    let console = shipped("one_trial.script");
    let baseline = root.join("baseline.toml");
    std::fs::write(&baseline, format!("[baseline]\nexample = false\nsource = \"physics_trial test\"\n\n[[task]]\nid = \"G4\"\nmean_s = {BASELINE_G4_S}\nn = 3\n")).unwrap();
    let out = root.join("sessions");
    let output = Command::new(env!("CARGO_BIN_EXE_pomdar"))
        .args([
            "trial",
            "--task",
            "G4",
            "--user",
            "sim",
            "--operator",
            "ci",
            "--practice",
            "0",
            "--trials",
            "1",
        ])
        .args(["--simulate", "--physics", "--simulate-glove-script"])
        .arg(shipped(script))
        .args([
            "--domain-id",
            &lease_domain(TEST_DOMAINS).unwrap().to_string(),
            "--countdown",
            "0.5",
            "--script",
        ])
        .arg(&console)
        .arg("--baseline")
        .arg(&baseline)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    eprintln!("--- pomdar trial ({script}) stderr:\n{stderr}");
    assert!(output.status.success(), "pomdar trial failed");
    let log = out.join("sim/orca_full/G4/G4-t01.mcap");
    let inputs = ScoringInputs::load(None, None, Some(&baseline)).unwrap();
    inputs.score_file(&log).unwrap()
}

#[test]
fn a_scripted_grasp_of_g4_is_scored_one_by_the_physics_and_a_miss_zero() {
    let root = std::env::temp_dir().join(format!("pomdar-physics-trial-{}", std::process::id()));
    std::fs::remove_dir_all(&root).ok();
    let grasp = simulated_trial(&root.join("grasp"), "grasp_place.toml");
    assert_eq!(grasp.correctness, 1.0, "{grasp:?}");
    assert!(grasp.score.is_some_and(|s| s > 0.8), "{grasp:?}");
    let miss = simulated_trial(&root.join("miss"), "grasp_miss.toml");
    assert_eq!(miss.correctness, 0.0, "{miss:?}");
    std::fs::remove_dir_all(&root).ok();
}

/// The shipped scripts in lock step, through the command a lab runs (`pomdar sim --task G4
/// --lockstep FILE`, its defaults: the task's arm constraint, the glove's rest noise at seed 1):
/// the grasp relocates the cylinder (0.5 then 1, correctness 1), the miss leaves it (no event,
/// correctness 0). A regression guard on the shipped script at its default seed; how the grasp
/// holds over seeds and noise is measured with `--seed` and `--glove-jitter-mm` (README).
#[test]
fn the_scripts_in_lock_step_give_the_same_levels() {
    for (script, expected, correctness) in [
        ("grasp_place.toml", vec![0.5, 1.0], "correctness 1.000"),
        ("grasp_miss.toml", vec![], "correctness 0.000"),
    ] {
        let output = Command::new(env!("CARGO_BIN_EXE_pomdar"))
            .args(["sim", "--task", "G4", "--lockstep"])
            .arg(shipped(script))
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(
            output.status.success(),
            "{script}: {stdout}{}",
            String::from_utf8_lossy(&output.stderr)
        );
        // Event lines, "   4.94 s  progress 0.5 level" (a drop: "   6.10 s  drop level"):
        // the value of every event that has one.
        let levels: Vec<f64> = stdout
            .lines()
            .filter_map(
                |l| match l.split_once(" s  ")?.1.split(' ').collect::<Vec<_>>()[..] {
                    [_, value, _] => value.parse().ok(),
                    _ => None,
                },
            )
            .collect();
        assert_eq!(levels, expected, "{script}: {stdout}");
        let summary = stdout.lines().last().unwrap_or_default();
        assert!(summary.contains(correctness), "{script}: {summary}");
        // "(1250 hand commands, 313 arm targets)"
        let count = |what: &str| -> u64 {
            let before = summary.split(what).next().unwrap_or_default();
            before
                .rsplit(['(', ' '])
                .find(|w| !w.is_empty())
                .and_then(|w| w.parse().ok())
                .unwrap_or(0)
        };
        assert!(
            count(" hand commands") > 500 && count(" arm targets") > 100,
            "{script}: {summary}"
        );
    }
}

/// `--runs`: one line per seed, in order, and a success count that is theirs; the first seed's
/// run is the single run's (the same correctness as `--seed 1` alone). With `--perturb-start`
/// each run's start is moved by its seed and the lines say how.
#[test]
fn lock_step_runs_over_seeds_count_their_successes() {
    for perturb in [false, true] {
        let mut command = Command::new(env!("CARGO_BIN_EXE_pomdar"));
        command.args([
            "sim",
            "--task",
            "G4",
            "--runs",
            "3",
            "--seed",
            "1",
            "--lockstep",
        ]);
        command.arg(shipped("grasp_place.toml"));
        if perturb {
            command.arg("--perturb-start");
        }
        let output = command.output().unwrap();
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(output.status.success(), "{stdout}");
        let runs: Vec<&str> = stdout.lines().filter(|l| l.starts_with("seed ")).collect();
        let seeds: Vec<&str> = runs
            .iter()
            .filter_map(|l| l.split(':').next()?.strip_prefix("seed "))
            .collect();
        assert_eq!(seeds, ["1", "2", "3"], "{stdout}");
        let successes = runs
            .iter()
            .filter(|l| l.contains("correctness 1.000"))
            .count();
        let summary = stdout.lines().last().unwrap_or_default();
        assert!(
            summary.starts_with(&format!(
                "correctness 1 in {successes} of 3 runs (seeds 1–3"
            )),
            "{stdout}"
        );
        assert!(runs[0].contains("correctness 1.000"), "{stdout}");
        // Each run names the move of its start ("(start +3.6, +1.9 mm, +3.0°)"), all different.
        let starts: Vec<&str> = runs
            .iter()
            .filter_map(|l| l.split_once("(start ").map(|(_, s)| s))
            .collect();
        assert_eq!(starts.len(), if perturb { 3 } else { 0 }, "{stdout}");
        assert!(starts.windows(2).all(|w| w[0] != w[1]), "{stdout}");
        assert_eq!(summary.contains("starts moved"), perturb, "{summary}");
    }
}

/// The manufacturer's MJCF of the hand (`--hand-mjcf`, from `../shared/reference/`) plays the
/// shipped G4 script through the same command: from five moved starts at 1 mm of glove noise it
/// relocates the cylinder every time. A regression guard on seeds 1–5 (the held-out figures,
/// 100 of 100 on seeds 501–600, are in the README). Skipped where the reference data is absent.
#[test]
fn the_manufacturers_hand_relocates_the_cylinder_from_moved_starts() {
    let hand = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/reference/orcahand_v1_mjcf/orcahand_right.mjcf");
    if !hand.is_file() {
        println!(
            "SKIPPED: the manufacturer's MJCF {} is absent",
            hand.display()
        );
        return;
    }
    let output = Command::new(env!("CARGO_BIN_EXE_pomdar"))
        .args(["sim", "--task", "G4", "--runs", "5", "--seed", "1"])
        .args(["--glove-jitter-mm", "1", "--perturb-start", "--hand-mjcf"])
        .arg(&hand)
        .arg("--lockstep")
        .arg(shipped("grasp_place.toml"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let summary = stdout.lines().last().unwrap_or_default();
    assert!(
        summary.starts_with(
            "correctness 1 in 5 of 5 runs (seeds 1–5, glove noise 1.0 mm, starts moved"
        ),
        "{stdout}"
    );
}
