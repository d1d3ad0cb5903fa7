//! The real full-screen console in a pseudo-terminal: `pomdar trial --simulate` runs under
//! util-linux `script` (a pty of 30 × 110), keys are typed into it, and its output is parsed
//! back into a screen (vt100) and checked for the main states: waiting for engage, counting
//! down, running (timer and marks), the trial summary; then q quits and the terminal is
//! restored.

use std::io::{Read as _, Write as _};
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use pomdar_tests::pomdar_binary::pomdar_binary;
use pomdar_tests::scratch_dir;
use pomdar_tests::station_harness::test_domain;

const ROWS: u16 = 30;
const COLS: u16 = 110;
/// Longest wait for a screen (an upper bound for a loaded machine; a pass takes a second).
const WAIT_S: f64 = 30.0;

/// The console's process, killed when dropped so a failing test leaves nothing running.
struct Console {
    child: std::process::Child,
    screen: Arc<Mutex<vt100::Parser>>,
    /// Where the sessions go (their console.log is shown when a wait fails).
    sessions: std::path::PathBuf,
}

impl Drop for Console {
    fn drop(&mut self) {
        self.child.kill().ok();
        self.child.wait().ok();
    }
}

impl Console {
    fn contents(&self) -> String {
        self.screen.lock().unwrap().screen().contents()
    }

    /// Waits until the screen contains every one of `texts`.
    fn wait_for(&self, texts: &[&str], timeout_s: f64) -> String {
        let start = Instant::now();
        loop {
            let screen = self.contents();
            if texts.iter().all(|t| screen.contains(t)) {
                return screen;
            }
            assert!(
                start.elapsed().as_secs_f64() < timeout_s,
                "waited {timeout_s} s for {texts:?}; the screen shows:\n{screen}\n{}",
                self.message_logs()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// Every console.log under the sessions directory, whole (the screen shows one line of
    /// each message).
    fn message_logs(&self) -> String {
        let mut logs = String::new();
        let mut dirs = vec![self.sessions.clone()];
        while let Some(dir) = dirs.pop() {
            for entry in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
                let path = entry.path();
                if path.is_dir() {
                    dirs.push(path);
                } else if path.file_name().is_some_and(|n| n == "console.log") {
                    let text = std::fs::read_to_string(&path).unwrap_or_default();
                    logs.push_str(&format!("--- {}\n{text}", path.display()));
                }
            }
        }
        logs
    }

    fn press(&mut self, keys: &str) {
        let stdin = self.child.stdin.as_mut().unwrap();
        stdin.write_all(keys.as_bytes()).unwrap();
        stdin.flush().unwrap();
    }
}

fn script_available() -> bool {
    Command::new("script")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

impl Console {
    /// `pomdar trial --simulate` (two recorded V2 trials, sessions under `dir`) under
    /// `script` in a 30 × 110 pty; its output parsed into the screen as it comes.
    fn start(dir: &Path) -> Console {
        let binary = pomdar_binary().unwrap();
        let command = format!(
            "stty rows {ROWS} cols {COLS} && exec '{}' trial --task V2 --user pty --operator ci --practice 0 --trials 2 --simulate --domain-id {} --countdown 3 --out '{}'",
            binary.display(),
            test_domain(),
            dir.join("sessions").display()
        );
        let mut child = Command::new("script")
            .args(["-q", "-f", "-e", "-c", &command, "/dev/null"])
            .env("TERM", "xterm-256color")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let screen = Arc::new(Mutex::new(vt100::Parser::new(
            ROWS.try_into().unwrap(),
            COLS.try_into().unwrap(),
            0,
        )));
        let mut stdout = child.stdout.take().unwrap();
        let feed = screen.clone();
        std::thread::spawn(move || {
            let mut buffer = [0u8; 4096];
            while let Ok(n) = stdout.read(&mut buffer) {
                if n == 0 {
                    break;
                }
                feed.lock().unwrap().process(&buffer[..n]);
            }
        });
        Console {
            child,
            screen,
            sessions: dir.join("sessions"),
        }
    }
}

/// Waiting for engage: the task, its instruction, the health, the key bar; a start is
/// refused before engaging; then engaged and ready.
fn engage(console: &mut Console) {
    let s = console.wait_for(
        &[
            "WAITING FOR ENGAGE",
            "V2 Stick",
            "press + at each of the 6 notches",
            "e engage/clutch",
            "input age",
        ],
        2.0 * WAIT_S,
    );
    assert!(
        s.contains("POMDAR trial console") && s.contains("Health") && s.contains("glove"),
        "{s}"
    );
    console.press(" ");
    console.wait_for(&["cannot start: "], WAIT_S);
    console.press("e");
    console.wait_for(&["READY", "drive", "engaged", "trial 1/2"], WAIT_S);
}

/// Trial 1: counting down, running (timer, two marks, a note typed into the prompt), then the
/// trial summary with its correctness and what comes next.
fn run_first_trial(console: &mut Console) {
    console.press(" ");
    console.wait_for(&["COUNTING DOWN"], WAIT_S);
    let s = console.wait_for(&["RUNNING", "V2-t01.mcap"], WAIT_S);
    assert!(s.contains("00:0"), "the running timer: {s}");
    console.press("++");
    console.wait_for(&["marked: 2 notches"], WAIT_S);
    // A note typed into the prompt.
    console.press("n");
    console.wait_for(&["note: "], WAIT_S);
    console.press("wheel stiff\r");
    console.wait_for(&["note logged: wheel stiff"], WAIT_S);
    console.press(" ");
    let s = console.wait_for(
        &[
            "TRIAL SUMMARY",
            "last trial 1: completed",
            "correctness 0.333",
            "recorded trials: 1/2 done",
        ],
        15.0,
    );
    assert!(s.contains("next: trial 2/2"), "{s}");
    assert!(
        s.contains("hand 1 listening"),
        "the mock hand is the one listener: {s}"
    );
}

/// q between trials quits (exit 0) and restores the terminal (the alternate screen left);
/// the session is not complete and says how to resume.
fn quit_between_trials(console: &mut Console) {
    console.press("q");
    let status = console.child.wait().unwrap();
    assert_eq!(status.code(), Some(0), "screen:\n{}", console.contents());
    std::thread::sleep(Duration::from_millis(200));
    let parser = console.screen.lock().unwrap();
    assert!(
        !parser.screen().alternate_screen(),
        "the alternate screen was left"
    );
    let end = parser.screen().contents();
    assert!(
        end.contains("1 of 2 recorded trials done") && end.contains("resume"),
        "{end}"
    );
}

#[test]
fn the_full_screen_console_shows_its_states_and_restores_the_terminal() {
    if !script_available() {
        assert!(
            !pomdar_tests::interop::under_ci(),
            "util-linux `script` is needed for the pty test in CI"
        );
        eprintln!("SKIPPED: util-linux `script` (a pseudo-terminal) is not available here");
        return;
    }
    let _no_flood_beside = pomdar_tests::load_turns::real_time();
    let dir = scratch_dir("console-screen");
    let mut console = Console::start(&dir);
    engage(&mut console);
    run_first_trial(&mut console);
    quit_between_trials(&mut console);
    let manifest: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("sessions/pty/orca_full/V2/session.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(manifest["trials"][0]["progress"], 2.0);
    std::fs::remove_dir_all(&dir).ok();
}
