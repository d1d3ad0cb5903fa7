//! Ctrl-C and a killed console in the middle of a human study: no finished trial is lost and
//! the same command resumes the study (finished tasks skipped, the cut trial kept aside and
//! run again). The console is a `pomdar study --plain --simulate` driven through its stdin,
//! on loopback DDS; the glove is simulated in its process.

use std::path::Path;
use std::time::Duration;

use pomdar_tests::line_console::LineConsole;
use pomdar_tests::station_harness::test_domain;
use pomdar_tests::{scratch_dir, session_trial_statuses, trial_event_names};

fn study_args(root: &Path, domain: u16) -> Vec<String> {
    [
        "study",
        "--participant",
        "cut",
        "--operator",
        "ci",
        "--tasks",
        "V1,C1",
        "--trials",
        "2",
        "--plain",
        "--simulate",
        "--countdown",
        "0.3",
        "--domain-id",
    ]
    .iter()
    .map(|s| s.to_string())
    .chain([
        domain.to_string(),
        "--out".into(),
        root.display().to_string(),
    ])
    .collect()
}

fn pairs(list: &[(&str, &str)]) -> Vec<(String, String)> {
    list.iter()
        .map(|(f, s)| (f.to_string(), s.to_string()))
        .collect()
}

/// Starts a trial once the glove is ready (the console said READY `ready_seen` times) and
/// waits until it records `file`.
fn start_trial(console: &mut LineConsole, ready_seen: usize, file: &str) {
    console.wait_for_nth("READY", ready_seen, 60.0);
    console.say("start");
    console.wait_for(&format!("→ {file}"), 30.0);
}

/// One trial by hand: started once the glove is ready, stopped after a second.
fn run_trial(console: &mut LineConsole, ready_seen: usize, file: &str) {
    start_trial(console, ready_seen, file);
    std::thread::sleep(Duration::from_secs(1));
    console.say("stop");
}

/// The task's second trial, once its first is summed up: one second, stopped.
fn second_trial(console: &mut LineConsole, file: &str) {
    console.wait_for("last trial 1: completed", 30.0);
    console.say("start");
    console.wait_for(&format!("→ {file}"), 30.0);
    std::thread::sleep(Duration::from_secs(1));
    console.say("stop");
}

/// 1. V1 done (both trials), Ctrl-C during C1's first trial: exit 130, V1 complete, the cut
///    trial logged as aborted and set aside.
fn ctrl_c_in_the_second_task(root: &Path, domain: u16) {
    let mut console = LineConsole::start(&study_args(root, domain));
    console.wait_for("task 1 of 2: V1", 30.0);
    run_trial(&mut console, 1, "V1-t01.mcap");
    second_trial(&mut console, "V1-t02.mcap");
    console.wait_for("task 2 of 2: C1", 30.0);
    start_trial(&mut console, 2, "C1-t01.mcap");
    std::thread::sleep(Duration::from_secs(1));
    let code = console.interrupt();
    assert_eq!(code, Some(130), "{}", console.printed());
    assert!(
        console.printed().contains("stopped at task 2 of 2: C1"),
        "{}",
        console.printed()
    );
    let v1 = root.join("cut/human/V1");
    assert_eq!(
        session_trial_statuses(&v1),
        pairs(&[("V1-t01.mcap", "scored"), ("V1-t02.mcap", "scored")])
    );
    let c1 = root.join("cut/human/C1");
    assert_eq!(
        session_trial_statuses(&c1),
        pairs(&[("C1-t01.mcap.interrupted", "interrupted")])
    );
    assert_eq!(
        trial_event_names(&c1.join("C1-t01.mcap.interrupted")),
        ["start", "abort", "stop"]
    );
}

/// 2. Resumed: V1 skipped, C1's trial 1 run again, then SIGKILL mid-trial: its log is a
///    .part, the manifests are as the Ctrl-C left them.
fn sigkill_after_resuming(root: &Path, domain: u16) {
    let mut console = LineConsole::start(&study_args(root, domain));
    console.wait_for("task 1 of 2: V1 is complete: skipped", 30.0);
    console.wait_for("task 2 of 2: C1", 30.0);
    start_trial(&mut console, 1, "C1-t01-a2.mcap");
    std::thread::sleep(Duration::from_millis(1500));
    console.process.0.kill().unwrap();
    console.process.0.wait().unwrap();
    let c1 = root.join("cut/human/C1");
    assert!(c1.join("C1-t01-a2.mcap.part").exists());
    assert_eq!(
        session_trial_statuses(&c1).len(),
        1,
        "the manifest is as the Ctrl-C left it"
    );
    assert_eq!(session_trial_statuses(&root.join("cut/human/V1")).len(), 2);
}

/// 3. Resumed again: the .part is recovered and set aside, C1's two trials run, the study
///    completes with every finished trial in place.
fn finish_the_study(root: &Path, domain: u16) {
    let mut console = LineConsole::start(&study_args(root, domain));
    console.wait_for("task 2 of 2: C1", 30.0);
    run_trial(&mut console, 1, "C1-t01-a3.mcap");
    second_trial(&mut console, "C1-t02.mcap");
    console.wait_for("session complete", 30.0);
    let status = console.process.0.wait().unwrap();
    assert!(status.success(), "{}", console.printed());
    let c1 = root.join("cut/human/C1");
    assert_eq!(
        session_trial_statuses(&c1),
        pairs(&[
            ("C1-t01.mcap.interrupted", "interrupted"),
            ("C1-t01-a2.mcap.interrupted", "interrupted"),
            ("C1-t01-a3.mcap", "scored"),
            ("C1-t02.mcap", "scored"),
        ])
    );
    for file in [
        "cut/human/V1/V1-t01.mcap",
        "cut/human/V1/V1-t02.mcap",
        "cut/human/C1/C1-t01-a3.mcap",
        "cut/human/C1/C1-t02.mcap",
    ] {
        assert_eq!(
            trial_event_names(&root.join(file)),
            ["start", "stop"],
            "{file}"
        );
    }
}

#[test]
fn ctrl_c_and_sigkill_mid_study_resume_losing_no_finished_trial() {
    let root = scratch_dir("study_interrupt");
    let domain = test_domain();
    ctrl_c_in_the_second_task(&root, domain);
    sigkill_after_resuming(&root, domain);
    finish_the_study(&root, domain);
}
