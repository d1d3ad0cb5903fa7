//! The human study end to end, on loopback DDS with simulated gloves: two participants each
//! do three tasks three times (`pomdar study --simulate`, each task a different simulated
//! motion, each participant their own hand size and trial times), and again with the same
//! motion for all three tasks. Every trial is recorded as a human trial; `pomdar baseline`'s
//! means equal the trial times read independently from the logs' events; a robot trial scored
//! against that table has speed = baseline / time; `pomdar study-report` finds the tasks
//! separated (silhouette > 0.5, "reasonable structure" by Kaufman & Rousseeuw's bands) when
//! the motions differ and not separated (< 0.25, "no substantial structure") when they do not.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Output;

use msgs::JointState;
use pomdar_tests::pomdar_binary::run_pomdar;
use pomdar_tests::scratch_dir;
use pomdar_tests::station_harness::test_domain;
use teleop::mcap_log::{TrialReader, read_trial_events};

const TASKS: [&str; 3] = ["V1", "C1", "G2"];
/// One simulated motion per task: the separated study.
const MOTIONS: &str = "open-close,pinches,abduction";
/// The same motion for every task: nothing to separate.
const SAME_MOTION: &str = "task-like";
/// Each participant's trial durations (seconds from start to stop, as scripted).
const PARTICIPANTS: [(&str, [f64; 3]); 2] = [("p1", [4.6, 5.2, 4.8]), ("p2", [5.5, 4.7, 5.0])];

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The console script of one task: three trials of the given durations.
fn study_script(durations: &[f64; 3]) -> String {
    let mut text = String::from("wait ready 60\n");
    for (i, d) in durations.iter().enumerate() {
        text.push_str(&format!("start\nwait running 60\n+{d} stop\n"));
        text.push_str(if i + 1 < durations.len() {
            "wait summary 60\n"
        } else {
            "wait complete 60\n"
        });
    }
    text
}

/// Starts `pomdar` with `args` on a thread; its output when it ends.
fn spawn_pomdar(args: Vec<String>) -> std::thread::JoinHandle<Output> {
    std::thread::spawn(move || {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        run_pomdar(&args)
    })
}

fn study_args(root: &Path, out: &str, participant: &str, motions: &str) -> Vec<String> {
    let durations = PARTICIPANTS.iter().find(|p| p.0 == participant).unwrap().1;
    let script = root.join(format!("{out}-{participant}.script"));
    std::fs::write(&script, study_script(&durations)).unwrap();
    [
        "study",
        "--participant",
        participant,
        "--operator",
        "ci",
        "--tasks",
        &TASKS.join(","),
        "--simulate",
        "--simulate-motion",
        motions,
        "--countdown",
        "0.5",
        "--plain",
        "--script",
        s(&script),
        "--domain-id",
        &test_domain().to_string(),
        "--out",
        s(&root.join(out)),
    ]
    .map(str::to_string)
    .to_vec()
}

/// A robot trial on V1 against `baseline`, and its session directory.
fn robot_args(root: &Path, baseline: &Path) -> Vec<String> {
    let script = root.join("robot.script");
    std::fs::write(
        &script,
        "engage\nwait ready 60\nstart\nwait running 60\n+3 stop\nwait complete 60\n",
    )
    .unwrap();
    [
        "trial",
        "--task",
        "V1",
        "--user",
        "robo",
        "--operator",
        "ci",
        "--practice",
        "0",
        "--trials",
        "1",
        "--simulate",
        "--countdown",
        "0.5",
        "--plain",
        "--script",
        s(&script),
        "--baseline",
        s(baseline),
        "--domain-id",
        &test_domain().to_string(),
        "--out",
        s(&root.join("robot")),
    ]
    .map(str::to_string)
    .to_vec()
}

