//! A normal run ends quietly: the commands an operator runs most, as the built binary on
//! their own loopback-only DDS domains, exit with status 0 and print no ERROR or WARN line, on
//! stdout or stderr, from the station or from the libraries' logging (RustDDS and ros2-client
//! through the `log` crate: `pomdar`'s logger writes `[ERROR target] message` lines on
//! stderr).
//!
//! The shutdown is where these came from: DDS endpoints dropped after their participant
//! (`Cannot remove Writer … Disconnected`), ros2-client's matched-count queries before a
//! first match, and the multicast leave of a participant restricted to 127.0.0.1.

use std::process::{Command, Output, Stdio};

use pomdar_tests::pomdar_binary::{ctrl_c_after, pomdar_binary, run_pomdar};
use pomdar_tests::station_harness::test_domain;
use pomdar_tests::{path_arg, scratch_dir};

/// The lines of `text` an operator would read as a failure: an ERROR or a WARN record.
fn alarming_lines(text: &str) -> Vec<&str> {
    text.lines()
        .filter(|line| line.contains("ERROR") || line.contains(" WARN") || line.contains("WARN "))
        .collect()
}

/// `output` ended with status 0 and printed no ERROR or WARN line.
fn assert_quiet(what: &str, output: &Output) {
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    let alarming: Vec<&str> = alarming_lines(&stdout)
        .into_iter()
        .chain(alarming_lines(&stderr))
        .collect();
    assert!(
        alarming.is_empty(),
        "{what}: a normal run printed {} ERROR/WARN lines, the first: {:?}",
        alarming.len(),
        &alarming[..alarming.len().min(5)]
    );
    assert_eq!(output.status.code(), Some(0), "{what}: exit status");
}

/// Run `pomdar args…` for `seconds`, stop it with SIGINT (Ctrl-C) and collect its output.
fn run_until_ctrl_c(args: &[&str], seconds: f64) -> Output {
    let child = Command::new(pomdar_binary().unwrap())
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let output = ctrl_c_after(child, seconds);
    println!(
        "$ pomdar {} (Ctrl-C after {seconds} s)\n--- stdout\n{}--- stderr\n{}",
        args.join(" "),
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

#[test]
fn the_filter_catches_both_logger_formats_and_lets_ordinary_lines_through() {
    let text = "[2026-11-26T17:07:18Z ERROR rustdds::dds::pubsub] Cannot remove Writer\n\
                [ERROR rustdds::network::udp_listener] leave_multicast_group\n\
                [WARN  rustdds::rtps::writer] no locators\n\
                [13.1 s] recorded trials: 1/1 done\n\
                note: avp ingress: waiting for the headset";
    assert_eq!(alarming_lines(text).len(), 3);
}

#[test]
fn a_simulated_calibration_ends_quietly() {
    let dir = scratch_dir("quiet-calibrate");
    let domain = test_domain().to_string();
    let output = run_pomdar(&[
        "calibrate",
        "--simulate",
        "--user",
        "quiet",
        "--out",
        path_arg(&dir.join("quiet.toml")),
        "--session-out",
        path_arg(&dir.join("session.mcap")),
        "--domain-id",
        &domain,
    ]);
    assert_quiet("pomdar calibrate --simulate", &output);
    assert!(dir.join("quiet.toml").exists(), "the profile is written");
}

#[test]
fn a_short_demo_ends_quietly() {
    let domain = test_domain().to_string();
    let output = run_pomdar(&["demo", "--duration", "3", "--domain-id", &domain]);
    assert_quiet("pomdar demo --duration 3", &output);
}

#[test]
fn a_scripted_simulated_trial_ends_quietly() {
    let dir = scratch_dir("quiet-trial");
    // launch_configs/sim/one_trial.script with a 1 s trial.
    let script = dir.join("one_trial.script");
    std::fs::write(
        &script,
        "engage\nwait ready 60\nstart\nwait running 60\n+1 stop\nwait complete 60\nquit\n",
    )
    .unwrap();
    let domain = test_domain().to_string();
    let output = run_pomdar(&[
        "trial",
        "--task",
        "V1",
        "--user",
        "sim",
        "--operator",
        "ci",
        "--practice",
        "0",
        "--trials",
        "1",
        "--countdown",
        "0.5",
        "--simulate",
        "--domain-id",
        &domain,
        "--interface",
        "127.0.0.1",
        "--script",
        path_arg(&script),
        "--out",
        path_arg(&dir.join("sessions")),
    ]);
    assert_quiet("pomdar trial --simulate --script", &output);
}

#[test]
fn the_rokoko_ingress_stopped_with_ctrl_c_ends_quietly() {
    let domain = test_domain().to_string();
    let output = run_until_ctrl_c(
        &[
            "ingress",
            "rokoko",
            "--bind",
            "127.0.0.1",
            "--port",
            "0",
            "--domain-id",
            &domain,
            "--interface",
            "127.0.0.1",
        ],
        2.0,
    );
    assert_quiet("pomdar ingress rokoko, Ctrl-C", &output);
}

#[test]
fn the_avp_ingress_without_a_headset_stopped_with_ctrl_c_ends_quietly() {
    let domain = test_domain().to_string();
    let output = run_until_ctrl_c(
        &[
            "ingress",
            "avp",
            "--address",
            "127.0.0.1:1",
            "--domain-id",
            &domain,
            "--interface",
            "127.0.0.1",
        ],
        2.0,
    );
    assert_quiet("pomdar ingress avp, Ctrl-C", &output);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.lines().filter(|l| l.starts_with("note:")).count() <= 1,
        "at most one note while no headset answers: {stderr}"
    );
}
