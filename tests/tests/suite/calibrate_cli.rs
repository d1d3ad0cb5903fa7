//! `pomdar calibrate` as the operator runs it (the built binary): a simulated user's whole
//! session over loopback DDS to a profile, the same session fitted again from its recording,
//! sessions with a bad pose refused without writing anything, and the station and resim
//! refusing a bad profile (naming the file and the key) and accepting the good one; the
//! session file decoded by the independent MCAP readers (interop).

use std::io::{BufRead as _, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;

use calibration::CalibrationProfile;
use msgs::Float32MultiArray;
use pomdar_tests::interop::{assert_readers_decode_as_we_do, independent_readers_with_values};
use pomdar_tests::pomdar_binary::{pomdar_binary, run_pomdar as pomdar};
use pomdar_tests::station_harness::test_domain;
use pomdar_tests::{path_arg, simulated_calibration_errors};
use teleop::calibrate::session_events::capture_windows;
use teleop::mcap_log::{LoggedMessage, TrialReader, TrialWriter, TrialWriterOptions};

const HAND_SCALE: f64 = 1.15;
const USER: &str = "sim_user";

/// This file's scratch directory, shared by its tests (not cleared: they share one session).
fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pomdar-calibrate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

struct Simulated {
    profile: PathBuf,
    session: PathBuf,
    stdout: String,
}

/// One simulated session for the whole file (it takes 7 × 2.5 s of DDS time).
fn simulated() -> &'static Simulated {
    static SIMULATED: OnceLock<Simulated> = OnceLock::new();
    SIMULATED.get_or_init(|| {
        let dir = scratch();
        let profile = dir.join("profiles").join(format!("{USER}.toml"));
        let session = dir.join("session.mcap");
        std::fs::remove_file(&profile).ok();
        std::fs::remove_file(&session).ok();
        let domain = test_domain().to_string();
        let scale = HAND_SCALE.to_string();
        let output = pomdar(&[
            "calibrate",
            "--simulate",
            "--hand-scale",
            &scale,
            "--glove-rpy",
            "8,-6,5",
            "--seed",
            "7",
            "--user",
            USER,
            "--out",
            path_arg(&profile),
            "--session-out",
            path_arg(&session),
            "--domain-id",
            &domain,
        ]);
        assert!(output.status.success(), "calibrate --simulate failed");
        Simulated {
            profile,
            session,
            stdout: String::from_utf8(output.stdout).unwrap(),
        }
    })
}

