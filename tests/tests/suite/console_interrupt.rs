//! Ctrl-C and a killed console mid-trial: no finished trial is lost, the station stops
//! commanding (the robot hears nothing more and holds its last target), and the session
//! resumes where it stopped. The glove is a `pomdar sim-glove` process, the console a
//! `pomdar trial` line console driven through its stdin, the robot's command listener is in
//! this process; all on loopback DDS.

use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use futures::StreamExt;
use msgs::JointState;
use pomdar_tests::line_console::{LineConsole, Process};
use pomdar_tests::pomdar_binary::{pomdar_binary, run_pomdar};
use pomdar_tests::station_harness::{loopback, test_domain};
use pomdar_tests::{scratch_dir, session_trial_statuses, trial_event_names};
use teleop::ros::NetworkContext as _;
use teleop::ros::{QosConfig, RosNode};

fn console_args(dir: &Path, domain: u16) -> Vec<String> {
    [
        "trial",
        "--task",
        "V1",
        "--user",
        "kill",
        "--operator",
        "ci",
        "--practice",
        "0",
        "--trials",
        "3",
        "--plain",
        "--countdown",
        "0.3",
        "--interface",
        "127.0.0.1",
        "--domain-id",
    ]
    .iter()
    .map(|s| s.to_string())
    .chain([
        domain.to_string(),
        "--out".to_string(),
        dir.display().to_string(),
    ])
    .collect()
}

fn manifest(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("session.json")).unwrap()).unwrap()
}

/// Joint targets the robot heard: receive times.
type Heard = Arc<Mutex<Vec<Instant>>>;

/// Asserts the robot heard commands before `stopped` and none from `grace` after it.
fn assert_silent_after(heard: &Heard, stopped: Instant, what: &str) {
    std::thread::sleep(Duration::from_millis(1500));
    let times = heard.lock().unwrap().clone();
    let before = times.iter().filter(|t| **t < stopped).count();
    let late: Vec<f64> = times
        .iter()
        .filter(|t| **t > stopped + Duration::from_millis(300))
        .map(|t| t.duration_since(stopped).as_secs_f64())
        .collect();
    assert!(
        before > 20,
        "{what}: only {before} joint targets before the stop"
    );
    assert!(
        late.is_empty(),
        "{what}: the robot still heard {} commands, at {late:?} s",
        late.len()
    );
}

/// The robot's command listener: every joint target heard on `/pomdar/hand/joint_targets`.
struct RobotEar {
    heard: Heard,
    listener: tokio::task::JoinHandle<()>,
    /// Keeps the subscription's node alive for the test.
    _node: RosNode,
}

impl RobotEar {
    fn start(domain: u16) -> RobotEar {
        let context = loopback(domain).context().unwrap();
        let mut node = RosNode::new(&context, "/", "robot").unwrap();
        let sub = node
            .subscription::<JointState>("/pomdar/hand/joint_targets", QosConfig::reliable(50))
            .unwrap();
        let heard: Heard = Arc::default();
        let ear = heard.clone();
        let listener = tokio::spawn(async move {
            let mut stream = Box::pin(sub.async_stream());
            while let Some(item) = stream.next().await {
                if item.is_ok() {
                    ear.lock().unwrap().push(Instant::now());
                }
            }
        });
        RobotEar {
            heard,
            listener,
            _node: node,
        }
    }
}

