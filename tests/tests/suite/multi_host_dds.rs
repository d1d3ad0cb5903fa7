//! Three hosts over DDS, as docs/DEPLOYMENT.md deploys them: the glove PC (A) replays the
//! reference recording, the station PC (B) runs `pomdar station --record`, the robot PC (C)
//! runs the mock hand and mock Franka, and `pomdar relay` for the station's commands; each host a network namespace cabled to a switch (a
//! bridge), addresses 10.251.0.1–3/24 inside the namespaces only. The commands are the guide's
//! `# on host` blocks, read from the guide and run as written.
//!
//! Asserted: joint targets and arm targets arrive on C at the station's control rate (the
//! guide's probe on C); pulling A's cable makes the station hold, then disengage, and the
//! trial log on B shows the gap, the held commands, the status turning held then disengaged,
//! the arm targets stopping, the frames after the cable is back, and every frame the station
//! counted. Skipped with a message where network namespaces cannot be created; under CI it
//! fails instead.

use std::path::Path;
use std::time::Duration;

use msgs::{JointState, StringMsg};
use pomdar_tests::guide_session::{
    GUIDE_HOSTS, Session, guide_blocks_and_station_config, lab_tag_or_skip, session_dir, wall_ns,
};
use pomdar_tests::interop::reference_file;
use pomdar_tests::netns_lab::NetnsLab;
use pomdar_tests::workspace_root;
use serde_json::Value;
use station::StationConfig;
use teleop::mcap_log::{LoggedMessage, TRIAL_EVENTS_TOPIC, TrialReader};

const MS: i64 = 1_000_000;
/// How long host A's cable stays pulled: longer than the disengage timeout.
const CUT: Duration = Duration::from_secs(3);
/// How long the replay runs after the cable is back, before everything stops.
const AFTER_RESTORE: Duration = Duration::from_secs(4);
const JOINT_TARGETS: &str = "/pomdar/hand/joint_targets";
const ARM_TARGETS: &str = "/franka/end_effector_pose_cmd";
const KEYPOINTS: &str = "/ingress/mano";
const STATUS: &str = "/pomdar/status";

/// The rate `pomdar probe` printed for `topic` (`  /topic  25.0 Hz (...)`).
fn probe_rate(report: &str, topic: &str) -> f64 {
    let line = report
        .lines()
        .skip_while(|l| l.trim() != "topics")
        .find(|l| l.split_whitespace().next() == Some(topic))
        .unwrap_or_else(|| panic!("the probe reported nothing for {topic}:\n{report}"));
    let words: Vec<&str> = line.split_whitespace().collect();
    assert_eq!(
        words.get(2),
        Some(&"Hz"),
        "{topic} not heard on host C: {line}"
    );
    words[1].parse().unwrap()
}

fn status_state(message: &LoggedMessage) -> (i64, String) {
    let status: Value = serde_json::from_str(&message.decode::<StringMsg>().unwrap().data).unwrap();
    (
        message.log_time_ns,
        status["state"].as_str().unwrap_or_default().to_string(),
    )
}

/// Where the glove frames stop and resume in the trial log.
struct Gap {
    /// Log times of every glove frame.
    frames: Vec<i64>,
    /// The first frame after the gap.
    back_ns: i64,
    /// The last *new* frame before the gap (keypoints changed from the one before).
    last_new_ns: i64,
}

