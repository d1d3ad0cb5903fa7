//! Every task that has a glove task script, done by the hand: the script in lock step through
//! the command a lab runs (`pomdar sim --task ID [--config FILE] --lockstep SCRIPT --runs 20
//! --glove-jitter-mm 1 --perturb-start --hand-mjcf HAND`), the station retargeting it and the
//! physics measuring the progress, from twenty moved starts (±5 mm, ±3°) at 1 mm of glove
//! noise: correctness 1 in at least 19 of 20. The hand is the manufacturer's MJCF where the
//! reference data is present (as in CI), else the hand the project writes from the URDF (said
//! so in the output); a script that holds only for the manufacturer's hand (its row says so)
//! is then skipped, said so. Each task is a test of its own and prints its row of the table (`--nocapture`).
//! Seeds 1–20 are a regression guard; the held-out figures
//! (seeds 501–600) are in README "The simulated benchmark". Tasks without a script yet are
//! listed.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A task's script under launch_configs/sim/, the station preset it is played with (under
/// launch_configs/station/) if not the built-in defaults, and the hands it holds for.
struct Row {
    task: &'static str,
    script: &'static str,
    config: Option<&'static str>,
    hands: Hands,
}

/// The hands a script holds for.
#[derive(Clone, Copy, PartialEq)]
enum Hands {
    /// The manufacturer's and the project's.
    Both,
    /// The manufacturer's only (README says why): skipped, said so, where its MJCF is absent.
    ManufacturersOnly,
}

const fn row(task: &'static str, script: &'static str) -> Row {
    Row {
        task,
        script,
        config: None,
        hands: Hands::Both,
    }
}

const fn twisting(task: &'static str, script: &'static str) -> Row {
    Row {
        config: TWIST,
        ..row(task, script)
    }
}

/// A script that holds for the manufacturer's hand only.
const fn manufacturers_hand_only(row: Row) -> Row {
    Row {
        hands: Hands::ManufacturersOnly,
        ..row
    }
}

/// The station preset under which the wrist's turn about the task's axis reaches the arm.
const TWIST: Option<&str> = Some("twist_about_axis.toml");

const SCRIPTS: [Row; 18] = [
    manufacturers_hand_only(twisting("V1", "tasks/V1.toml")),
    twisting("V2", "tasks/V2.toml"),
    manufacturers_hand_only(twisting("V3", "tasks/V3.toml")),
    row("H1", "tasks/H1.toml"),
    row("H2", "tasks/H2.toml"),
    row("H3", "tasks/H3.toml"),
    row("H4", "tasks/H4.toml"),
    row("H5", "tasks/H5.toml"),
    twisting("C1", "tasks/C1.toml"),
    twisting("C2", "tasks/C2.toml"),
    twisting("C3", "tasks/C3.toml"),
    row("C4", "tasks/C4.toml"),
    row("G1", "tasks/G1.toml"),
    row("G2", "tasks/G2.toml"),
    row("G3", "tasks/G3.toml"),
    row("G4", "grasp_place.toml"),
    row("G5", "tasks/G5.toml"),
    row("G6", "tasks/G6.toml"),
];
const RUNS: u32 = 20;

fn launch_configs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../launch_configs")
}

/// The manufacturer's MJCF of the hand, where the reference data is present.
fn manufacturers_hand() -> Option<PathBuf> {
    let hand = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/reference/orcahand_v1_mjcf/orcahand_right.mjcf");
    hand.is_file().then_some(hand)
}

/// The number of runs of `row`'s script that scored correctness 1, and the summary line.
fn successes(row: &Row, hand: Option<&Path>) -> (u32, String) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_pomdar"));
    command.args(["sim", "--task", row.task, "--runs", &RUNS.to_string()]);
    command.args(["--seed", "1", "--glove-jitter-mm", "1", "--perturb-start"]);
    if let Some(config) = row.config {
        command
            .arg("--config")
            .arg(launch_configs().join("station").join(config));
    }
    if let Some(hand) = hand {
        command.arg("--hand-mjcf").arg(hand);
    }
    let script = launch_configs().join("sim").join(row.script);
    let output = command.arg("--lockstep").arg(&script).output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    let task = row.task;
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

/// Play `task`'s row and require correctness 1 in at least 19 of 20 runs; prints the row.
fn done_by_the_hand(task: &str) {
    let row = SCRIPTS.iter().find(|r| r.task == task).unwrap();
    let hand = manufacturers_hand();
    if hand.is_none() && row.hands == Hands::ManufacturersOnly {
        println!(
            "| {task} | {} | skipped: the script holds for the manufacturer's hand only, whose MJCF is absent beside the checkout |",
            row.script
        );
        return;
    }
    let (count, summary) = successes(row, hand.as_deref());
    let played_on = if hand.is_some() {
        "manufacturer's"
    } else {
        "project's (the manufacturer's MJCF is absent beside the checkout)"
    };
    println!(
        "| {task} | {} | {} | {played_on} | {count} of {RUNS} |",
        row.script,
        row.config.unwrap_or("built-in")
    );
    assert!(count >= 19, "{task}: {summary}");
}

/// One test per task, so that each stays short and a failure names its task.
macro_rules! done_by_the_hand {
    ($($name:ident => $task:literal),* $(,)?) => {
        $(
            #[test]
            fn $name() {
                done_by_the_hand($task);
            }
        )*
    };
}

done_by_the_hand! {
    v1_is_done_by_the_hand => "V1",
    v2_is_done_by_the_hand => "V2",
    v3_is_done_by_the_hand => "V3",
    h1_is_done_by_the_hand => "H1",
    h2_is_done_by_the_hand => "H2",
    h3_is_done_by_the_hand => "H3",
    h4_is_done_by_the_hand => "H4",
    h5_is_done_by_the_hand => "H5",
    c1_is_done_by_the_hand => "C1",
    c2_is_done_by_the_hand => "C2",
    c3_is_done_by_the_hand => "C3",
    c4_is_done_by_the_hand => "C4",
    g1_is_done_by_the_hand => "G1",
    g2_is_done_by_the_hand => "G2",
    g3_is_done_by_the_hand => "G3",
    g4_is_done_by_the_hand => "G4",
    g5_is_done_by_the_hand => "G5",
    g6_is_done_by_the_hand => "G6",
}

/// Every row is a task of the catalog with its script and preset in place and a test of its
/// own above; the tasks without a script yet are printed.
#[test]
fn every_script_is_in_place_and_the_tasks_without_one_are_listed() {
    let here = include_str!("physics_tasks.rs");
    for row in &SCRIPTS {
        assert!(
            simulation::scene::TASK_IDS.contains(&row.task),
            "{}",
            row.task
        );
        assert!(launch_configs().join("sim").join(row.script).is_file());
        if let Some(config) = row.config {
            assert!(launch_configs().join("station").join(config).is_file());
        }
        let test = format!(
            "{}_is_done_by_the_hand => \"{}\"",
            row.task.to_lowercase(),
            row.task
        );
        assert!(here.contains(&test), "no test plays {}", row.task);
    }
    let scripted: Vec<&str> = SCRIPTS.iter().map(|r| r.task).collect();
    let without: Vec<&str> = simulation::scene::TASK_IDS
        .iter()
        .copied()
        .filter(|t| !scripted.contains(t))
        .collect();
    println!("without a script yet: {}", without.join(", "));
}
