//! The operator console killed with SIGKILL at 20 random moments and resumed each time with
//! the same command, until its sessions are complete: two tasks (V1, G2) of three scripted
//! trials each, `pomdar trial --simulate` (glove, hand and arm simulated in the process, on
//! loopback DDS).
//!
//! The moments are drawn by a seeded generator (the seed is printed; `POMDAR_KILL_SEED=N`
//! draws the same moments again, where they land may still shift with the machine's timing)
//! from a deck that covers the console's whole life: the start of a resumed process (its
//! first 1.2 s), a running trial, a finished trial's log being saved and scored, the manifest
//! just saved, the report being written, and the recovery of a `.part` log on resume. The saving steps take milliseconds, so the console runs with its test-only
//! slow-down `POMDAR_CONSOLE_TEST_PAUSE_MS` (a pause at each step, announced on stderr) and a
//! kill aimed at a step lands at a random point of its pause. Each kill's phase is read from
//! the console's last line before it and the files it left, and printed in a table.
//!
//! Asserted: no finished trial is lost (every log finished or set aside before a kill is still
//! there at the end with the same bytes, readable, and in the manifest); the trial running at
//! a kill loses at most 1 s (its recovered `.interrupted` log ends within 1 s of the kill's
//! wall time; the station stamps its logs with a wall-anchored clock); the manifest is valid
//! after every kill; every run not killed exits successfully and the sessions end complete,
//! with every planned trial scored, no `.part` left and the report written.

use station::fuzz::rng::FuzzRng as Rng;
use std::collections::BTreeMap;
use std::io::{BufRead as _, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use pomdar_tests::pomdar_binary::pomdar_binary;
use pomdar_tests::scratch_dir;
use pomdar_tests::station_harness::test_domain;
use teleop::console::manifest::{Manifest, ManifestFile, TrialStatus};
use teleop::console::message_log::MESSAGE_LOG_FILE;
use teleop::console::test_pause::TEST_PAUSE_ENV;
use teleop::mcap_log::TrialReader;

/// Kills over the whole test, half of them in each task's session.
const KILLS: usize = 20;
/// The console's pause at each saving step, ms.
const PAUSE_MS: u64 = 400;
/// Recorded trials per task.
const TRIALS: usize = 3;
/// The tasks and the progress mark their scripts give.
const TASKS: [(&str, &str); 2] = [("V1", "progress"), ("G2", "progress 1")];
/// A scripted trial's length, start to stop, s (the script: +2.5 s mark, +1 s stop).
const TRIAL_S: f64 = 3.5;
/// The longest a run may take to reach its kill or its end.
const RUN_TIMEOUT: Duration = Duration::from_secs(90);
/// How much of the running trial a kill may lose (the bound the console promises), ms.
const MAX_LOSS_MS: f64 = 1000.0;

fn unix_ns() -> i64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .unwrap()
        .as_nanos() as i64
}

/// Uniform in [low, high) ms, from the seeded generator (the kill moments, reproducible from
/// the seed).
fn millis(rng: &mut Rng, low: u64, high: u64) -> Duration {
    Duration::from_millis(low + rng.below((high - low).max(1) as usize) as u64)
}

/// The seed: `POMDAR_KILL_SEED`, else the clock.
fn seed() -> u64 {
    std::env::var("POMDAR_KILL_SEED")
        .ok()
        .and_then(|s| s.trim().parse().ok())
        .unwrap_or_else(|| unix_ns() as u64 | 1)
}

/// What a kill aims at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Aim {
    /// The first 1.2 s of the (resumed) process: opening the session (recovering, entering
    /// what a kill left, saving the manifest), starting the station, engaging.
    StartUp,
    /// A running trial.
    Running,
    /// A trial's log finished by the station, being scored for the manifest.
    TrialSaved,
    /// The manifest written after a trial.
    Manifest,
    /// The report written when the session is complete.
    Report,
    /// A `.part` log recovered on resume.
    Recovery,
}

impl Aim {
    /// The console's line that opens the aimed moment (`None`: the process start).
    fn marker(self) -> Option<&'static str> {
        match self {
            Aim::StartUp => None,
            Aim::Running => Some("] RUNNING ·"),
            Aim::TrialSaved => Some("finished: scoring it"),
            Aim::Manifest => Some("the manifest saved"),
            Aim::Report => Some("writing its report"),
            Aim::Recovery => Some("opening the session"),
        }
    }
}