/// The gap: the longest silence between glove frames is where the cable was pulled, as long
/// as the cut, with enough frames recorded after the cable was back.
fn check_gap(log: &TrialReader, cut_ns: i64, restored_ns: i64) -> Gap {
    let frames: Vec<i64> = log.messages_on(KEYPOINTS).map(|m| m.log_time_ns).collect();
    assert!(frames.len() > 100, "{} glove frames recorded", frames.len());

    let (gap_index, gap_ns) = frames
        .windows(2)
        .enumerate()
        .map(|(i, w)| (i, w[1] - w[0]))
        .max_by_key(|(_, gap)| *gap)
        .unwrap();
    let last_ns = frames[gap_index];
    let back_ns = frames[gap_index + 1];
    // Freshness is the age of the last *new* frame: the glove's ingress republishes its last
    // keypoints at 200 Hz between real changes (~24 a second), and a repeat refreshes nothing.
    let payloads: Vec<&[u8]> = log
        .messages_on(KEYPOINTS)
        .map(|m| m.data.as_slice())
        .collect();
    let last_new_ns = (1..=gap_index)
        .rev()
        .find(|&i| payloads[i] != payloads[i - 1])
        .map_or(frames[0], |i| frames[i]);
    println!(
        "trial log: {} glove frames; gap {} ms from {} ms after the cut to {} ms after the restore; last new frame {} ms before the gap",
        frames.len(),
        gap_ns / MS,
        (last_ns - cut_ns) / MS,
        (back_ns - restored_ns) / MS,
        (last_ns - last_new_ns) / MS
    );
    assert!(
        gap_ns >= CUT.as_nanos() as i64 - 300 * MS,
        "the longest gap in the glove frames is {} ms, the cable was pulled for {} ms",
        gap_ns / MS,
        CUT.as_millis()
    );
    assert!(
        (last_ns - cut_ns).abs() < 500 * MS && (back_ns - restored_ns).abs() < 2_000 * MS,
        "the gap ({last_ns}..{back_ns}) is not where the cable was pulled ({cut_ns}..{restored_ns})"
    );
    let after = frames.len() - gap_index - 1;
    assert!(
        after >= 100,
        "only {after} glove frames recorded after the cable was back"
    );
    Gap {
        frames,
        back_ns,
        last_new_ns,
    }
}

/// The hand commands in the trial log, and how they held through the gap.
struct HandCommands {
    /// Every hand command: (log time, held).
    all: Vec<(i64, bool)>,
    /// The first held command, after the last new frame.
    hold_after_ms: i64,
    /// Held commands after the first, in the gap.
    held_in_gap: usize,
    /// Held commands after the cable was back.
    held_after: usize,
}

/// Held hand commands carry the station clock (stamp = log time); commands computed from a
/// frame carry the frame's source stamp. Once the hand holds, every command in the gap is held
/// and they keep flowing at the control rate (≥ 80 %); commands flow again after the gap.
fn check_hand_held_through_gap(
    log: &TrialReader,
    config: &StationConfig,
    gap: &Gap,
) -> HandCommands {
    let hand: Vec<(i64, bool)> = log
        .messages_on(JOINT_TARGETS)
        .map(|m| {
            let stamp = m.decode::<JointState>().unwrap().header.stamp.to_nanos();
            (m.log_time_ns, stamp == m.log_time_ns)
        })
        .collect();
    let first_held = hand
        .iter()
        .find(|(t, held)| *t > gap.last_new_ns && *held)
        .map(|(t, _)| *t)
        .expect("no held hand command after the last frame before the gap");
    assert!(
        hand.iter()
            .filter(|(t, _)| *t > first_held && *t < gap.back_ns)
            .all(|(_, held)| *held),
        "a command during the gap was not held"
    );
    let held_in_gap = hand
        .iter()
        .filter(|(t, _)| *t > first_held && *t < gap.back_ns)
        .count();
    let held_after = hand
        .iter()
        .filter(|(t, held)| *t > gap.back_ns && *held)
        .count();
    let gap_s = (gap.back_ns - first_held) as f64 * 1e-9;
    assert!(
        held_in_gap as f64 >= 0.8 * config.control.rate_hz * gap_s,
        "{held_in_gap} held commands over {gap_s:.2} s of gap"
    );
    assert!(held_after > 0, "no hand command after the cable was back");
    HandCommands {
        hold_after_ms: (first_held - gap.last_new_ns) / MS,
        all: hand,
        held_in_gap,
        held_after,
    }
}

/// The arm targets in the trial log: their log times, when the last before the gap came
/// (after the last new frame) and how many came after it.
struct ArmTargets {
    all: Vec<i64>,
    stop_ms: i64,
    after: usize,
}

