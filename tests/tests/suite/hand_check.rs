//! `pomdar hand-check` as the operator runs it (the built binary, `--script`), against the mock
//! hand on real loopback DDS: the mock hand follows the consumer topic through the inverse of
//! the same table, so every joint the check names must move, alone, the way it names; every
//! joint confirmed writes the verified table, a joint left unconfirmed writes nothing and
//! fails naming the joints.

use std::path::Path;
use std::sync::{Arc, Mutex};

use pomdar_tests::pomdar_binary::run_pomdar;
use pomdar_tests::station_harness::{loopback, test_domain};
use pomdar_tests::{path_arg, scratch_dir, workspace_root};
use retarget::HandModel;
use station::StationConfig;
use station::policy_output::PolicyOutput;
use teleop::clock::StationClock;
use teleop::hand_check::directions::direction_sentence;
use teleop::hand_check::session::neutral_pose;
use teleop::stand_ins::mock_hand::{MockHandConfig, MockHandReport, PolicyInput, run_mock_hand};

fn preset(name: &str) -> (std::path::PathBuf, StationConfig) {
    let path = workspace_root().join("launch_configs/station").join(name);
    let config = StationConfig::from_toml_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    (path, config)
}

/// `joint k of 17: NAME: watch: SENTENCE (+0.15 rad over …` → (NAME, SENTENCE, step).
fn watched(stdout: &str) -> Vec<(String, String, f64)> {
    stdout
        .lines()
        .filter_map(|line| {
            let (head, rest) = line.split_once(": watch: ")?;
            let name = head.rsplit(": ").next()?.to_string();
            let (sentence, step) = rest.rsplit_once(" (")?;
            let step: f64 = step.split_whitespace().next()?.parse().ok()?;
            Some((name, sentence.to_string(), step))
        })
        .collect()
}

/// `pomdar hand-check` on `config_path` with `script`, fast motion, on loopback `domain`.
fn hand_check(config_path: &Path, out: &Path, script: &Path, domain: u16) -> std::process::Output {
    run_pomdar(&[
        "hand-check",
        "--config",
        path_arg(config_path),
        "--out",
        path_arg(out),
        "--user",
        "tester",
        "--script",
        path_arg(script),
        "--move-s",
        "1",
        "--hold-s",
        "0.3",
        "--settle-s",
        "1.5",
        "--domain-id",
        &domain.to_string(),
        "--interface",
        "127.0.0.1",
    ])
}

/// Run `pomdar hand-check` while the mock hand, in process, follows the consumer topic through
/// the inverse of `config`'s table, recording its measured states.
fn with_mock_hand(
    config: &StationConfig,
    domain: u16,
    run: impl FnOnce() -> std::process::Output,
) -> (std::process::Output, MockHandReport) {
    let model = HandModel::orca_v1_right();
    let table = PolicyOutput::new(&model, &config.policy_output).unwrap();
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    let report = Arc::new(Mutex::new(MockHandReport::default()));
    let (stop, stopped) = tokio::sync::watch::channel(false);
    let mock = runtime.spawn(run_mock_hand(
        model,
        MockHandConfig {
            targets_topic: "/pomdar/hand_check_test/unused".into(),
            policy: Some(PolicyInput {
                topic: config.policy_output.topic.clone(),
                table,
            }),
            record_states: true,
            ..MockHandConfig::default()
        },
        loopback(domain),
        StationClock::new(),
        report.clone(),
        stopped,
    ));
    let output = run();
    stop.send(true).unwrap();
    runtime.block_on(mock).unwrap().unwrap();
    let report = report.lock().unwrap().clone();
    (output, report)
}

