//! A station whose DDS sockets cannot be guarded does not start: `pomdar station` with every
//! attach of the datagram filter refused (`POMDAR_TEST_DATAGRAM_GUARD_FAIL=1`, a test-only
//! knob) exits at start-up with an error naming the socket and the way out
//! (`--no-datagram-guard`); with that flag the same station runs, and says once that it is
//! unguarded.

use std::process::{Command, Stdio};

use pomdar_tests::pomdar_binary::{ctrl_c_after, pomdar_binary};
use pomdar_tests::station_harness::test_domain;
use teleop::ros::participant_guard::GUARD_FAIL_ENV;

fn station(domain: u16, unguarded: bool) -> Command {
    let config = pomdar_tests::workspace_root().join("launch_configs/station/eth_lab.toml");
    let mut command = Command::new(pomdar_binary().unwrap());
    command
        .args(["station", "--interface", "127.0.0.1", "--domain-id"])
        .arg(domain.to_string())
        .arg("--config")
        .arg(config)
        .env(GUARD_FAIL_ENV, "1")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    if unguarded {
        command.arg("--no-datagram-guard");
    }
    command
}

#[test]
fn a_guard_that_cannot_attach_stops_start_up_and_the_flag_runs_unguarded() {
    let domain = test_domain();
    let output = station(domain, false).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    println!("{stderr}");
    assert!(!output.status.success(), "it started: {stderr}");
    assert!(
        stderr.contains("cannot guard the DDS participant")
            && stderr.contains("UDP socket on port")
            && stderr.contains("--no-datagram-guard"),
        "{stderr}"
    );

    // Declined: it runs (still up after 3 s), says so once, and stops cleanly on Ctrl-C.
    let output = ctrl_c_after(station(domain, true).spawn().unwrap(), 3.0);
    let stderr = String::from_utf8_lossy(&output.stderr);
    println!("{stderr}");
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    assert_eq!(
        stderr.matches("--no-datagram-guard: this process").count(),
        1,
        "{stderr}"
    );
}