fn arm_targets(log: &TrialReader, gap: &Gap) -> ArmTargets {
    let arm: Vec<i64> = log
        .messages_on(ARM_TARGETS)
        .map(|m| m.log_time_ns)
        .collect();
    let last_arm = arm
        .iter()
        .copied()
        .filter(|t| *t < gap.back_ns)
        .max()
        .expect("no arm target before the gap");
    ArmTargets {
        stop_ms: (last_arm - gap.last_new_ns) / MS,
        after: arm.iter().filter(|t| **t > last_arm).count(),
        all: arm,
    }
}

/// The hand holds after the hold timeout; the arm gets targets until the disengage timeout,
/// none after (disengaged until engage). The status: held, then disengaged during the gap,
/// still disengaged after; and it kept being recorded through the gap.
fn check_hold_then_disengage(
    log: &TrialReader,
    config: &StationConfig,
    gap: &Gap,
    hand: &HandCommands,
    arm: &ArmTargets,
) {
    let hold_ms = config.watchdog.hold_timeout_ms as i64;
    let disengage_ms = config.watchdog.disengage_timeout_ms as i64;
    let tick_ms = (1000.0 / config.control.rate_hz).ceil() as i64;
    let statuses: Vec<(i64, String)> = log.messages_on(STATUS).map(status_state).collect();
    let first_state = |state: &str| {
        statuses
            .iter()
            .find(|(t, s)| *t > gap.last_new_ns && s == state)
            .map(|(t, _)| (*t - gap.last_new_ns) / MS)
    };
    let held_status_ms = first_state("held").expect("no `held` status after the gap began");
    let disengaged_status_ms =
        first_state("disengaged").expect("no `disengaged` status after the gap began");
    let status_gap_ms = statuses
        .windows(2)
        .map(|w| (w[1].0 - w[0].0) / MS)
        .max()
        .unwrap();
    let (hold_after_ms, arm_stop_ms) = (hand.hold_after_ms, arm.stop_ms);
    println!(
        "hold: first held command {hold_after_ms} ms after the last new frame ({} held commands in the gap, {} after), status `held` at {held_status_ms} ms; last arm target at {arm_stop_ms} ms, `disengaged` status at {disengaged_status_ms} ms; longest status interval {status_gap_ms} ms",
        hand.held_in_gap, hand.held_after
    );
    assert!(
        (hold_ms..=hold_ms + tick_ms + 150).contains(&hold_after_ms),
        "held {hold_after_ms} ms after the last new frame; configured {hold_ms} ms (+ one {tick_ms} ms tick)"
    );
    assert!(
        (disengage_ms - tick_ms..=disengage_ms + tick_ms + 300).contains(&arm_stop_ms),
        "the last arm target came {arm_stop_ms} ms after the last new frame; disengage at {disengage_ms} ms"
    );
    assert_eq!(
        arm.after, 0,
        "{} arm targets after the disengage (the station must stay disengaged until engage)",
        arm.after
    );
    assert!(held_status_ms < disengaged_status_ms);
    assert!(
        statuses
            .iter()
            .filter(|(t, _)| *t > gap.back_ns + 500 * MS)
            .all(|(_, s)| s == "disengaged"),
        "the station re-engaged by itself after the cable was back"
    );
    let status_period_ms = (1000.0 / config.output.status_rate_hz) as i64;
    assert!(
        status_gap_ms <= 2 * status_period_ms,
        "the status was not recorded for {status_gap_ms} ms"
    );
}

/// Nothing the station received or sent is missing from the log: every frame up to the last
/// status is counted in it, and the stop event's totals match the commands logged.
fn check_nothing_missing(log: &TrialReader, frames: &[i64], hand_commands: usize, arm: usize) {
    let (last_status_ns, last_status) = log
        .messages_on(STATUS)
        .map(|m| {
            let status: Value =
                serde_json::from_str(&m.decode::<StringMsg>().unwrap().data).unwrap();
            (m.log_time_ns, status)
        })
        .last()
        .unwrap();
    let counters = &last_status["counters"];
    let counted = counters["frames_new"].as_u64().unwrap()
        + counters["frames_repeated"].as_u64().unwrap()
        + counters["rejected"]
            .as_object()
            .unwrap()
            .values()
            .map(|v| v.as_u64().unwrap())
            .sum::<u64>();
    let logged = frames.iter().filter(|t| **t <= last_status_ns).count() as u64;
    assert_eq!(
        logged, counted,
        "frames in the log up to the last status vs the station's counters"
    );
    let events = log.decode_topic::<StringMsg>(TRIAL_EVENTS_TOPIC).unwrap();
    let stop: Value = serde_json::from_str(&events.last().unwrap().data).unwrap();
    assert_eq!(stop["event"], "stop", "{stop}");
    assert_eq!(
        stop["summary"]["hand_commands"].as_u64().unwrap(),
        hand_commands as u64
    );
    assert_eq!(stop["summary"]["arm_targets"].as_u64().unwrap(), arm as u64);
}

