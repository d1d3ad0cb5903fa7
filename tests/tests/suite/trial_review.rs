//! The operator's review of a trial, end to end: `pomdar trial --simulate` runs a scripted
//! session (simulated glove, mock robot, loopback DDS) whose glove script pauses for 350 ms
//! (a dropout) and pinches the thumb to the little finger, which the embodiment `orca_3`
//! cannot follow (its little finger is locked). The console says both after the trial, the
//! review written into the session's `review/` directory names both with their times, the
//! session's report lists the trial with a link to its figure, and `pomdar review` on the log
//! says the same. A clean session (the full hand, an index pinch, no dropout) gets no feedback.

use std::path::Path;
use std::sync::{Mutex, PoisonError};

use pomdar_tests::pomdar_binary::run_pomdar;
use pomdar_tests::scratch_dir;
use pomdar_tests::station_harness::test_domain;
use serde_json::Value;

/// The two sessions run one at a time: each is a whole console, station, glove and robot in
/// real time, and the suite's other real-time tests share the machine's two cores with them.
static ONE_SESSION_AT_A_TIME: Mutex<()> = Mutex::new(());

/// Start of the glove script's dropout, and its end, seconds after the trial's start.
const DROPOUT_S: (f64, f64) = (5.3, 5.65);

/// The glove's task: an index pinch (1.5–2.5 s), a little-finger pinch (3.5–4.5 s), open;
/// with `dropout`, no frames during [`DROPOUT_S`].
fn glove_script(dropout: bool) -> String {
    let mut text = String::new();
    for (t, pose) in [
        (0.0, "open"),
        (1.0, "open"),
        (1.5, "pinch_index"),
        (2.5, "pinch_index"),
        (3.0, "open"),
        (3.5, "pinch_little"),
        (4.5, "pinch_little"),
        (5.0, "open"),
    ] {
        let pose = if !dropout && pose == "pinch_little" {
            "open"
        } else {
            pose
        };
        text.push_str(&format!(
            "[[keyframes]]\nt_s = {t}\nwrist_m = [0.0, 0.0, 0.0]\npose = \"{pose}\"\n\n"
        ));
    }
    if dropout {
        text.push_str(&format!(
            "[[dropouts]]\nfrom_s = {}\nto_s = {}\n",
            DROPOUT_S.0, DROPOUT_S.1
        ));
    }
    text
}

/// One recorded trial of task H5 with `embodiment`, the glove playing `script`; the console's
/// output (its lines on stderr).
fn session(root: &Path, embodiment: &str, script: &str) -> std::process::Output {
    let _one = ONE_SESSION_AT_A_TIME
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    let glove = root.join("glove.toml");
    std::fs::write(&glove, script).unwrap();
    let operator = root.join("operator.script");
    std::fs::write(
        &operator,
        "engage\nwait ready 60\nstart\nwait running 60\n+6.5 stop\n",
    )
    .unwrap();
    let domain = test_domain().to_string();
    let output = run_pomdar(&[
        "trial",
        "--task",
        "H5",
        "--embodiment",
        embodiment,
        "--user",
        "sim",
        "--operator",
        "ci",
        "--practice",
        "0",
        "--trials",
        "1",
        "--simulate",
        "--simulate-glove-script",
        glove.to_str().unwrap(),
        "--domain-id",
        &domain,
        "--countdown",
        "0.5",
        "--script",
        operator.to_str().unwrap(),
        "--out",
        root.join("sessions").to_str().unwrap(),
    ]);
    assert!(output.status.success(), "the session failed: {output:?}");
    output
}

/// The one trial's log and its review JSON.
fn trial_and_review(root: &Path) -> (std::path::PathBuf, Value) {
    let logs: Vec<_> = walk(&root.join("sessions"))
        .into_iter()
        .filter(|p| p.extension().is_some_and(|e| e == "mcap"))
        .collect();
    let [log] = &logs[..] else {
        panic!("expected one trial log: {logs:?}")
    };
    let stem = log.file_stem().unwrap().to_string_lossy().into_owned();
    let json = log
        .parent()
        .unwrap()
        .join("review")
        .join(format!("{stem}.review.json"));
    let review: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(json.with_extension("png").is_file() && json.with_extension("svg").is_file());
    (log.clone(), review)
}

fn walk(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let path = entry.path();
        if path.is_dir() {
            found.extend(walk(&path));
        } else {
            found.push(path);
        }
    }
    found
}