/// A `pomdar sim-glove` publishing on loopback `domain`.
fn start_glove(domain: u16) -> Process {
    Process(
        Command::new(pomdar_binary().unwrap())
            .args([
                "sim-glove",
                "--interface",
                "127.0.0.1",
                "--domain-id",
                &domain.to_string(),
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap(),
    )
}

/// 1. Ctrl-C during trial 2: trial 1 stays scored, trial 2 is logged as aborted
///    ("interrupted") and set aside; exit status 130; the station stops commanding.
fn ctrl_c_during_trial_two(root: &Path, dir: &Path, domain: u16, heard: &Heard) {
    let mut console = LineConsole::start(&console_args(root, domain));
    console.wait_for("WAITING FOR ENGAGE", 30.0);
    console.say("engage");
    console.wait_for("engaged", 30.0);
    console.say("start");
    console.wait_for("RUNNING · trial 1/3", 30.0);
    console.say("progress");
    console.say("progress");
    std::thread::sleep(Duration::from_millis(1000));
    console.say("stop");
    console.wait_for("last trial 1: completed", 30.0);
    console.say("start");
    console.wait_for("RUNNING · trial 2/3", 30.0);
    console.say("progress");
    std::thread::sleep(Duration::from_millis(1000));
    let status = Command::new("kill")
        .args(["-INT", &console.pid()])
        .status()
        .unwrap();
    assert!(status.success());
    let code = console.process.0.wait().unwrap().code();
    let stopped = Instant::now();
    assert_eq!(code, Some(130), "{}", console.stderr.lock().unwrap());
    assert_silent_after(heard, stopped, "after Ctrl-C");
    assert_eq!(
        session_trial_statuses(dir),
        [
            ("V1-t01.mcap".to_string(), "scored".to_string()),
            (
                "V1-t02.mcap.interrupted".to_string(),
                "interrupted".to_string()
            )
        ]
    );
    assert_eq!(
        trial_event_names(&dir.join("V1-t01.mcap")),
        ["start", "progress", "progress", "stop"]
    );
    assert_eq!(
        trial_event_names(&dir.join("V1-t02.mcap.interrupted")),
        ["start", "progress", "abort", "stop"]
    );
    assert_eq!(manifest(dir)["trials"][0]["progress"], 2.0);
}

/// 2. Resumed at trial 2, then SIGKILL mid-trial: the manifest still holds everything
///    finished, the running trial's log is a .part, the robot hears nothing more.
fn sigkill_after_resuming(root: &Path, dir: &Path, domain: u16, heard: &Heard) {
    let mut console = LineConsole::start(&console_args(root, domain));
    console.wait_for("resumed", 30.0);
    console.say("engage");
    console.wait_for("engaged", 30.0);
    console.say("start");
    console.wait_for("RUNNING · trial 2/3", 30.0);
    console.say("progress");
    std::thread::sleep(Duration::from_millis(1500));
    console.process.0.kill().unwrap();
    console.process.0.wait().unwrap();
    let stopped = Instant::now();
    assert_silent_after(heard, stopped, "after SIGKILL");
    assert!(dir.join("V1-t02-a2.mcap.part").exists());
    assert_eq!(
        session_trial_statuses(dir).len(),
        2,
        "the manifest is as the Ctrl-C left it"
    );
    assert_eq!(
        trial_event_names(&dir.join("V1-t01.mcap")),
        ["start", "progress", "progress", "stop"]
    );
}

/// 3. Resumed by a script: the .part is recovered and set aside, trials 2 and 3 run.
fn finish_by_script(root: &Path, dir: &Path, domain: u16) {
    let script = root.join("finish.script");
    std::fs::write(
        &script,
        "engage\nwait ready 60\nstart\nwait running 60\n+1 progress\n+1 stop\nwait summary 60\nstart\nwait running 60\n+1 stop\nwait complete 60\n",
    )
    .unwrap();
    let mut args = console_args(root, domain);
    args.extend(["--script".to_string(), script.display().to_string()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = run_pomdar(&args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("V1-t02-a2.mcap.part: interrupted"),
        "{stderr}"
    );
    assert_eq!(
        session_trial_statuses(dir),
        [
            ("V1-t01.mcap", "scored"),
            ("V1-t02.mcap.interrupted", "interrupted"),
            ("V1-t02-a2.mcap.interrupted", "interrupted"),
            ("V1-t02-a3.mcap", "scored"),
            ("V1-t03.mcap", "scored"),
        ]
        .map(|(f, s)| (f.to_string(), s.to_string()))
    );
    // The recovered log keeps what was flushed before the kill: the start and the mark.
    let recovered = trial_event_names(&dir.join("V1-t02-a2.mcap.interrupted"));
    assert_eq!(&recovered[..2], ["start", "progress"], "{recovered:?}");
    assert!(!dir.join("V1-t02-a2.mcap.part").exists());
    assert_eq!(manifest(dir)["runs"], 3);
    assert!(dir.join("report/report.md").exists());
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ctrl_c_or_a_kill_mid_trial_loses_no_finished_trial_and_the_robot_holds() {
    let domain = test_domain();
    let root = scratch_dir("console-interrupt");
    let dir = root.join("kill/orca_full/V1");

    // The robot's ear and the glove.
    let robot = RobotEar::start(domain);
    let _glove = start_glove(domain);

    ctrl_c_during_trial_two(&root, &dir, domain, &robot.heard);
    sigkill_after_resuming(&root, &dir, domain, &robot.heard);
    finish_by_script(&root, &dir, domain);
    robot.listener.abort();
    std::fs::remove_dir_all(&root).ok();
}