/// What the trial log on host B shows about the cut.
fn check_trial_log(path: &Path, config: &StationConfig, cut_ns: i64, restored_ns: i64) {
    let log = TrialReader::open(path).unwrap();
    let gap = check_gap(&log, cut_ns, restored_ns);
    let hand = check_hand_held_through_gap(&log, config, &gap);
    let arm = arm_targets(&log, &gap);
    check_hold_then_disengage(&log, config, &gap, &hand, &arm);
    check_nothing_missing(&log, &gap.frames, hand.all.len(), arm.all.len());
}

/// The check on C (the last block's output): commands at the station's rate (±20 %).
fn check_probe_rates(report: &str, config: &StationConfig) {
    let joint_hz = probe_rate(report, JOINT_TARGETS);
    let arm_hz = probe_rate(report, ARM_TARGETS);
    let rate = config.control.rate_hz;
    println!(
        "on host C: joint targets {joint_hz:.1} Hz, arm targets {arm_hz:.1} Hz (configured {rate} Hz)"
    );
    for (topic, hz) in [(JOINT_TARGETS, joint_hz), (ARM_TARGETS, arm_hz)] {
        assert!(
            hz >= 0.8 * rate && hz <= 1.2 * rate,
            "{topic} arrives on host C at {hz:.1} Hz, the station runs at {rate} Hz"
        );
    }
}

/// Ctrl-C: the station first (it finishes its log, and must exit cleanly), then the glove and
/// the robot.
fn stop_nodes(session: &mut Session<'_>) {
    let station = session.node("B", "pomdar station");
    let status = station.interrupt();
    assert!(
        status.success(),
        "the station exited with {status}: {}",
        station.output()
    );
    println!("host B: {}", station.output().trim_end());
    let replay = session.node("A", "pomdar replay");
    replay.interrupt();
    println!("host A: {}", replay.output().trim_end());
    for node in session.nodes.iter_mut().filter(|n| n.host == "C") {
        node.interrupt();
        println!("host C: {}", node.output().trim_end());
    }
}

/// What `pomdar relay` on host C said at exit about one robot topic.
#[derive(Debug)]
struct RelayLine {
    forwarded: u64,
    dropped: u64,
    /// Dropped as too old by the command's header stamp (its glove frame's time) only, the
    /// station–robot link having delivered it within the limit: the glove link was cut.
    dropped_input_late: u64,
    lost_in_dds: u64,
    not_published: u64,
}

/// `relay: TOPIC: forwarded F, dropped D (O older than 100 ms of which W by their stamp only
/// (late input, not the link), A ahead of this clock, U without a send time or stamp), L lost
/// in DDS, P not published`.
fn relay_line(session: &Session<'_>, topic: &str) -> RelayLine {
    let text = session.output_of("C", "pomdar relay");
    let prefix = format!("relay: {topic}: forwarded ");
    let line = text
        .lines()
        .find(|l| l.starts_with(&prefix))
        .unwrap_or_else(|| panic!("the relay said nothing about {topic} at exit: {text}"));
    let numbers: Vec<u64> = line[prefix.len() - "forwarded ".len()..]
        .split(|c: char| !c.is_ascii_digit())
        .filter_map(|w| w.parse().ok())
        .collect();
    let [
        forwarded,
        dropped,
        _old,
        _limit,
        late,
        _ahead,
        _unstamped,
        lost,
        failed,
    ] = numbers[..]
    else {
        panic!("unexpected relay summary: {line}");
    };
    RelayLine {
        forwarded,
        dropped,
        dropped_input_late: late,
        lost_in_dds: lost,
        not_published: failed,
    }
}