fn assert_success(what: &str, output: &Output) {
    assert!(
        output.status.success(),
        "{what} failed ({:?}):\nstdout:\n{}\nstderr:\n{}",
        output.status.code(),
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Start and stop log times of a trial, from its events.
fn start_stop_ns(path: &Path) -> (i64, i64) {
    let events = read_trial_events(path).unwrap().events;
    let at = |name: &str| {
        events
            .iter()
            .find(|(_, text)| {
                serde_json::from_str::<serde_json::Value>(text).unwrap()["event"] == name
            })
            .map(|(t, _)| *t)
            .unwrap_or_else(|| panic!("{}: no {name} event", path.display()))
    };
    (at("start"), at("stop"))
}

/// Every trial of the separated study is a recorded human trial of its participant and task,
/// with the glove's keypoints and no joint target; returns the trial times by task.
fn assert_trials_recorded(dir: &Path) -> BTreeMap<String, Vec<f64>> {
    let mut times: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for (participant, durations) in PARTICIPANTS {
        for task in TASKS {
            let session = dir.join(participant).join("human").join(task);
            for (i, scripted) in durations.iter().enumerate() {
                let path = session.join(format!("{task}-t{:02}.mcap", i + 1));
                assert!(path.exists(), "{} missing", path.display());
                let reader = TrialReader::open(&path).unwrap();
                let meta = reader.metadata_named("pomdar_trial").unwrap();
                assert_eq!(meta["embodiment"], "human", "{}", path.display());
                assert_eq!(meta["user"], participant);
                assert_eq!(meta["task"], task);
                assert_eq!(meta["practice"], "false");
                let (start, stop) = start_stop_ns(&path);
                let time_s = (stop - start) as f64 * 1e-9;
                assert!(
                    (time_s - scripted).abs() < 1.0,
                    "{}: {time_s} s, scripted {scripted} s",
                    path.display()
                );
                let keypoints = reader.messages_on("/ingress/mano").count() as f64;
                assert!(
                    keypoints > 40.0 * time_s,
                    "{}: {keypoints} keypoint frames in {time_s:.1} s",
                    path.display()
                );
                assert!(reader.messages_on("/ingress/wrist").count() > 0);
                assert_eq!(
                    reader
                        .decode_topic::<JointState>("/pomdar/hand/joint_targets")
                        .unwrap()
                        .len(),
                    0,
                    "no robot in a human study"
                );
                times.entry(task.to_string()).or_default().push(time_s);
            }
        }
    }
    times
}

/// `pomdar baseline` over the study: its means are the trial times read from the logs.
fn assert_baseline(root: &Path, times: &BTreeMap<String, Vec<f64>>) -> BTreeMap<String, f64> {
    let baseline = root.join("baseline.toml");
    let output = run_pomdar(&[
        "baseline",
        s(&root.join("study")),
        "--out",
        s(&baseline),
        "--source",
        "human_study test",
    ]);
    assert_success("pomdar baseline", &output);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("p1") && stdout.contains("p2"),
        "per participant:\n{stdout}"
    );
    let table: toml::Value = toml::from_str(&std::fs::read_to_string(&baseline).unwrap()).unwrap();
    let mut means = BTreeMap::new();
    for entry in table["task"].as_array().unwrap() {
        let id = entry["id"].as_str().unwrap().to_string();
        let mean_s = entry["mean_s"].as_float().unwrap();
        let logged = &times[&id];
        let expected = logged.iter().sum::<f64>() / logged.len() as f64;
        assert!(
            (mean_s - expected).abs() < 1.5e-3,
            "{id}: baseline {mean_s} s, the logs say {expected} s"
        );
        assert_eq!(entry["n"].as_integer(), Some(6), "{id}");
        means.insert(id, mean_s);
    }
    assert_eq!(means.len(), 3, "{table}");
    means
}

/// A robot trial scored against the study's baseline: speed = baseline / time.
fn assert_robot_speed(root: &Path, baseline_v1_s: f64) {
    let out = root.join("robot_scores");
    let output = run_pomdar(&[
        "score",
        s(&root.join("robot")),
        "--baseline",
        s(&root.join("baseline.toml")),
        "--out",
        s(&out),
    ]);
    assert_success("pomdar score", &output);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("scores.json")).unwrap()).unwrap();
    let trial = &json["trials"][0];
    let file = PathBuf::from(trial["file"].as_str().unwrap());
    let (start, stop) = start_stop_ns(&file);
    let time_s = (stop - start) as f64 * 1e-9;
    let speed = trial["speed"].as_f64().unwrap();
    assert!(
        (speed - baseline_v1_s / time_s).abs() < 2e-3,
        "speed {speed}, baseline {baseline_v1_s} s / time {time_s} s = {}",
        baseline_v1_s / time_s
    );
}

/// `pomdar study-report` over a study: the overall silhouette, after checking the files.
fn strategy_silhouette(root: &Path, study: &str) -> f64 {
    let out = root.join(format!("{study}_report"));
    let output = run_pomdar(&["study-report", s(&root.join(study)), "--out", s(&out)]);
    assert_success("pomdar study-report", &output);
    for file in [
        "report.md",
        "strategy.json",
        "strategy_pc1_pc2.svg",
        "strategy_pc1_pc2.png",
        "strategy_pc1_pc3.svg",
        "strategy_pc1_pc3.png",
    ] {
        assert!(out.join(file).exists(), "{study}: {file} not written");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("strategy.json")).unwrap()).unwrap();
    assert_eq!(json["trials_used"], 18, "{study}");
    assert_eq!(json["participants"], 2, "{study}");
    assert_eq!(json["variance_explained"].as_array().unwrap().len(), 3);
    json["silhouette"].as_f64().unwrap()
}

// About a minute, one of the suite's longest: four studies of 9 real-time trials (two
// participants, separated and same motions) run side by side; the strategy check needs 3
// trials per task and participant, so none can be dropped.
#[test]
fn a_scripted_study_gives_the_baseline_the_scores_and_the_strategy_check() {
    let root = scratch_dir("human_study");
    let mut runs = Vec::new();
    for (participant, _) in PARTICIPANTS {
        runs.push(spawn_pomdar(study_args(
            &root,
            "study",
            participant,
            MOTIONS,
        )));
        runs.push(spawn_pomdar(study_args(
            &root,
            "same",
            participant,
            SAME_MOTION,
        )));
    }
    for run in runs {
        assert_success("pomdar study", &run.join().unwrap());
    }
    let times = assert_trials_recorded(&root.join("study"));
    let means = assert_baseline(&root, &times);

    let robot = run_pomdar(
        &robot_args(&root, &root.join("baseline.toml"))
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>(),
    );
    assert_success("pomdar trial (robot)", &robot);
    assert_robot_speed(&root, means["V1"]);

    let separated = strategy_silhouette(&root, "study");
    let same = strategy_silhouette(&root, "same");
    eprintln!("silhouette: {separated:.3} with a motion per task, {same:.3} with one motion");
    assert!(separated > 0.5, "tasks not separated: {separated}");
    assert!(same < 0.25, "one motion separated by task label: {same}");
}
