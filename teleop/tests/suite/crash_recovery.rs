//! Crash test: `pomdar demo --out DIR` (the station recording its run) is killed with SIGKILL
//! at random moments; each interrupted log recovers with `pomdar recover`, losing at most about
//! one second of data (the flush interval). The test measures the loss.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use teleop::mcap_log::{TrialReader, recover};
use teleop::ros::domain_lease::{TEST_DOMAINS, lease_domain};

const KILLS: usize = 20;
/// Kills at once.
const LANES: usize = 2;

fn unix_ns() -> i64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .unwrap()
        .as_nanos() as i64
}

/// A small deterministic generator for the kill moments (seeded, reproducible).
fn kill_delays() -> Vec<Duration> {
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    (0..KILLS)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            Duration::from_millis(1500 + state % 2000)
        })
        .collect()
}

fn part_file(dir: &Path) -> Option<PathBuf> {
    std::fs::read_dir(dir)
        .ok()?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .find(|p| p.to_string_lossy().ends_with(".mcap.part"))
}

/// Run `i`: `pomdar demo --out` killed `delay` after its start, its log recovered; the data
/// lost, in milliseconds.
fn kill_and_recover(root: &Path, i: usize, delay: Duration) -> f64 {
    let dir = root.join(format!("run{i}"));
    std::fs::create_dir_all(&dir).unwrap();
    let domain = lease_domain(TEST_DOMAINS).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_pomdar"))
        .args([
            "demo",
            "--duration",
            "30",
            "--json",
            "--domain-id",
            &domain.to_string(),
            "--out",
        ])
        .arg(&dir)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let started = Instant::now();
    // Kill only once the log exists (DDS start-up takes a moment), then at the chosen time.
    while part_file(&dir).is_none() && started.elapsed() < Duration::from_secs(20) {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(delay.saturating_sub(started.elapsed()));
    child.kill().unwrap(); // SIGKILL
    let killed_ns = unix_ns();
    child.wait().unwrap();

    let part = part_file(&dir).unwrap_or_else(|| panic!("run {i}: no .part file after the kill"));
    let out = dir.join("recovered.mcap");
    let report = recover(&part, &out).unwrap();
    let log = TrialReader::open(&out).unwrap();
    assert!(
        log.metadata_named("pomdar_trial").is_some(),
        "run {i}: trial metadata lost"
    );
    assert!(
        log.topic("/pomdar/trial_events").is_some(),
        "run {i}: start event lost"
    );
    let last = report.last_log_time_ns.unwrap_or(0);
    let lost_ms = (killed_ns - last) as f64 * 1e-6;
    println!(
        "run {i}: killed after {:.2} s, recovered {} messages, lost the last {lost_ms:.0} ms",
        delay.as_secs_f64(),
        report.message_count
    );
    lost_ms
}

/// The kills run in two lanes side by side (each run its own directory and domain), so the
/// test takes half the time of one lane; two recording stations at once are also a little
/// load on each.
#[test]
fn killed_recordings_recover_losing_at_most_about_a_second() {
    let root = std::env::temp_dir().join(format!("pomdar-crash-{}", std::process::id()));
    std::fs::remove_dir_all(&root).ok();
    let runs: Vec<(usize, Duration)> = kill_delays().into_iter().enumerate().collect();
    let mut losses_ms: Vec<f64> = std::thread::scope(|scope| {
        let lanes: Vec<_> = runs
            .chunks(KILLS / LANES)
            .map(|lane| {
                let root = &root;
                scope.spawn(move || {
                    (lane.iter())
                        .map(|(i, delay)| kill_and_recover(root, *i, *delay))
                        .collect::<Vec<f64>>()
                })
            })
            .collect();
        lanes
            .into_iter()
            .flat_map(|lane| lane.join().unwrap())
            .collect()
    });
    losses_ms.sort_by(f64::total_cmp);
    println!(
        "loss over {KILLS} kills: median {:.0} ms, max {:.0} ms",
        losses_ms[KILLS / 2],
        losses_ms[KILLS - 1]
    );
    // Flushes come at least once per second of log time (and the status, 5 Hz, drives them
    // when inputs are quiet); allow the writes in flight at the kill on top.
    assert!(
        losses_ms[KILLS - 1] <= 1300.0,
        "lost {} ms",
        losses_ms[KILLS - 1]
    );
    std::fs::remove_dir_all(&root).ok();
}