/// Host C heard every command the station sent (reliable QoS, and the B–C link stayed up),
/// except those the relay dropped as older than `[robot_link] max_age_ms` by their header
/// stamp only (their glove frame's time; the B–C link delivered them within the limit): the
/// commands between 100 ms into the glove cut and the hold at 150 ms, still stamped with the
/// last frame's time. Every
/// command is accounted for: sent = forwarded + dropped, heard = forwarded, and nothing
/// dropped for the link's sake, lost or left unpublished.
fn check_c_heard_every_command(session: &Session<'_>) {
    // `stopped: 216 new frames, 301 hand commands, 151 arm targets, ...`
    let sent = |what: &str| -> u64 {
        let text = session.output_of("B", "pomdar station");
        let words: Vec<&str> = text.split_whitespace().collect();
        let at = words
            .windows(3)
            .position(|w| format!("{} {}", w[1], w[2].trim_end_matches(',')) == what)
            .unwrap_or_else(|| panic!("the station's summary has no `{what}`: {text}"));
        words[at].parse().unwrap()
    };
    let received = |program: &str| -> u64 {
        let text = session.output_of("C", program);
        let rest = text
            .split("received ")
            .nth(1)
            .unwrap_or_else(|| panic!("`{program}` printed no summary: {text}"));
        rest.split_whitespace().next().unwrap().parse().unwrap()
    };
    for (topic, program, what) in [
        (JOINT_TARGETS, "pomdar mock-hand", "hand commands"),
        (ARM_TARGETS, "pomdar mock-franka", "arm targets"),
    ] {
        let relay = relay_line(session, topic);
        println!(
            "{topic}: {} sent by the station, relay {relay:?}",
            sent(what)
        );
        assert_eq!(
            relay.forwarded + relay.dropped,
            sent(what),
            "{topic}: relayed or dropped vs sent by the station"
        );
        assert_eq!(
            (relay.dropped, relay.lost_in_dds, relay.not_published),
            (relay.dropped_input_late, 0, 0),
            "{topic}: the relay dropped for the link's sake, or lost commands: {relay:?}"
        );
        assert_eq!(
            received(program),
            relay.forwarded,
            "{topic}: received on C vs forwarded by the relay"
        );
    }
}

#[test]
fn three_hosts_deployed_as_the_guide_says_drive_the_robot_and_hold_when_the_glove_link_is_cut() {
    let Some(_reference) = reference_file("rokoko_orca_2024-11-20.mcap") else {
        return;
    };
    let Some(tag) = lab_tag_or_skip() else {
        return;
    };
    let (blocks, config) = guide_blocks_and_station_config(&workspace_root());
    let (dir, bin) = session_dir("multi-host", &tag);

    let lab = NetnsLab::create(&tag, &GUIDE_HOSTS).unwrap();
    let mut session = Session::new(&lab, dir.clone(), bin);
    let mut reports = Vec::new();
    for block in &blocks {
        println!("== {}", block.title);
        reports.extend(session.run(block));
    }
    check_probe_rates(
        reports.last().expect("the check block printed nothing"),
        &config,
    );

    // Pull the glove PC's cable, plug it back.
    let cut_ns = wall_ns();
    lab.cut("A").unwrap();
    std::thread::sleep(CUT);
    let restored_ns = wall_ns();
    lab.restore("A").unwrap();
    std::thread::sleep(AFTER_RESTORE);

    stop_nodes(&mut session);
    check_c_heard_every_command(&session);

    let trial = session.home("B").join("pomdar-trials/deploy_check.mcap");
    assert!(
        trial.is_file(),
        "the station's trial log {} is missing",
        trial.display()
    );
    check_trial_log(&trial, &config, cut_ns, restored_ns);
    drop(session);
    drop(lab);
    std::fs::remove_dir_all(&dir).ok();
}