/// Each task's kills before shuffling: every moment of the console's life, several times.
/// A kill aimed at a trial's saving or its manifest comes after the run's first trial (one
/// trial done per such kill); the report comes once one trial or none is left.
const DECK: [(Aim, usize); 6] = [
    (Aim::Running, 3),
    (Aim::StartUp, 3),
    (Aim::TrialSaved, 1),
    (Aim::Manifest, 1),
    (Aim::Report, 1),
    (Aim::Recovery, 1),
];

fn shuffled_deck(rng: &mut Rng) -> Vec<Aim> {
    let mut deck: Vec<Aim> = DECK
        .iter()
        .flat_map(|(aim, n)| std::iter::repeat_n(*aim, *n))
        .collect();
    for i in (1..deck.len()).rev() {
        let j = rng.below(i + 1);
        deck.swap(i, j);
    }
    deck
}

/// The names of the files in `dir`, sorted.
fn file_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .map(|listed| {
            listed
                .flatten()
                .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
                .map(|e| e.file_name().to_string_lossy().to_string())
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}

/// Whether `name` is a finished trial log of `task` (`V1-t02.mcap`, `V1-t02-a3.mcap`).
fn finished_log(name: &str, task: &str) -> bool {
    name.starts_with(&format!("{task}-t")) && name.ends_with(".mcap")
}

/// Recorded trials still to run: the plan less the finished logs in the directory.
fn trials_left(dir: &Path, task: &str) -> usize {
    let done = file_names(dir)
        .iter()
        .filter(|n| finished_log(n, task))
        .count();
    TRIALS.saturating_sub(done)
}

/// The operator's script for the trials left: engage, then each trial (a mark after 2.5 s,
/// the stop a second later).
fn script(left: usize, mark: &str) -> String {
    if left == 0 {
        return "wait complete 30\n".to_string();
    }
    let mut text = String::from("engage\nwait ready 60\n");
    for i in 0..left {
        text.push_str(&format!("start\nwait running 60\n+2.5 {mark}\n+1 stop\n"));
        text.push_str(if i + 1 == left {
            "wait complete 60\n"
        } else {
            "wait summary 60\n"
        });
    }
    text
}

/// One task's session: its command line and where it writes.
struct Session {
    task: &'static str,
    mark: &'static str,
    args: Vec<String>,
    dir: PathBuf,
    script: PathBuf,
}

impl Session {
    fn new(root: &Path, task: &'static str, mark: &'static str, domain: u16) -> Session {
        let script = root.join(format!("{task}.script"));
        let args = [
            "trial",
            "--task",
            task,
            "--user",
            "kills",
            "--operator",
            "ci",
            "--practice",
            "0",
            "--trials",
            &TRIALS.to_string(),
            "--simulate",
            "--domain-id",
            &domain.to_string(),
            "--countdown",
            "0.3",
            "--min-glove-rate",
            "5",
            "--baseline",
            root.join("baseline.toml").to_str().unwrap(),
            "--script",
            script.to_str().unwrap(),
            "--out",
            root.join("sessions").to_str().unwrap(),
        ]
        .map(String::from)
        .to_vec();
        Session {
            task,
            mark,
            args,
            dir: root.join("sessions/kills/orca_full").join(task),
            script,
        }
    }
}

/// A running console: its process and its stderr lines with the time each arrived.
struct Run {
    child: Child,
    started: Instant,
    lines: Arc<Mutex<Vec<(Instant, String)>>>,
}

impl Run {
    fn start(session: &Session) -> Run {
        let mut child = Command::new(pomdar_binary().unwrap())
            .args(&session.args)
            .env(TEST_PAUSE_ENV, PAUSE_MS.to_string())
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let started = Instant::now();
        let lines: Arc<Mutex<Vec<(Instant, String)>>> = Arc::default();
        let sink = lines.clone();
        let pipe = child.stderr.take().unwrap();
        std::thread::spawn(move || {
            for line in BufReader::new(pipe).lines() {
                let Ok(line) = line else { break };
                sink.lock().unwrap().push((Instant::now(), line));
            }
        });
        Run {
            child,
            started,
            lines,
        }
    }

    fn count(&self, marker: &str) -> usize {
        let lines = self.lines.lock().unwrap();
        lines.iter().filter(|(_, l)| l.contains(marker)).count()
    }

    fn stderr(&self) -> String {
        let lines = self.lines.lock().unwrap();
        lines
            .iter()
            .map(|(_, l)| l.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// Waits for the `n`-th line holding `marker` (1-based); `false` if the console exited
    /// first.
    fn wait_for(&mut self, marker: &str, n: usize) -> bool {
        while self.count(marker) < n {
            if self.child.try_wait().unwrap().is_some() {
                // Its last lines may still be in the pipe.
                std::thread::sleep(Duration::from_millis(100));
                return self.count(marker) >= n;
            }
            assert!(
                self.started.elapsed() < RUN_TIMEOUT,
                "no line {marker:?} #{n} after {RUN_TIMEOUT:?}:\n{}",
                self.stderr()
            );
            std::thread::sleep(Duration::from_millis(2));
        }
        true
    }

    /// Waits for the console to end by itself; asserts it succeeded.
    fn finish(mut self) {
        let started = self.started;
        let status = loop {
            if let Some(status) = self.child.try_wait().unwrap() {
                break status;
            }
            assert!(
                started.elapsed() < RUN_TIMEOUT,
                "the console did not end in {RUN_TIMEOUT:?}:\n{}",
                self.stderr()
            );
            std::thread::sleep(Duration::from_millis(20));
        };
        std::thread::sleep(Duration::from_millis(100));
        assert!(
            status.success(),
            "a resumed console failed ({status}):\n{}",
            self.stderr()
        );
    }
}

/// The console's phase at `at`, from its last line before it: a banner, or a test pause
/// still under way.
fn phase_at(lines: &[(Instant, String)], at: Instant) -> String {
    let pause = Duration::from_millis(PAUSE_MS);
    let banners = [
        ("] WAITING FOR ENGAGE", "engaging"),
        ("] READY", "engaging"),
        ("] COUNTING DOWN", "countdown"),
        ("] RUNNING", "running"),
        (
            "] SAVING THE TRIAL",
            "saving the trial: the station finishing its log",
        ),
        ("] TRIAL SUMMARY", "between trials"),
        ("] SESSION COMPLETE", "session complete"),
    ];
    let pauses = [
        (
            "recovered to",
            "resuming: a .part recovered, not yet removed",
        ),
        (
            "opening the session: saving the manifest",
            "opening the session: saving the manifest",
        ),
        (
            "finished: scoring it",
            "saving the trial: log finished, not yet in the manifest",
        ),
        (
            "the manifest saved",
            "the manifest just saved after a trial",
        ),
        ("writing its report", "writing the report"),
    ];
    for (time, line) in lines.iter().rev().filter(|(t, _)| *t <= at) {
        if let Some((_, phase)) = pauses.iter().find(|(m, _)| line.contains(m)) {
            if at.duration_since(*time) < pause {
                return (*phase).to_string();
            }
            return format!("just after {phase}");
        }
        if let Some((_, phase)) = banners.iter().find(|(m, _)| line.contains(m)) {
            return (*phase).to_string();
        }
    }
    "starting (no line yet)".to_string()
}

/// One kill: where it was aimed, when it came, what it hit.
struct Kill {
    task: &'static str,
    aim: Aim,
    /// Seconds after the process started.
    at_s: f64,
    /// The kill's wall time, ns since the Unix epoch.
    wall_ns: i64,
    phase: String,
    /// The running trial's log (`NAME.mcap.part`) at the kill, if one was being written, and
    /// when it was created (ns since the Unix epoch).
    part: Option<(String, i64)>,
    /// What the files said at the kill.
    files: String,
    /// Of the running trial: how much its recovered log lacks before the kill, ms.
    lost_ms: Option<f64>,
}

/// Everything the test saw along the way.
#[derive(Default)]
struct Seen {
    kills: Vec<Kill>,
    /// Every trial log finished or set aside at some kill, and its bytes then.
    kept: BTreeMap<PathBuf, Vec<u8>>,
    runs: usize,
}

/// Chooses the next kill's aim from the deck: a recovery when a `.part` waits for one, else
/// any aim this run can reach.
fn next_aim(deck: &mut Vec<Aim>, rng: &mut Rng, left: usize, part_waiting: bool) -> Aim {
    let saves_left = deck
        .iter()
        .any(|a| matches!(a, Aim::TrialSaved | Aim::Manifest));
    let reachable = |aim: Aim| match aim {
        Aim::Running | Aim::TrialSaved | Aim::Manifest => left > 0,
        Aim::Recovery => part_waiting,
        Aim::Report => left == 0 || (left == 1 && !saves_left),
        Aim::StartUp => true,
    };
    if part_waiting && let Some(i) = deck.iter().position(|a| *a == Aim::Recovery) {
        return deck.remove(i);
    }
    let choices: Vec<usize> = (0..deck.len()).filter(|i| reachable(deck[*i])).collect();
    if choices.is_empty() {
        // Nothing left this run can reach (a recovery with no .part waiting): the start.
        deck.pop();
        return Aim::StartUp;
    }
    deck.remove(choices[rng.below(choices.len())])
}

/// Runs the console until the kill aimed at `aim`; `None` if it ended by itself first.
fn kill_run(session: &Session, aim: Aim, rng: &mut Rng) -> Option<Kill> {
    let mut run = Run::start(session);
    let delay = match (aim, aim.marker()) {
        (Aim::StartUp, _) | (_, None) => millis(rng, 0, 1200),
        (_, Some(marker)) => {
            // A recovery: the pause after the .part's recovery, or the manifest's after it.
            let nth = if aim == Aim::Recovery {
                1 + rng.below(2)
            } else {
                1
            };
            if !run.wait_for(marker, nth) {
                run.finish();
                return None;
            }
            let window = if aim == Aim::Running {
                (TRIAL_S * 1000.0) as u64 - 100
            } else {
                PAUSE_MS
            };
            let since = run.started.elapsed();
            since + millis(rng, 0, window)
        }
    };
    std::thread::sleep(delay.saturating_sub(run.started.elapsed()));
    if let Some(status) = run.child.try_wait().unwrap() {
        std::thread::sleep(Duration::from_millis(100));
        assert!(status.success(), "{status}:\n{}", run.stderr());
        return None;
    }
    run.child.kill().unwrap(); // SIGKILL
    let at = Instant::now();
    let wall_ns = unix_ns();
    run.child.wait().unwrap();
    std::thread::sleep(Duration::from_millis(50));
    let phase = phase_at(&run.lines.lock().unwrap(), at);
    Some(Kill {
        task: session.task,
        aim,
        at_s: at.duration_since(run.started).as_secs_f64(),
        wall_ns,
        phase,
        part: None,
        files: String::new(),
        lost_ms: None,
    })
}

/// The session directory after a kill: the manifest parses (if written yet), finished and
/// set-aside logs are kept (and those seen before are unchanged), the running trial's `.part`
/// (one the killed run made: not among the files `before` it) is noted.
fn look_after_kill(session: &Session, before: &[String], kill: &mut Kill, seen: &mut Seen) {
    let dir = &session.dir;
    let manifest_path = dir.join("session.json");
    let listed = if manifest_path.exists() {
        let manifest = Manifest::load(&manifest_path)
            .unwrap_or_else(|e| panic!("the manifest after a kill in {}: {e}", kill.phase));
        manifest.trials.len()
    } else {
        0
    };
    let names = file_names(dir);
    let mut logs = 0;
    for name in &names {
        let done = finished_log(name, session.task) || name.ends_with(".mcap.interrupted");
        if done {
            logs += 1;
            let path = dir.join(name);
            let bytes = std::fs::read(&path).unwrap();
            if let Some(before) = seen.kept.get(&path) {
                assert!(
                    *before == bytes,
                    "{name} changed after the kill in {}",
                    kill.phase
                );
            }
            seen.kept.insert(path, bytes);
        }
        if let Some(log) = name.strip_suffix(".part")
            && log.ends_with(".mcap")
        {
            // A .part beside its finished log is the same file, linked just before the kill.
            if !names.iter().any(|n| n == log) && !before.contains(name) {
                let meta = std::fs::metadata(dir.join(name)).unwrap();
                let born = meta.created().or_else(|_| meta.modified()).unwrap();
                let born_ns = born.duration_since(UNIX_EPOCH).unwrap().as_nanos() as i64;
                kill.part = Some((name.clone(), born_ns));
            }
        }
    }
    kill.files = format!(
        "{logs} logs, {listed} in the manifest{}",
        kill.part
            .as_ref()
            .map(|(p, _)| format!(", {p}"))
            .unwrap_or_default()
    );
}

/// One task's session killed `kills` times (aims from `deck`), then resumed to the end.
fn kill_and_resume(session: &Session, deck: &mut Vec<Aim>, rng: &mut Rng, seen: &mut Seen) {
    let mut kills = 0;
    loop {
        let left = trials_left(&session.dir, session.task);
        std::fs::write(&session.script, script(left, session.mark)).unwrap();
        seen.runs += 1;
        if deck.is_empty() {
            Run::start(session).finish();
            assert_eq!(trials_left(&session.dir, session.task), 0);
            return;
        }
        let names = file_names(&session.dir);
        // A .part to recover (not one beside its finished log: that is only removed).
        let part_waiting = names.iter().any(|n| {
            n.strip_suffix(".part")
                .is_some_and(|log| log.ends_with(".mcap") && !names.iter().any(|m| m == log))
        });
        let aim = next_aim(deck, rng, left, part_waiting);
        match kill_run(session, aim, rng) {
            Some(mut kill) => {
                look_after_kill(session, &names, &mut kill, seen);
                kills += 1;
                println!(
                    "kill {:2} ({}, kill {kills} of its session): {:?} at {:.2} s: {} [{}]",
                    seen.kills.len() + 1,
                    session.task,
                    kill.aim,
                    kill.at_s,
                    kill.phase,
                    kill.files
                );
                seen.kills.push(kill);
            }
            // Ended by itself before the moment came: the aim goes back in the deck.
            None => deck.push(aim),
        }
    }
}

/// The last log time in a trial log, ns.
fn last_log_time_ns(path: &Path) -> Option<i64> {
    let reader = TrialReader::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    reader.messages().map(|m| m.log_time_ns).max()
}

/// Each kill that hit a running trial: its recovered log ends within [`MAX_LOSS_MS`] of the
/// kill.
fn measure_losses(sessions: &[Session], seen: &mut Seen) {
    for kill in &mut seen.kills {
        let Some((part, born_ns)) = &kill.part else {
            continue;
        };
        let session = sessions.iter().find(|s| s.task == kill.task).unwrap();
        let recovered = session
            .dir
            .join(format!("{}.interrupted", part.trim_end_matches(".part")));
        assert!(
            recovered.exists(),
            "{part} (killed in {}) was not recovered to {}",
            kill.phase,
            recovered.display()
        );
        // Killed between the log's creation and its first flush (the start event), nothing
        // is recovered: the trial lost all it had, since the file was created.
        let last = last_log_time_ns(&recovered).unwrap_or_else(|| {
            kill.phase.push_str(" (log created, nothing flushed yet)");
            *born_ns
        });
        kill.lost_ms = Some((kill.wall_ns - last) as f64 * 1e-6);
    }
}

/// The end: each session complete (every planned trial scored, readable, from start to
/// stop), every log kept along the way unchanged and in the manifest, no `.part`, the report.
fn assert_complete(session: &Session, seen: &Seen) {
    let dir = &session.dir;
    let manifest = Manifest::load(&dir.join("session.json")).unwrap();
    assert_eq!(manifest.next_slot(), None, "{} not complete", session.task);
    let scored: Vec<&str> = manifest
        .trials
        .iter()
        .filter(|t| t.status == TrialStatus::Scored)
        .map(|t| t.file.as_str())
        .collect();
    assert_eq!(scored.len(), TRIALS, "{:?}", manifest.trials);
    for file in &scored {
        let events = pomdar_tests::trial_event_names(&dir.join(file));
        assert_eq!(events.first().map(String::as_str), Some("start"), "{file}");
        assert_eq!(events.last().map(String::as_str), Some("stop"), "{file}");
    }
    for (path, bytes) in seen.kept.iter().filter(|(p, _)| p.starts_with(dir)) {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let now = std::fs::read(path).unwrap_or_else(|e| panic!("{name} lost: {e}"));
        assert!(now == *bytes, "{name} changed since a kill");
        TrialReader::open(path).unwrap_or_else(|e| panic!("{name} unreadable: {e}"));
        let entry = manifest.trials.iter().find(|t| t.file == name);
        let want = if name.ends_with(".interrupted") {
            TrialStatus::Interrupted
        } else {
            TrialStatus::Scored
        };
        assert_eq!(
            entry.map(|t| t.status),
            Some(want),
            "{name} in the manifest"
        );
    }
    for name in file_names(dir) {
        assert!(!name.ends_with(".part"), "{name} left after the end");
        if name != "session.json" && name != MESSAGE_LOG_FILE {
            assert!(
                manifest.trials.iter().any(|t| t.file == name),
                "{name} is not in the manifest"
            );
        }
    }
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report/scores.json")).unwrap())
            .unwrap();
    assert!(report.is_object());
    assert!(dir.join("report/report.md").exists());
}

/// The table of kills, and the figures: kills per phase, the running trial's largest loss.
fn print_table(seen: &Seen) {
    println!(
        "\n{:>4}  {:<4} {:<10} {:>7}  {:<55} {:>9}  files at the kill",
        "kill", "task", "aimed at", "at (s)", "phase (console's last line, files)", "lost (ms)"
    );
    for (i, k) in seen.kills.iter().enumerate() {
        println!(
            "{:>4}  {:<4} {:<10} {:>7.2}  {:<55} {:>9}  {}",
            i + 1,
            k.task,
            format!("{:?}", k.aim),
            k.at_s,
            k.phase,
            k.lost_ms.map(|l| format!("{l:.0}")).unwrap_or_default(),
            k.files
        );
    }
    let mut per_phase: BTreeMap<&str, usize> = BTreeMap::new();
    for k in &seen.kills {
        *per_phase.entry(k.phase.as_str()).or_default() += 1;
    }
    println!("\nkills per phase:");
    for (phase, n) in &per_phase {
        println!("  {n:2}  {phase}");
    }
    let losses: Vec<f64> = seen.kills.iter().filter_map(|k| k.lost_ms).collect();
    let max = losses.iter().copied().fold(0.0, f64::max);
    println!(
        "running trial at {} kills: lost at most {max:.0} ms; {} runs of the console; {} logs kept along the way",
        losses.len(),
        seen.runs,
        seen.kept.len()
    );
}

// About a minute, one of the suite's longest: 20 kills at random moments of real trials (each
// resumed and played on to the next kill), and the kill moments are the point: a shorter trial
// would leave fewer phases of the console to be killed in.
#[test]
fn the_console_killed_at_random_moments_resumes_losing_no_finished_trial() {
    let started = Instant::now();
    let seed = seed();
    println!("seed {seed} (POMDAR_KILL_SEED={seed} draws these kill moments again)");
    let mut rng = Rng::new(seed);
    let root = scratch_dir("console-random-kills");
    std::fs::write(
        root.join("baseline.toml"),
        "[baseline]\nexample = false\nsource = \"console_random_kills test\"\n\n[[task]]\nid = \"V1\"\nmean_s = 4.0\nn = 3\n\n[[task]]\nid = \"G2\"\nmean_s = 3.0\nn = 3\n",
    )
    .unwrap();
    let domain = test_domain();
    let sessions: Vec<Session> = TASKS
        .iter()
        .map(|(task, mark)| Session::new(&root, task, mark, domain))
        .collect();
    let mut seen = Seen::default();
    for session in &sessions {
        let mut deck = shuffled_deck(&mut rng);
        kill_and_resume(session, &mut deck, &mut rng, &mut seen);
    }
    measure_losses(&sessions, &mut seen);
    print_table(&seen);
    println!("took {:.0} s", started.elapsed().as_secs_f64());
    assert_eq!(seen.kills.len(), KILLS);
    for session in &sessions {
        assert_complete(session, &seen);
    }
    for k in &seen.kills {
        if let Some(lost) = k.lost_ms {
            assert!(
                lost <= MAX_LOSS_MS,
                "the trial running at a kill ({}) lost {lost:.0} ms (seed {seed})",
                k.phase
            );
        }
    }
    std::fs::remove_dir_all(&root).ok();
}