fn read_profile(path: &Path) -> CalibrationProfile {
    CalibrationProfile::from_toml_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn part_of(path: &Path) -> PathBuf {
    PathBuf::from(format!("{}.part", path.display()))
}

#[test]
fn a_simulated_session_writes_a_profile_close_to_the_truth() {
    let sim = simulated();
    let profile = read_profile(&sim.profile);
    profile.validate().unwrap();
    profile
        .check_fits(
            &retarget::HandModel::orca_v1_right(),
            retarget::KeypointLayout::Lab22,
        )
        .unwrap();
    assert_eq!(profile.user, USER);
    assert!(
        profile.date.ends_with('Z') && profile.date.len() == 20,
        "{}",
        profile.date
    );
    let expected = 1.0 / HAND_SCALE;
    let scale = profile.parameters.scale;
    assert!(
        (scale - expected).abs() <= 0.15 * expected,
        "scale {scale}, expected 1/{HAND_SCALE} = {expected:.3} within 15 %"
    );
    assert!(profile.objective.after_rad < profile.objective.before_rad);
    assert!(!part_of(&sim.profile).exists(), ".part left behind");
    assert!(sim.stdout.contains("recovered") && sim.stdout.contains("true"));
    // The printed comparison with the user's true transform: within the acceptance bounds.
    let (line, scale_error_pct, rotation_error_deg) = simulated_calibration_errors(&sim.stdout);
    assert!(
        scale_error_pct.abs() <= 3.0 && rotation_error_deg <= 3.0,
        "{line}"
    );

    // The session log: the seven capture windows, keypoints in each, the commanded poses.
    let log = TrialReader::open(&sim.session).unwrap();
    let windows = capture_windows(&log).unwrap();
    assert_eq!(windows.len(), 7, "{windows:?}");
    for (pose, (start, end)) in &windows {
        let frames = log
            .messages_on("/ingress/mano")
            .filter(|m| m.log_time_ns >= *start && m.log_time_ns < *end)
            .count();
        assert!(
            frames >= 50,
            "{pose}: {frames} frames in its capture window"
        );
    }
    let commanded = log
        .decode_topic::<msgs::JointState>("/pomdar/hand/joint_targets")
        .unwrap();
    assert!(
        commanded.len() >= 7 * 10,
        "{} commanded poses",
        commanded.len()
    );
}

/// The session file (another kind of file the station writes, beside trial logs) decodes with
/// the independent readers (`mcap` + `mcap-ros2-support`, `rosbags`) to exactly the values the
/// station reads from it, message for message (the same session as the test above: no extra
/// DDS time).
#[test]
fn the_independent_readers_decode_the_session_file_as_the_station_does() {
    let sim = simulated();
    let log = TrialReader::open(&sim.session).unwrap();
    if let Some(report) = independent_readers_with_values(&sim.session) {
        assert_readers_decode_as_we_do(&report, &log);
    }
}

#[test]
fn fitting_the_recorded_session_again_reproduces_the_parameters() {
    let sim = simulated();
    let out = scratch().join("again.toml");
    std::fs::remove_file(&out).ok();
    let output = pomdar(&[
        "calibrate",
        "--from",
        path_arg(&sim.session),
        "--user",
        USER,
        "--out",
        path_arg(&out),
    ]);
    assert!(output.status.success());
    let first = read_profile(&sim.profile);
    let again = read_profile(&out);
    assert_eq!(again.parameters, first.parameters);
    assert_eq!(again.objective, first.objective);
    assert_eq!(again.poses, first.poses);
}

/// A copy of `session` where the keypoint messages inside `pose`'s capture window are
/// replaced by `edit` (None: dropped).
fn doctored_session(
    session: &Path,
    out: &Path,
    pose: &str,
    edit: impl Fn(&LoggedMessage) -> Option<Float32MultiArray>,
) {
    std::fs::remove_file(out).ok();
    let log = TrialReader::open(session).unwrap();
    let (start, end) = capture_windows(&log).unwrap()[pose];
    let mut writer = TrialWriter::create(out, TrialWriterOptions::default()).unwrap();
    for topic in log.topics() {
        let qos = topic.offered_qos().unwrap().unwrap();
        writer
            .add_channel_raw(&topic.topic, &topic.type_name, &topic.schema_text, &qos)
            .unwrap();
    }
    for (name, entries) in log.metadata() {
        writer.write_metadata(name, entries.clone()).unwrap();
    }
    for m in log.messages() {
        let inside = m.log_time_ns >= start && m.log_time_ns < end;
        if m.topic == "/ingress/mano" && inside {
            if let Some(replacement) = edit(m) {
                writer
                    .write(&m.topic, m.log_time_ns, m.publish_time_ns, &replacement)
                    .unwrap();
            }
            continue;
        }
        let info = log.topic(&m.topic).unwrap();
        writer
            .write_raw(
                &m.topic,
                &info.type_name,
                &info.schema_text,
                m.log_time_ns,
                m.publish_time_ns,
                &m.data,
            )
            .unwrap();
    }
    writer.finish().unwrap();
}

fn assert_refused(session: &Path, pose: &str) {
    let out = scratch().join(format!("refused-{pose}.toml"));
    std::fs::remove_file(&out).ok();
    let output = pomdar(&[
        "calibrate",
        "--from",
        path_arg(session),
        "--user",
        USER,
        "--out",
        path_arg(&out),
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success(),
        "a bad '{pose}' capture was accepted"
    );
    assert!(
        stderr.contains(&format!("'{pose}'")) && stderr.contains("refused"),
        "{stderr}"
    );
    assert!(!out.exists(), "a profile was written");
    assert!(!part_of(&out).exists(), "a .part was left");
}

#[test]
fn a_session_with_a_corrupted_or_missing_pose_is_refused_naming_it() {
    let sim = simulated();
    let dir = scratch();
    let corrupted = dir.join("corrupted.mcap");
    doctored_session(&sim.session, &corrupted, "pinch_ring", |m| {
        let mut array: Float32MultiArray = m.decode().unwrap();
        array.data.iter_mut().for_each(|v| *v = f32::NAN);
        Some(array)
    });
    assert_refused(&corrupted, "pinch_ring");
    let missing = dir.join("missing.mcap");
    doctored_session(&sim.session, &missing, "open_spread", |_| None);
    assert_refused(&missing, "open_spread");
}

#[test]
fn the_station_and_resim_refuse_a_bad_profile_and_accept_the_good_one() {
    let sim = simulated();
    let dir = scratch();
    let good_text = std::fs::read_to_string(&sim.profile).unwrap();
    let bad = dir.join("bad_profile.toml");
    let bad_text: String = good_text
        .lines()
        .map(|l| {
            if l.starts_with("scale = ") {
                "scale = 9.0"
            } else {
                l
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    assert_ne!(bad_text.trim(), good_text.trim());
    std::fs::write(&bad, bad_text).unwrap();

    // resim --profile: bad refused, good accepted and applied (other joint targets).
    let resim = |profile: Option<&Path>, out: &Path| {
        std::fs::remove_file(out).ok();
        let mut args = vec!["resim", path_arg(&sim.session), "--out", path_arg(out)];
        if let Some(p) = profile {
            args.extend(["--profile", path_arg(p)]);
        }
        pomdar(&args)
    };
    let output = resim(Some(&bad), &dir.join("resim_bad.mcap"));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(
        stderr.contains("bad_profile.toml") && stderr.contains("parameters.scale"),
        "{stderr}"
    );
    assert!(!dir.join("resim_bad.mcap").exists());
    let calibrated = dir.join("resim_good.mcap");
    let output = resim(Some(&sim.profile), &calibrated);
    assert!(output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains(&format!("user {USER}")));
    let plain = dir.join("resim_plain.mcap");
    assert!(resim(None, &plain).status.success());
    let targets = |p: &Path| {
        TrialReader::open(p)
            .unwrap()
            .decode_topic::<msgs::JointState>("/pomdar/hand/joint_targets")
            .unwrap()
    };
    assert_ne!(
        targets(&calibrated),
        targets(&plain),
        "the profile changed nothing"
    );

    // The station configuration's calibration_profile, relative to the config file.
    let config = dir.join("station_bad.toml");
    std::fs::write(&config, "calibration_profile = \"bad_profile.toml\"\n").unwrap();
    let output = pomdar(&["station", "--config", path_arg(&config)]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(
        stderr.contains("bad_profile.toml") && stderr.contains("parameters.scale"),
        "{stderr}"
    );
    // The good profile: the station starts and says whose calibration it applies.
    let good = dir.join("good_profile.toml");
    std::fs::write(&good, &good_text).unwrap();
    let config = dir.join("station_good.toml");
    std::fs::write(&config, "calibration_profile = \"good_profile.toml\"\n").unwrap();
    let domain = test_domain().to_string();
    let mut station = Command::new(pomdar_binary().unwrap())
        .args([
            "station",
            "--config",
            path_arg(&config),
            "--domain-id",
            &domain,
        ])
        .args(["--interface", "127.0.0.1"])
        .stderr(Stdio::piped())
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    let stderr = station.stderr.take().unwrap();
    let mut seen = Vec::new();
    for line in BufReader::new(stderr).lines() {
        let line = line.unwrap();
        let done = line.starts_with("calibration profile:") || line.starts_with("error");
        seen.push(line);
        if done {
            break;
        }
    }
    station.kill().ok();
    station.wait().unwrap();
    let last = seen.last().cloned().unwrap_or_default();
    assert!(
        last.starts_with("calibration profile:") && last.contains(&format!("user {USER}")),
        "{seen:?}"
    );
}
