//! Ctrl-C in the middle of a calibration fit: the fit stops, no profile is written
//! (an existing one is left as it was) and the exit status is 130. `pomdar calibrate --from`
//! is interrupted once in the Bayesian search and once in the Nelder–Mead polish, the line
//! console (`--simulate --plain`, loopback DDS) once in the fit after its session. The
//! `--from` session is a synthetic user's, written here without DDS; each fit is made long
//! with a settings file, and the signal is sent (`kill -INT`) once the fit's progress lines
//! on stderr show it is in the stage.

use std::collections::BTreeMap;
use std::ffi::OsStr;
use std::io::{BufRead as _, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Duration;

use calibration::{CAPTURE_RATE_HZ, CaptureSchedule, POSE_NAMES, PoseSet, SyntheticUser};
use msgs::Float32MultiArray;
use pomdar_tests::path_arg;
use pomdar_tests::pomdar_binary::pomdar_binary;
use pomdar_tests::station_harness::test_domain;
use retarget::HandModel;
use station::StationConfig;
use teleop::calibrate::session_events::{SESSION_METADATA, capture_event};
use teleop::mcap_log::{OfferedQos, TrialWriter, TrialWriterOptions};

/// This file's scratch directory (its tests share the session).
fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pomdar-fit-interrupt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A synthetic user's session log: the metadata the fit reads, and each pose's capture window
/// with its keypoint frames (25 Hz, on the default station's keypoint topic).
fn session() -> &'static Path {
    static SESSION: OnceLock<PathBuf> = OnceLock::new();
    SESSION.get_or_init(|| {
        let path = scratch().join("session.mcap");
        let station = StationConfig::default();
        let layout = station.retarget.layout;
        let topic = station.input.keypoints_topic.clone();
        let model = HandModel::orca_v1_right();
        let copies = calibration::human_copies(&model, &PoseSet::orca_v1()).unwrap();
        let schedule = CaptureSchedule::default();
        let user = SyntheticUser::random(11);
        let mut writer = TrialWriter::create(&path, TrialWriterOptions::default()).unwrap();
        writer
            .add_channel::<Float32MultiArray>(&topic, &[OfferedQos::from(station.input.qos)])
            .unwrap();
        let metadata = BTreeMap::from([
            ("layout".to_string(), layout.name().to_string()),
            ("keypoints_topic".to_string(), topic.clone()),
            ("model".to_string(), model.name().to_string()),
        ]);
        writer.write_metadata(SESSION_METADATA, metadata).unwrap();
        let ns = |t_s: f64| (t_s * 1e9).round() as i64;
        for (k, pose) in POSE_NAMES.iter().enumerate() {
            let (start, end) = schedule.capture_window(k);
            writer
                .write_event(ns(start), &capture_event(pose, true))
                .unwrap();
            let frames = user
                .capture_frames(layout, &schedule, &copies, k, CAPTURE_RATE_HZ)
                .unwrap();
            for (i, frame) in frames.iter().enumerate() {
                let at = ns(start + i as f64 / CAPTURE_RATE_HZ);
                let rows: Vec<[f32; 3]> = frame
                    .iter()
                    .map(|p| [p.x as f32, p.y as f32, p.z as f32])
                    .collect();
                let message = Float32MultiArray::from_points(&rows).unwrap();
                writer.write(&topic, at, at, &message).unwrap();
            }
            writer
                .write_event(ns(end), &capture_event(pose, false))
                .unwrap();
        }
        writer.finish().unwrap().path
    })
}

/// A settings file giving the fit `evaluations` Bayesian evaluations (`initial` of them the
/// initial design) and 2 × `polish` polish evaluations.
fn settings(name: &str, evaluations: usize, initial: usize, polish: usize) -> PathBuf {
    let path = scratch().join(name);
    let text = format!(
        "[optimiser]\nevaluations = {evaluations}\ninitial_design = {initial}\npolish_evaluations = {polish}\n"
    );
    std::fs::write(&path, text).unwrap();
    path
}

/// `pomdar calibrate` running, its stderr read line by line on a thread.
struct Fit {
    child: Child,
    lines: mpsc::Receiver<String>,
    stderr: Arc<Mutex<String>>,
    /// The thread reading stderr: joined after the exit, so that nothing printed is missed.
    reader: Option<std::thread::JoinHandle<()>>,
}

impl Fit {
    /// `pomdar calibrate --user cut --out OUT --settings SETTINGS` and `more`.
    fn start(out: &Path, settings: &Path, more: &[&OsStr]) -> Fit {
        let mut child = Command::new(pomdar_binary().unwrap())
            .args(["calibrate", "--user", "cut", "--out"])
            .arg(out)
            .arg("--settings")
            .arg(settings)
            .args(more)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let (tx, lines) = mpsc::channel();
        let stderr = Arc::new(Mutex::new(String::new()));
        let text = Arc::clone(&stderr);
        let pipe = child.stderr.take().unwrap();
        let reader = std::thread::spawn(move || {
            for line in BufReader::new(pipe).lines().map_while(Result::ok) {
                let mut all = text.lock().unwrap();
                all.push_str(&line);
                all.push('\n');
                tx.send(line).ok();
            }
        });
        Fit {
            child,
            lines,
            stderr,
            reader: Some(reader),
        }
    }

