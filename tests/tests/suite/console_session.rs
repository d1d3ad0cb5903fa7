//! `pomdar trial` end to end, as a demo or a test drives it: a scripted session with the
//! simulated glove and the mock robot (`--simulate`, loopback DDS): 1 practice and 3 recorded
//! V1 trials (one of them redone), then one grasp trial, with a baseline. Checks every trial's
//! MCAP (metadata, events, glove input and joint targets inside the trial), the manifests, the
//! session report the console wrote and `pomdar score` over both sessions.

use std::path::{Path, PathBuf};

use msgs::JointState;
use pomdar_tests::pomdar_binary::run_pomdar;
use pomdar_tests::scratch_dir;
use pomdar_tests::station_harness::test_domain;
use teleop::mcap_log::{TRIAL_EVENTS_TOPIC, TrialReader, read_trial_events};

const BASELINE_V1_S: f64 = 4.0;
const BASELINE_G2_S: f64 = 3.0;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn session(
    root: &Path,
    task: &str,
    practice: u32,
    trials: u32,
    script: &str,
    baseline: &Path,
    domain: u16,
) -> std::process::Output {
    let script_path = root.join(format!("{task}.script"));
    std::fs::write(&script_path, script).unwrap();
    let domain = domain.to_string();
    let practice = practice.to_string();
    let trials = trials.to_string();
    let output = run_pomdar(&[
        "trial",
        "--task",
        task,
        "--user",
        "sim",
        "--operator",
        "ci",
        "--practice",
        &practice,
        "--trials",
        &trials,
        "--simulate",
        "--domain-id",
        &domain,
        "--countdown",
        "0.5",
        "--baseline",
        s(baseline),
        "--script",
        s(&script_path),
        "--out",
        s(&root.join("sessions")),
    ]);
    eprintln!(
        "--- pomdar trial --task {task} stderr:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// One scripted trial: start, marks one second apart, stop, wait for its summary.
fn trial_lines(marks: &[&str]) -> String {
    let mut text = String::from("start\nwait running 60\n");
    for mark in marks {
        text.push_str(&format!("+1 {mark}\n"));
    }
    text.push_str("+1 stop\n");
    text
}

fn events(path: &Path) -> Vec<serde_json::Value> {
    read_trial_events(path)
        .unwrap()
        .events
        .iter()
        .map(|(_, text)| serde_json::from_str(text).unwrap())
        .collect()
}

fn names(events: &[serde_json::Value]) -> Vec<String> {
    events
        .iter()
        .map(|e| e["event"].as_str().unwrap().to_string())
        .collect()
}

/// The baseline table the sessions score against: V1 and G2.
fn write_baseline(root: &Path) -> PathBuf {
    let baseline = root.join("baseline.toml");
    std::fs::write(
        &baseline,
        format!(
            "[baseline]\nexample = false\nsource = \"console_session test\"\n\n[[task]]\nid = \"V1\"\nmean_s = {BASELINE_V1_S}\nn = 3\n\n[[task]]\nid = \"G2\"\nmean_s = {BASELINE_G2_S}\nn = 3\n"
        ),
    )
    .unwrap();
    baseline
}

/// V1: practice (1 notch), trial 1 (3 notches), trial 2 redone after its stop, trial 2
/// again (6 notches, one taken back), trial 3 (2 notches and a drop).
fn v1_script() -> String {
    let mut v1 = String::from("engage\nwait ready 60\n");
    v1.push_str(&trial_lines(&["progress"]));
    v1.push_str("wait summary 60\n");
    v1.push_str(&trial_lines(&["progress", "progress", "progress"]));
    v1.push_str("wait summary 60\n");
    v1.push_str(&trial_lines(&["progress"]));
    v1.push_str("wait summary 60\nredo\nnote trial 2 redone: the wheel was not reset\n");
    v1.push_str(&trial_lines(&[
        "progress", "progress", "progress", "progress", "progress", "progress", "progress",
        "unmark",
    ]));
    v1.push_str("wait summary 60\n");
    v1.push_str(&trial_lines(&[
        "progress",
        "drop",
        "progress",
        "note glove slipped",
    ]));
    v1.push_str("wait complete 60\n");
    v1
}

/// The V1 session's directory holds every trial's log (the redone one set aside), each
/// trial's review, its report, its manifest and the console's messages.
fn assert_v1_files(dir: &Path) {
    let mut files: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().to_string())
        .collect();
    files.sort();
    assert_eq!(
        files,
        [
            "V1-p01.mcap",
            "V1-t01.mcap",
            "V1-t02-a2.mcap",
            "V1-t02.mcap.redone",
            "V1-t03.mcap",
            "console.log",
            "report",
            "review",
            "session.json"
        ]
    );
    // What the console said, whole and stamped: the redo and the note among it.
    let said = std::fs::read_to_string(dir.join("console.log")).unwrap();
    assert!(
        said.lines().all(|l| l
            .split(' ')
            .next()
            .is_some_and(|t| t.len() == 16 && t.ends_with('Z'))),
        "{said}"
    );
    assert!(
        said.contains("note added to the session: trial 2 redone"),
        "{said}"
    );
    for trial in ["V1-p01", "V1-t01", "V1-t02-a2", "V1-t03"] {
        for ext in ["png", "svg", "json"] {
            let review = dir.join("review").join(format!("{trial}.review.{ext}"));
            assert!(review.is_file(), "{} is missing", review.display());
        }
    }
}

/// One V1 log: its metadata (practice or not, trial index), its events in order (`want`),
/// glove input and finite joint targets, every target inside the trial.
fn assert_v1_log(dir: &Path, file: &str, practice: &str, index: &str, want: &[&str]) {
    let path = dir.join(file);
    let log = read_trial_events(&path).unwrap();
    let meta = log.metadata_named("pomdar_trial").unwrap();
    assert_eq!(meta["task"], "V1", "{file}");
    assert_eq!(meta["embodiment"], "orca_full", "{file}");
    assert_eq!(meta["user"], "sim", "{file}");
    assert_eq!(meta["operator"], "ci", "{file}");
    assert_eq!(meta["practice"], practice, "{file}");
    assert_eq!(meta["trial_index"], index, "{file}");
    // Named by the simulated glove's status on /ingress/status, as an ingress names itself.
    assert_eq!(meta["keypoint_source"], "simulated", "{file}");
    assert!(
        meta["keypoint_device"].contains("simulated glove"),
        "{file}"
    );
    assert_eq!(names(&events(&path)), want, "{file}");
    let reader = TrialReader::open(&path).unwrap();
    let targets: Vec<JointState> = reader.decode_topic("/pomdar/hand/joint_targets").unwrap();
    let glove = reader.messages_on("/ingress/mano").count();
    assert!(
        glove > 50,
        "{file}: {glove} glove frames in a ≥ 2 s trial at 100 Hz"
    );
    assert!(
        targets.len() > 20,
        "{file}: {} joint targets in a ≥ 2 s trial at 25 Hz",
        targets.len()
    );
    assert!(
        targets
            .iter()
            .all(|t| t.position.iter().all(|v| v.is_finite()))
    );
    let (start, stop) = (log.events[0].0, log.events.last().unwrap().0);
    for m in reader.messages_on("/pomdar/hand/joint_targets") {
        assert!(
            m.log_time_ns >= start && m.log_time_ns <= stop,
            "{file}: a target outside the trial"
        );
    }
    assert!(reader.topic(TRIAL_EVENTS_TOPIC).is_some());
}

/// Each V1 log as the script made it; the taken-back mark and the note's text.
fn assert_v1_logs(dir: &Path) {
    assert_v1_log(
        dir,
        "V1-p01.mcap",
        "true",
        "1",
        &["start", "progress", "stop"],
    );
    assert_v1_log(
        dir,
        "V1-t01.mcap",
        "false",
        "1",
        &["start", "progress", "progress", "progress", "stop"],
    );
    assert_v1_log(
        dir,
        "V1-t02.mcap.redone",
        "false",
        "2",
        &["start", "progress", "stop"],
    );
    assert_v1_log(
        dir,
        "V1-t02-a2.mcap",
        "false",
        "2",
        &[
            "start", "progress", "progress", "progress", "progress", "progress", "progress",
            "progress", "progress", "stop",
        ],
    );
    assert_v1_log(
        dir,
        "V1-t03.mcap",
        "false",
        "3",
        &["start", "progress", "drop", "progress", "note", "stop"],
    );
    assert_eq!(events(&dir.join("V1-t02-a2.mcap"))[8]["value"], -1.0);
    assert_eq!(events(&dir.join("V1-t03.mcap"))[4]["text"], "glove slipped");
}

/// The manifest: every trial, its status and score; the session note. Returns its trials.
fn assert_v1_manifest(dir: &Path) -> Vec<serde_json::Value> {
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("session.json")).unwrap()).unwrap();
    assert_eq!(manifest["format"], "pomdar-session/1");
    assert_eq!(manifest["practice_planned"], 1);
    assert_eq!(manifest["trials_planned"], 3);
    assert_eq!(
        manifest["notes"][0],
        "trial 2 redone: the wheel was not reset"
    );
    let trials = manifest["trials"].as_array().unwrap();
    let rows: Vec<(&str, &str, f64)> = trials
        .iter()
        .map(|t| {
            (
                t["file"].as_str().unwrap(),
                t["status"].as_str().unwrap(),
                t["progress"].as_f64().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        rows,
        [
            ("V1-p01.mcap", "scored", 1.0),
            ("V1-t01.mcap", "scored", 3.0),
            ("V1-t02.mcap.redone", "redone", 1.0),
            ("V1-t02-a2.mcap", "scored", 6.0),
            ("V1-t03.mcap", "scored", 2.0),
        ]
    );
    for t in trials {
        let c = t["progress"].as_f64().unwrap().min(6.0) / 6.0;
        assert!((t["correctness"].as_f64().unwrap() - c).abs() < 1e-12);
        let time = t["time_s"].as_f64().unwrap();
        assert!(time > 1.5 && time < 30.0, "trial time {time}");
        let want = 0.8 * c + 0.2 * BASELINE_V1_S / time;
        assert!((t["score"].as_f64().unwrap() - want).abs() < 1e-9, "{t}");
        assert_eq!(t["outcome"], "completed");
    }
    trials.clone()
}

/// The session report: the three counted trials (of the manifest's `trials`), practice not
/// averaged, their mean in the Markdown; the console's last words (`stdout`).
fn assert_v1_report(dir: &Path, trials: &[serde_json::Value], stdout: &str) {
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report/scores.json")).unwrap())
            .unwrap();
    let text = report.to_string();
    assert!(dir.join("report/report.md").exists());
    let counted: Vec<f64> = trials
        .iter()
        .filter(|t| t["status"] == "scored" && t["practice"] == false)
        .map(|t| t["score"].as_f64().unwrap())
        .collect();
    assert_eq!(counted.len(), 3);
    let mean = counted.iter().sum::<f64>() / 3.0;
    assert!(
        text.contains("V1-t03.mcap") && !text.contains("redone"),
        "{text}"
    );
    assert!(
        stdout.contains("1 of 1 practice and 3 of 3 recorded trials done"),
        "{stdout}"
    );
    let md = std::fs::read_to_string(dir.join("report/report.md")).unwrap();
    assert!(
        md.contains(&format!("{mean:.2}")),
        "mean {mean:.2} not in the report:\n{md}"
    );
}

/// A grasp trial: levels are checked (0.7 refused), the last level counts, a drop is 0.5.
fn run_grasp_session(root: &Path, baseline: &Path) {
    let mut g2 = String::from("engage\nwait ready 60\n");
    g2.push_str(&trial_lines(&["progress 0.7", "progress 1", "drop"]));
    g2.push_str("wait complete 60\n");
    let out = session(root, "G2", 0, 1, &g2, baseline, test_domain());
    assert!(out.status.success(), "G2 session failed");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("grasp level 0.7: allowed 0"), "{stderr}");
    let gdir = root.join("sessions/sim/orca_full/G2");
    assert_eq!(
        names(&events(&gdir.join("G2-t01.mcap"))),
        ["start", "progress", "drop", "stop"]
    );
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(gdir.join("session.json")).unwrap()).unwrap();
    assert_eq!(manifest["trials"][0]["correctness"], 0.5);
}