/// Each joint the check named moved its step the named way (in the URDF's sense), the others
/// held still.
fn assert_moved_as_named(stdout: &str, report: &MockHandReport, neutral: &[f64]) {
    let model = HandModel::orca_v1_right();
    assert!(
        report.policy_targets > 100 && report.policy_rejected == 0,
        "{} followed, {} rejected",
        report.policy_targets,
        report.policy_rejected
    );
    let settled = report
        .states
        .iter()
        .position(|q| q.iter().zip(neutral).all(|(a, b)| (a - b).abs() < 1e-3))
        .expect("the mock hand reached the neutral pose");
    let states = &report.states[settled..];
    let moves = watched(stdout);
    assert_eq!(moves.len(), 17, "{stdout}");
    for (name, sentence, step) in moves {
        let dof = model.dof_index(&name).unwrap();
        assert_eq!(sentence, direction_sentence(&name, step), "{name}");
        let deviation = |q: &Vec<f64>| (q[dof] - neutral[dof]).abs();
        let peak = states
            .iter()
            .max_by(|a, b| deviation(a).total_cmp(&deviation(b)))
            .unwrap();
        let moved = peak[dof] - neutral[dof];
        assert!(
            moved * step > 0.0 && (moved - step).abs() < 0.2 * step.abs(),
            "{name}: moved {moved:+.3} rad, named {step:+.3}"
        );
        for (other, (a, b)) in peak.iter().zip(neutral).enumerate() {
            if other != dof {
                assert!(
                    (a - b).abs() < 0.01,
                    "{name} moving: dof {other} at {a} (neutral {b})"
                );
            }
        }
    }
}

#[test]
fn every_joint_confirmed_writes_the_verified_table_and_the_mock_hand_moved_as_named() {
    let (path, config) = preset("eth_lab.toml");
    let model = HandModel::orca_v1_right();
    let table = PolicyOutput::new(&model, &config.policy_output).unwrap();
    let neutral = neutral_pose(&model, &table).unwrap();
    let dir = scratch_dir("hand-check");
    let out = dir.join("eth_lab_verified.toml");
    let script = dir.join("all_yes.script");
    std::fs::write(&script, "wait asking 30\nyes\n".repeat(17)).unwrap();
    let domain = test_domain();
    let (output, report) =
        with_mock_hand(&config, domain, || hand_check(&path, &out, &script, domain));
    assert!(output.status.success(), "hand-check failed");
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(stdout.contains("joint 6 of 17: index_abd"), "{stdout}");

    // The table: every row verified, by whom and when; nothing else changed.
    let written = StationConfig::from_toml_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let verified = &written.policy_output;
    assert!(
        verified.verification().is_verified(),
        "{:?}",
        verified.verification()
    );
    assert_eq!(verified.verified_by, "tester");
    assert!(
        verified.verified_at.ends_with('Z'),
        "{}",
        verified.verified_at
    );
    for (row, before) in verified.joints.iter().zip(&config.policy_output.joints) {
        assert_eq!(
            (&row.joint, row.sign, row.offset_deg),
            (&before.joint, before.sign, before.offset_deg)
        );
    }
    assert_eq!(written.control, config.control);
    assert!(!dir.join("eth_lab_verified.toml.part").exists());
    assert_moved_as_named(&stdout, &report, &neutral);
}

#[test]
fn a_joint_left_unconfirmed_writes_nothing_and_names_the_joints() {
    let (path, _) = preset("orca_core.toml");
    let dir = scratch_dir("hand-check-quit");
    let out = dir.join("orca_core_verified.toml");
    let script = dir.join("quit.script");
    // thumb_mcp confirmed; thumb_abd reported wrong, then the operator quits.
    std::fs::write(
        &script,
        "wait asking 30\nyes\nwait asking 30\nno\nwait offer_flip 5\nquit\n",
    )
    .unwrap();
    let domain = test_domain();
    let output = hand_check(&path, &out, &script, domain);
    assert!(!output.status.success());
    assert!(!out.exists() && !dir.join("orca_core_verified.toml.part").exists());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(
        stderr.contains(
            "no table written: not confirmed: thumb_abd, thumb_pip, thumb_dip, index_abd,"
        ) && stderr.trim_end().ends_with("pinky_pip, wrist"),
        "{stderr}"
    );
    // A script that ends before the check does is a stop, too.
    std::fs::write(&script, "wait asking 30\nyes\n").unwrap();
    let output = hand_check(&path, &out, &script, domain);
    assert!(!output.status.success() && !out.exists());
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(stdout.contains("the script has ended"), "{stdout}");
}