    /// Waits for a progress line (`[###...] DONE/BUDGET best …`) with at least `done`
    /// evaluations; returns its count.
    fn wait_for_evaluations(&mut self, done: usize) -> usize {
        loop {
            let line = self
                .lines
                .recv_timeout(Duration::from_secs(120))
                .unwrap_or_else(|e| panic!("no progress line ({e}):\n{}", self.printed()));
            if let Some(n) = evaluations_done(&line)
                && n >= done
            {
                return n;
            }
        }
    }

    /// Sends SIGINT and waits for the exit status.
    fn interrupt(&mut self) -> Option<i32> {
        let status = Command::new("kill")
            .args(["-INT", &self.child.id().to_string()])
            .status()
            .unwrap();
        assert!(status.success(), "kill -INT failed");
        let code = self.child.wait().unwrap().code();
        if let Some(reader) = self.reader.take() {
            reader.join().unwrap();
        }
        code
    }

    fn printed(&self) -> String {
        self.stderr.lock().unwrap().clone()
    }
}

/// The evaluations done in a fit's progress line, `[#####.....] 52/100 best 0.213 rad`.
fn evaluations_done(line: &str) -> Option<usize> {
    let (bar, rest) = line.strip_prefix('[')?.split_once("] ")?;
    if !bar.chars().all(|c| c == '#' || c == '.') {
        return None;
    }
    let (fraction, _) = rest.split_once(" best ")?;
    fraction.split_once('/')?.0.parse().ok()
}

/// Interrupts `fit` once it has made `done` evaluations and checks it ended with status 130,
/// saying `said`, with nothing written to `out`.
fn interrupt_after(mut fit: Fit, out: &Path, done: usize, said: &str) -> String {
    let seen = fit.wait_for_evaluations(done);
    let code = fit.interrupt();
    let printed = fit.printed();
    assert_eq!(code, Some(130), "interrupted after {seen}:\n{printed}");
    assert!(printed.contains(said), "{printed}");
    assert!(
        !PathBuf::from(format!("{}.part", out.display())).exists(),
        ".part left behind"
    );
    printed
}

/// What `--from` says when interrupted.
const FROM_INTERRUPTED: &str = "calibration interrupted (Ctrl-C): no profile written";

#[test]
fn ctrl_c_in_the_bayesian_search_writes_no_profile_and_exits_130() {
    // 300 Bayesian evaluations: the Gaussian process is refitted at each, so minutes of work.
    let settings = settings("bayesian.toml", 300, 20, 1000);
    let out = scratch().join("profiles").join("bayesian.toml");
    std::fs::remove_file(&out).ok();
    // Past the initial design: in the Bayesian iterations.
    let fit = Fit::start(
        &out,
        &settings,
        &[OsStr::new("--from"), session().as_os_str()],
    );
    interrupt_after(fit, &out, 30, FROM_INTERRUPTED);
    assert!(!out.exists(), "a profile was written after Ctrl-C");
}

#[test]
fn ctrl_c_in_the_polish_leaves_an_existing_profile_untouched_and_exits_130() {
    // 10 Bayesian evaluations, then 2 × 1000 Nelder–Mead evaluations.
    let settings = settings("polish.toml", 10, 5, 1000);
    let out = scratch().join("profiles").join("polish.toml");
    std::fs::create_dir_all(out.parent().unwrap()).unwrap();
    let existing = "# an earlier profile, to be left as it is\n";
    std::fs::write(&out, existing).unwrap();
    // Past the Bayesian search: in the first polish.
    let fit = Fit::start(
        &out,
        &settings,
        &[OsStr::new("--from"), session().as_os_str()],
    );
    interrupt_after(fit, &out, 40, FROM_INTERRUPTED);
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        existing,
        "the existing profile was replaced after Ctrl-C"
    );
}

#[test]
fn ctrl_c_during_the_console_fit_writes_no_profile_keeps_the_session_and_exits_130() {
    let settings = settings("console.toml", 300, 20, 1000);
    let out = scratch().join("profiles").join("console.toml");
    let session = scratch().join("console-session.mcap");
    std::fs::remove_file(&out).ok();
    let domain = test_domain().to_string();
    let more = [
        "--simulate",
        "--plain",
        "--session-out",
        path_arg(&session),
        "--domain-id",
        &domain,
    ]
    .map(OsStr::new);
    let fit = Fit::start(&out, &settings, &more);
    let printed = interrupt_after(
        fit,
        &out,
        30,
        "calibration interrupted (Ctrl-C) during the fit: no profile written",
    );
    assert!(printed.contains("FITTING"), "{printed}");
    assert!(!out.exists(), "a profile was written after Ctrl-C");
    assert!(session.exists(), "the session log is kept");
}

#[test]
fn the_progress_line_parser_reads_the_count() {
    assert_eq!(
        evaluations_done("[#####.....] 52/100 best 0.213 rad"),
        Some(52)
    );
    assert_eq!(evaluations_done("calibration interrupted"), None);
    let capture = "[####......] GOOD · jitter 7.3 mm at little_tip (limit 12.0) · 100/101 frames";
    assert_eq!(evaluations_done(capture), None);
    assert_eq!(evaluations_done("[    2.7 s] [2/7] pinch_middle: …"), None);
}