/// `pomdar score` over both sessions agrees with the console.
fn assert_score_agrees(root: &Path, baseline: &Path) {
    let scored = run_pomdar(&[
        "score",
        s(&root.join("sessions")),
        "--baseline",
        s(baseline),
        "--json",
    ]);
    assert!(
        scored.status.success(),
        "{}",
        String::from_utf8_lossy(&scored.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&scored.stdout).unwrap();
    let trials = report["trials"].as_array().unwrap();
    assert_eq!(
        trials.len(),
        5,
        "4 V1 logs (the redone one set aside) and 1 G2"
    );
    let g = trials.iter().find(|t| t["task"] == "G2").unwrap();
    assert_eq!(g["correctness"], 0.5);
}

// Under a minute alone, one of the suite's longest: two whole sessions in real time (V1:
// practice, three trials, a redo; G2), each trial a few seconds of glove input as the console
// runs it.
#[test]
fn a_scripted_session_logs_scores_and_reports_every_trial() {
    let root = scratch_dir("console-session");
    let baseline = write_baseline(&root);

    let out = session(&root, "V1", 1, 3, &v1_script(), &baseline, test_domain());
    assert!(out.status.success(), "V1 session failed: {:?}", out.status);
    let dir = root.join("sessions/sim/orca_full/V1");
    assert_v1_files(&dir);
    assert_v1_logs(&dir);
    let trials = assert_v1_manifest(&dir);
    assert_v1_report(&dir, &trials, &String::from_utf8_lossy(&out.stdout));

    run_grasp_session(&root, &baseline);
    assert_score_agrees(&root, &baseline);
    std::fs::remove_dir_all(&root).ok();
}
