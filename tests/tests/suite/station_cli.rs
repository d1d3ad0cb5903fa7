//! `pomdar station` as an operator starts it: before any glove publishes it says what it
//! waits for (at most once a second), once frames arrive it says so, and Ctrl-C ends it
//! cleanly with no ERROR or WARN line.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use pomdar_tests::pomdar_binary::pomdar_binary;
use pomdar_tests::station_harness::test_domain;
use pomdar_tests::workspace_root;

/// Run `pomdar station` for `seconds` (with a simulated glove on the same domain when
/// `glove`), stop it with SIGINT, and return its stderr.
fn station_for(seconds: f64, glove: bool) -> (String, Option<i32>) {
    let binary = pomdar_binary().unwrap();
    let domain = test_domain().to_string();
    let config = workspace_root().join("launch_configs/station/eth_lab.toml");
    let station = Command::new(&binary)
        .args(["station", "--config"])
        .arg(&config)
        .args(["--interface", "127.0.0.1"])
        .env("ROS_DOMAIN_ID", &domain)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut sim = glove.then(|| {
        Command::new(&binary)
            .args(["sim-glove", "--interface", "127.0.0.1"])
            .env("ROS_DOMAIN_ID", &domain)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap()
    });
    let started = Instant::now();
    std::thread::sleep(Duration::from_secs_f64(seconds));
    let elapsed = started.elapsed().as_secs_f64();
    let pid = station.id().to_string();
    Command::new("kill").args(["-INT", &pid]).status().unwrap();
    let output = station.wait_with_output().unwrap();
    if let Some(sim) = sim.as_mut() {
        sim.kill().ok();
        sim.wait().ok();
    }
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    println!("--- stderr after {elapsed:.1} s\n{stderr}");
    (stderr, output.status.code())
}

fn no_error_or_warning_lines(stderr: &str) {
    for line in stderr.lines() {
        assert!(
            !line.contains("ERROR") && !line.contains("WARN"),
            "a normal run printed: {line}"
        );
    }
}

#[test]
fn without_a_glove_the_station_says_what_it_waits_for_at_most_once_a_second() {
    let (stderr, code) = station_for(4.5, false);
    assert_eq!(code, Some(0), "Ctrl-C ends the station cleanly");
    let waiting = stderr
        .lines()
        .filter(|l| l.starts_with("waiting for glove keypoints on /ingress/mano"))
        .count();
    assert!(
        (1..=5).contains(&waiting),
        "{waiting} waiting lines in 4.5 s: at least one, at most one a second"
    );
    no_error_or_warning_lines(&stderr);
}

#[test]
fn once_frames_arrive_the_station_says_so_and_stops_waiting() {
    let (stderr, code) = station_for(6.0, true);
    assert_eq!(code, Some(0));
    let arriving = stderr
        .lines()
        .position(|l| l.starts_with("glove frames arriving on /ingress/mano"))
        .expect("the station says when glove frames arrive");
    let after = stderr.lines().skip(arriving + 1);
    assert_eq!(
        after.filter(|l| l.starts_with("waiting for glove")).count(),
        0,
        "no waiting line after the first frame"
    );
}
