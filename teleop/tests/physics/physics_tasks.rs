//! Every task that has a glove task script, done by the hand: the script in lock step through
//! the command a lab runs (`pomdar sim --task ID --lockstep FILE --runs 20 --glove-jitter-mm 1
//! --perturb-start`), the station retargeting it and the physics measuring the progress, from
//! twenty moved starts (±5 mm, ±3°) at 1 mm of glove noise: correctness 1 in at least 19 of 20.
//! Prints the table. Seeds 1–20 are a regression guard; the held-out figures (seeds 201–300,
//! 501–600) are in README "The simulated benchmark". Tasks without a script yet are listed.

use std::path::Path;
use std::process::Command;

/// Task, its script under launch_configs/sim/.
const SCRIPTS: [(&str, &str); 4] = [
    ("G1", "tasks/G1.toml"),
    ("G3", "tasks/G3.toml"),
    ("G4", "grasp_place.toml"),
    ("C4", "tasks/C4.toml"),
];
const RUNS: u32 = 20;

/// The number of runs of `script` on `task` that scored correctness 1, and the summary line.
fn successes(task: &str, script: &str) -> (u32, String) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../launch_configs/sim")
        .join(script);
    let output = Command::new(env!("CARGO_BIN_EXE_pomdar"))
        .args([
            "sim",
            "--task",
            task,
            "--runs",
            &RUNS.to_string(),
            "--seed",
            "1",
        ])
        .args(["--glove-jitter-mm", "1", "--perturb-start", "--lockstep"])
        .arg(&path)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{task}: {stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let summary = stdout.lines().last().unwrap_or_default().to_string();
    // "correctness 1 in 19 of 20 runs (…"
    let count = summary
        .strip_prefix("correctness 1 in ")
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{task}: no success count in {summary:?}"));
    (count, summary)
}

#[test]
fn every_scripted_task_is_done_by_the_hand_from_moved_starts() {
    println!("| task | script | correctness 1 |");
    println!("|---|---|---|");
    let mut failures = Vec::new();
    for (task, script) in SCRIPTS {
        let (count, summary) = successes(task, script);
        println!("| {task} | {script} | {count} of {RUNS} |");
        if count < 19 {
            failures.push(format!("{task}: {summary}"));
        }
    }
    let scripted: Vec<&str> = SCRIPTS.iter().map(|(t, _)| *t).collect();
    let without: Vec<&str> = simulation::scene::TASK_IDS
        .iter()
        .copied()
        .filter(|t| !scripted.contains(t))
        .collect();
    println!("without a script yet: {}", without.join(", "));
    assert!(failures.is_empty(), "{failures:#?}");
}