fn feedback_of<'a>(review: &'a Value, kind: &str) -> Vec<&'a Value> {
    review["feedback"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["kind"] == kind)
        .collect()
}

#[test]
fn a_glove_gap_and_a_pinch_the_hand_cannot_close_are_said_with_their_times() {
    let root = scratch_dir("trial-review-faults");
    let output = session(&root, "orca_3", &glove_script(true));
    let console = String::from_utf8_lossy(&output.stderr);
    let (log, review) = trial_and_review(&root);
    println!("{}", serde_json::to_string_pretty(&review).unwrap());

    // The hold: 150 ms (and at most a 40 ms tick and a little) after the glove's last frame
    // before the dropout; the glove's gap about the dropout's 350 ms.
    let holds = review["holds"].as_array().unwrap();
    assert_eq!(holds.len(), 1, "{holds:?}");
    let value = |v: &Value| v.as_f64().unwrap();
    let gap_from = value(&holds[0]["glove_gap_from_s"]);
    let after = value(&holds[0]["from_s"]) - gap_from;
    assert!(
        (0.15..0.25).contains(&after),
        "hold {after} s after the last frame"
    );
    let gap = value(&holds[0]["glove_gap_ms"]);
    assert!((330.0..450.0).contains(&gap), "glove gap {gap} ms");
    let [held] = &feedback_of(&review, "holds")[..] else {
        panic!("{review}")
    };
    assert!(
        held["text"]
            .as_str()
            .unwrap()
            .starts_with("held once (glove gap "),
        "{held}"
    );
    assert_eq!(held["times_s"][0], holds[0]["from_s"]);

    // The little-finger pinch, not closed, at its time.
    let little: Vec<&Value> = review["pinches"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["finger"] == "little")
        .collect();
    let [little] = &little[..] else {
        panic!("{review}")
    };
    assert_eq!(little["closed"], false);
    // Script time: closing 3.0–3.5 s, the dropout from 5.3 s.
    let before_gap = gap_from - value(&little["from_s"]);
    assert!(
        (1.2..2.5).contains(&before_gap),
        "little pinch {before_gap} s before the gap"
    );
    let missed = feedback_of(&review, "pinch_not_closed");
    let said = missed
        .iter()
        .find(|f| {
            f["text"]
                .as_str()
                .unwrap()
                .starts_with("little pinch did not close in 1 of 1")
        })
        .unwrap_or_else(|| panic!("{review}"));
    assert_eq!(said["times_s"][0], little["from_s"]);

    // The console said both after the trial; the report lists the trial with its figure.
    assert!(
        console.contains("feedback: held once (glove gap "),
        "{console}"
    );
    assert!(
        console.contains("feedback: little pinch did not close"),
        "{console}"
    );
    let report = walk(&root.join("sessions"))
        .into_iter()
        .find(|p| p.file_name().is_some_and(|n| n == "report.md"))
        .expect("the session's report");
    let report = std::fs::read_to_string(report).unwrap();
    let stem = log.file_stem().unwrap().to_string_lossy().into_owned();
    assert!(report.contains("## Trials, worst first"), "{report}");
    let row = report
        .lines()
        .find(|l| l.starts_with(&format!("| {stem} |")))
        .unwrap_or_else(|| panic!("no row for {stem}: {report}"));
    assert!(
        row.contains("held once (glove gap ") && row.contains("little pinch did not close"),
        "{row}"
    );
    assert!(
        report.contains(&format!("[figure](../review/{stem}.review.png)")),
        "{report}"
    );

    // `pomdar review` on the log says the same.
    let out = root.join("again");
    let again = run_pomdar(&[
        "review",
        log.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(again.status.success());
    let again: Value = serde_json::from_slice(&again.stdout).unwrap();
    assert_eq!(again["feedback"], review["feedback"]);
    assert!(out.join(format!("{stem}.review.png")).is_file());
}

#[test]
fn a_clean_trial_gets_no_feedback() {
    let root = scratch_dir("trial-review-clean");
    let output = session(&root, "orca_full", &glove_script(false));
    let (_, review) = trial_and_review(&root);
    assert_eq!(review["feedback"], Value::Array(Vec::new()), "{review}");
    assert_eq!(review["holds"], Value::Array(Vec::new()));
    let pinches = review["pinches"].as_array().unwrap();
    assert!(
        !pinches.is_empty() && pinches.iter().all(|p| p["closed"] == true),
        "{pinches:?}"
    );
    assert!(!String::from_utf8_lossy(&output.stderr).contains("feedback:"));
}
