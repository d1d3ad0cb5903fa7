//! Glove faults against the real station over loopback DDS, each asserting exactly what
//! docs/FAULTS.md says the station does: drop-outs shorter and longer than the hold timeout,
//! a dead glove whose ingress republishes its last frame, bursts (timer and every-frame
//! control), duplicated frames, out-of-order frames, and jumps of the sender's clock. (SIGKILL
//! of the station is `fault_station_kill.rs`; the glove lost for good, then an explicit engage,
//! is `station_dds.rs`.)
//!
//! Frames whose DDS source stamp matters are sent by [`StampedGlove`], which sets it; the
//! station here shares the test's clock, so times on both sides compare directly.

use std::time::Duration;

use msgs::JointState;
use nalgebra::{Isometry3, Point3};
use pomdar_tests::stamped_glove::StampedGlove;
use pomdar_tests::station_harness::{Harness, Heard, test_domain};
use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove};
use retarget::{EmbodimentCatalog, HandModel, KeypointLayout, Retargeter};
use station::time_step_between;
use station::{ControlMode, StationConfig};
use teleop::ros::QosConfig;
use teleop::station_node::ros_node::OperatorCommand;

const MS: i64 = 1_000_000;
const HOUR: i64 = 3_600_000 * MS;
/// Loopback delivery of a frame to the station, and the scheduling of its timer, under load.
const DELIVERY_SLACK_NS: i64 = 15 * MS;

fn glove() -> SimGlove {
    let shape = HumanHandShape::average();
    let motion = Motion::new(MotionKind::OpenClose, 4.0, &shape).unwrap();
    SimGlove::new(shape, motion, KeypointLayout::Lab22).unwrap()
}

fn rows(glove: &SimGlove, t: f64) -> Vec<[f32; 3]> {
    glove
        .frame(t)
        .0
        .iter()
        .map(|p| [p.x as f32, p.y as f32, p.z as f32])
        .collect()
}

fn points(glove: &SimGlove, t: f64) -> (Vec<Point3<f64>>, Isometry3<f64>) {
    glove.frame(t)
}

fn config(mode: ControlMode) -> StationConfig {
    let mut config = StationConfig::default();
    config.control.mode = mode;
    config.control.auto_engage = true;
    config.input.qos = QosConfig::reliable(1000);
    config.output.qos = QosConfig::reliable(1000);
    config.output.status_rate_hz = 20.0;
    config
}

async fn stamped_glove(h: &Harness) -> StampedGlove {
    let glove = StampedGlove::new(&h.network, "/ingress/mano", QosConfig::reliable(1000)).unwrap();
    glove
        .wait_for_reader(Duration::from_secs(15))
        .await
        .unwrap();
    glove
}

/// Keypoints and wrist through the harness (source stamp: now), `seconds` at `rate_hz`.
async fn play(h: &Harness, glove: &SimGlove, from_s: f64, seconds: f64, rate_hz: f64) {
    for i in 0..(seconds * rate_hz) as usize {
        let t = from_s + i as f64 / rate_hz;
        let (keypoints, wrist) = points(glove, t);
        h.publish(&keypoints, &wrist).await.unwrap();
        tokio::time::sleep(Duration::from_secs_f64(1.0 / rate_hz)).await;
    }
}

/// Stamped frames at `rate_hz` for `seconds`, each stamped now + `offset_ns`; returns the
/// stamps sent.
async fn play_stamped(
    h: &Harness,
    sender: &StampedGlove,
    glove: &SimGlove,
    from_s: f64,
    seconds: f64,
    offset_ns: i64,
) -> Vec<i64> {
    let mut stamps = Vec::new();
    for i in 0..(seconds * 50.0) as usize {
        let stamp = h.clock.now_ns() + offset_ns;
        sender
            .publish(&rows(glove, from_s + i as f64 * 0.02), stamp)
            .await
            .unwrap();
        stamps.push(stamp);
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    stamps
}

fn stamp_ns(m: &JointState) -> i64 {
    m.header.stamp.to_nanos()
}

/// The DDS timestamp keeps 2^-32 s: a stamp comes back within a nanosecond or so.
fn same_stamp(a: i64, b: i64) -> bool {
    (a - b).abs() < 1_000
}

/// The stamps of the joint targets that were computed from a frame of `burst`, in arrival
/// order (a held command repeats its frame's stamp).
fn burst_stamps_driven(heard: &Heard, burst: &[i64]) -> Vec<i64> {
    heard
        .targets
        .iter()
        .map(|(_, m)| stamp_ns(m))
        .filter(|s| burst.iter().any(|b| same_stamp(*b, *s)))
        .collect()
}

/// The latest status counters, once `condition` holds on them (at most 5 s).
async fn counters_when(
    h: &Harness,
    condition: impl Fn(&serde_json::Value) -> bool,
) -> serde_json::Value {
    h.wait_until(Duration::from_secs(5), |heard| {
        heard
            .status
            .last()
            .is_some_and(|(_, s)| condition(&s["counters"]))
    })
    .await
    .unwrap_or_else(|e| panic!("{e}: last status {:?}", h.last_status()));
    h.last_status().unwrap()["counters"].clone()
}

fn states_between(heard: &Heard, from: i64, to: i64) -> Vec<String> {
    heard
        .status
        .iter()
        .filter(|(t, _)| *t > from && *t <= to)
        .map(|(_, s)| s["state"].as_str().unwrap_or("").to_string())
        .collect()
}

/// The first held command (the first stamped later than the last frame) comes within one
/// control tick after the hold timeout, on the last frame's clock: the station got that frame
/// at most a loopback delivery after its stamp.
fn check_first_held_within_a_tick(in_gap: &[&JointState], last_fresh: &JointState) {
    let config = config(ControlMode::Rate);
    let last_stamp = stamp_ns(last_fresh);
    let first_held = in_gap
        .iter()
        .map(|m| stamp_ns(m))
        .find(|s| *s > last_stamp)
        .expect("no held command in the gap");
    let hold = config.watchdog.hold_timeout_ms as i64 * MS;
    let tick = (1e9 / config.control.rate_hz) as i64;
    let after = first_held - last_stamp;
    println!(
        "first held command {:.1} ms after the last frame (hold {} ms, tick {} ms)",
        after as f64 / 1e6,
        hold / MS,
        tick / MS
    );
    assert!(
        after > hold && after <= hold + tick + DELIVERY_SLACK_NS,
        "first held command {after} ns after the last frame: not within one tick after the hold timeout"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn dropouts_shorter_than_the_hold_timeout_change_nothing_longer_ones_hold_then_follow_again()
{
    let h = Harness::start(config(ControlMode::Rate), test_domain())
        .await
        .unwrap();
    let glove = glove();
    play(&h, &glove, 0.0, 0.6, 50.0).await;

    // 80 ms without frames (hold timeout 150 ms): still engaged throughout.
    let short_gap = h.clock.now_ns();
    tokio::time::sleep(Duration::from_millis(80)).await;
    play(&h, &glove, 0.7, 0.3, 50.0).await;
    let after_short = h.clock.now_ns();

    // A gap between the hold and the disengage timeouts: held within one tick of the hold
    // timeout, not disengaged.
    let watchdog = config(ControlMode::Rate).watchdog;
    // (100 ms short of the disengage timeout: the last frame went out up to 20 ms earlier.)
    let medium_gap_ms = watchdog.disengage_timeout_ms - 100;
    let stopped = h.clock.now_ns();
    tokio::time::sleep(Duration::from_millis(medium_gap_ms)).await;
    let resumed = h.clock.now_ns();
    play(&h, &glove, 1.5, 0.6, 50.0).await;
    let end = h.clock.now_ns();

    {
        let heard = h.heard.lock().unwrap();
        let short = states_between(&heard, short_gap, after_short);
        assert!(
            !short.is_empty() && short.iter().all(|s| s == "engaged"),
            "{short:?}"
        );
        let medium = states_between(&heard, stopped, end);
        assert!(medium.iter().any(|s| s == "held"), "{medium:?}");
        assert!(medium.iter().all(|s| s != "disengaged"), "{medium:?}");
        // The hand repeats its last command through the gap; once held (timeout + one 40 ms tick)
        // the command is stamped with the station's clock, not the last frame's source time.
        // The last frame was sent 20 ms before `stopped`; its command is heard on the next
        // 40 ms tick after delivery, so the gap is judged from `settled` (before the timeout).
        let settled = stopped + 100 * MS;
        let last_fresh = heard
            .targets
            .iter()
            .rfind(|(t, _)| *t <= settled)
            .unwrap()
            .1
            .clone();
        let in_gap: Vec<&JointState> = heard
            .targets
            .iter()
            .filter(|(t, _)| *t > settled && *t <= resumed)
            .map(|(_, m)| m)
            .collect();
        // A held command every tick of the gap (all its whole ticks but one).
        let tick = (1e9 / config(ControlMode::Rate).control.rate_hz) as i64;
        let ticks_in_gap = ((resumed - settled) / tick - 1) as usize;
        assert!(
            in_gap.len() >= ticks_in_gap,
            "{} targets in the gap, {ticks_in_gap} ticks",
            in_gap.len()
        );
        assert!(
            in_gap.iter().all(|m| m.position == last_fresh.position),
            "the hand's command changed in the gap"
        );
        let held: Vec<&&JointState> = in_gap
            .iter()
            .filter(|m| stamp_ns(m) > stopped + 150 * MS)
            .collect();
        let held_ticks = ((resumed - stopped - 150 * MS) / tick - 1) as usize;
        assert!(
            held.len() >= held_ticks,
            "{} held targets, {held_ticks} ticks",
            held.len()
        );
        check_first_held_within_a_tick(&in_gap, &last_fresh);
        let arm_in_gap: Vec<_> = heard
            .arm
            .iter()
            .filter(|(t, _)| *t > settled && *t <= resumed)
            .map(|(_, m)| m.pose)
            .collect();
        assert!(!arm_in_gap.is_empty());
        assert!(
            arm_in_gap.windows(2).all(|w| w[0] == w[1]),
            "the arm target moved while held"
        );
        // Frames return: followed again without an engage.
        assert!(
            heard
                .targets
                .iter()
                .any(|(t, m)| *t > resumed && m.position != last_fresh.position),
            "the hand did not follow after the hold"
        );
        assert_eq!(
            states_between(&heard, end - 100 * MS, end).last().unwrap(),
            "engaged"
        );
    }
    h.stop().await.unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_dead_glove_republished_by_the_ingress_holds_then_disengages_the_arm_until_engage() {
    let h = Harness::start(config(ControlMode::Rate), test_domain())
        .await
        .unwrap();
    let glove = glove();
    play(&h, &glove, 0.0, 0.6, 50.0).await;
    let before = counters_when(&h, |c| c["frames_new"] == 30).await;

    // The glove dies; the ingress keeps republishing its last frame at 50 Hz (new source
    // stamps, same keypoints): repeats keep nothing alive.
    let died = h.clock.now_ns();
    let (last, wrist) = points(&glove, 0.58);
    for _ in 0..75 {
        h.publish(&last, &wrist).await.unwrap();
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let after = counters_when(&h, |c| {
        c["frames_repeated"].as_u64() >= Some(before["frames_repeated"].as_u64().unwrap() + 70)
    })
    .await;
    assert_eq!(after["frames_new"], before["frames_new"]);
    let disengaged_at = {
        let heard = h.heard.lock().unwrap();
        let states = states_between(&heard, died, h.clock.now_ns());
        assert!(states.iter().any(|s| s == "held"), "{states:?}");
        heard
            .status
            .iter()
            .find(|(t, s)| *t > died && s["state"] == "disengaged")
            .map(|(t, _)| *t)
            .unwrap_or_else(|| panic!("never disengaged: {states:?}"))
    };

    // New frames, no engage: the hand keeps its held command, the arm gets nothing.
    play(&h, &glove, 1.0, 0.5, 50.0).await;
    let engaged_at = h.clock.now_ns();
    {
        let heard = h.heard.lock().unwrap();
        let arm_late = heard
            .arm
            .iter()
            .filter(|(t, _)| *t > disengaged_at + 100 * MS)
            .count();
        assert_eq!(arm_late, 0, "arm targets after the disengage");
        let hand: Vec<&JointState> = heard
            .targets
            .iter()
            .filter(|(t, _)| *t > disengaged_at)
            .map(|(_, m)| m)
            .collect();
        assert!(
            hand.len() >= 10,
            "the hand stopped hearing its held command"
        );
        assert!(hand.windows(2).all(|w| w[0].position == w[1].position));
        // Held commands carry the station's clock.
        assert!(hand.iter().all(|m| stamp_ns(m) > died + 150 * MS));
    }

    // An explicit engage resumes hand and arm.
    h.operator(OperatorCommand::Engage);
    play(&h, &glove, 1.5, 0.6, 50.0).await;
    {
        let heard = h.heard.lock().unwrap();
        assert!(
            heard.arm.iter().any(|(t, _)| *t > engaged_at),
            "the arm did not resume after engage"
        );
        let held = &heard
            .targets
            .iter()
            .rfind(|(t, _)| *t <= engaged_at)
            .unwrap()
            .1;
        assert!(
            heard
                .targets
                .iter()
                .any(|(t, m)| *t > engaged_at && m.position != held.position)
        );
    }
    h.stop().await.unwrap();
}

/// A burst of `count` frames sent back to back after half a second of steady input; returns
/// their stamps, the time the burst started and the last frame.
async fn burst(
    h: &Harness,
    sender: &StampedGlove,
    glove: &SimGlove,
    count: usize,
) -> (Vec<i64>, i64, Vec<[f32; 3]>) {
    play_stamped(h, sender, glove, 0.0, 0.5, 0).await;
    counters_when(h, |c| c["frames_new"].as_u64() >= Some(25)).await;
    let started = h.clock.now_ns();
    let mut stamps = Vec::new();
    for i in 0..count {
        let stamp = started + i as i64 * 1_000; // a microsecond apart, in order
        sender
            .publish(&rows(glove, 0.5 + i as f64 * 0.002), stamp)
            .await
            .unwrap();
        stamps.push(stamp);
    }
    (
        stamps,
        started,
        rows(glove, 0.5 + (count - 1) as f64 * 0.002),
    )
}

/// The timer burst test checks which frame a command was computed from, so the joint-speed
/// limit, the input filter and the smoothing's speed and pinch-approach releases (whose history is every frame the
/// station took before) are lifted: the solution then depends on the frame and the previous command only (see
/// `station_dds.rs`, joint targets equal the in-process retargeter). On every-frame control
/// the frames of a burst are microseconds apart and the speed limit binds whatever its value,
/// so there the stamps and the count say it.
fn burst_config(mode: ControlMode) -> StationConfig {
    let mut config = config(mode);
    config.retarget.solver.max_joint_speed_rad_s = 100.0;
    config.retarget.solver.max_rate_dt_s = 1.0;
    config.retarget.input_filter.min_cutoff_hz = 0.0;
    config.retarget.smoothing.release_speed_m_s = 0.0;
    config.retarget.smoothing.approach_speed_m_s = 0.0;
    config
}

/// The command stamped `stamp` (its first occurrence) is what the retargeter computes for
/// `frame` from the command before it (to 1e-6 rad; another frame differs by far more), over
/// the time step between their frames' stamps, as the station reckons it: when a tick falls
/// inside the burst, two of its frames are driven a few microseconds apart, and the joint-speed
/// limit binds over that step.
fn assert_computed_from(heard: &Heard, config: &StationConfig, stamp: i64, frame: &[[f32; 3]]) {
    let k = heard
        .targets
        .iter()
        .position(|(_, m)| same_stamp(stamp_ns(m), stamp))
        .unwrap();
    let dt_s = time_step_between(stamp_ns(&heard.targets[k - 1].1), stamp);
    let mut reference = Retargeter::new(
        HandModel::orca_v1_right(),
        config.retarget.clone(),
        &EmbodimentCatalog::builtin(),
    )
    .unwrap();
    reference
        .set_command(&heard.targets[k - 1].1.position)
        .unwrap();
    let points: Vec<Point3<f64>> = frame
        .iter()
        .map(|r| Point3::new(f64::from(r[0]), f64::from(r[1]), f64::from(r[2])))
        .collect();
    let expected = reference.retarget(&points, dt_s).unwrap().q;
    let worst = heard.targets[k]
        .1
        .position
        .iter()
        .zip(&expected)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(
        worst <= 1e-6,
        "not computed from the newest frame: differs by {worst} rad"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_burst_on_timer_control_is_judged_whole_and_only_the_newest_frame_is_driven() {
    let config = burst_config(ControlMode::Rate);
    let h = Harness::start(config.clone(), test_domain()).await.unwrap();
    let sender = stamped_glove(&h).await;
    let glove = glove();
    let (burst, started, newest) = burst(&h, &sender, &glove, 200).await;
    // Every frame of the burst reaches the gate.
    counters_when(&h, |c| c["frames_new"].as_u64() >= Some(225)).await;
    tokio::time::sleep(Duration::from_millis(300)).await;

    {
        let heard = h.heard.lock().unwrap();
        let window = heard
            .targets
            .iter()
            .filter(|(t, _)| *t > started && *t <= started + 400 * MS)
            .count();
        assert!(window <= 13, "{window} targets in 400 ms at 25 Hz");
        // A tick without a new frame repeats the last command with its stamp: stamps never go
        // back, and few burst frames are ever driven.
        let from_burst = burst_stamps_driven(&heard, &burst);
        assert!(
            from_burst.windows(2).all(|w| w[0] <= w[1]),
            "an older frame after a newer one"
        );
        let mut driven = from_burst.clone();
        driven.dedup();
        println!("{} of 200 burst frames driven", driven.len());
        assert!(
            !driven.is_empty() && driven.len() <= 12,
            "{} of 200 burst frames driven",
            driven.len()
        );
        assert!(
            same_stamp(*from_burst.last().unwrap(), *burst.last().unwrap()),
            "the newest frame of the burst was not the last driven"
        );
        assert_computed_from(&heard, &config, *burst.last().unwrap(), &newest);
    }
    h.stop().await.unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_burst_on_every_frame_control_is_coalesced_and_the_newest_frame_wins() {
    let config = burst_config(ControlMode::OnArrival);
    let h = Harness::start(config.clone(), test_domain()).await.unwrap();
    let sender = stamped_glove(&h).await;
    let glove = glove();
    let (burst, _, _) = burst(&h, &sender, &glove, 200).await;
    counters_when(&h, |c| c["frames_new"].as_u64() >= Some(225)).await;
    tokio::time::sleep(Duration::from_millis(100)).await;

    {
        let heard = h.heard.lock().unwrap();
        let from_burst = burst_stamps_driven(&heard, &burst);
        println!("{} of 200 burst frames driven", from_burst.len());
        assert!(
            !from_burst.is_empty() && from_burst.len() < 200,
            "{} of 200 burst frames driven: no coalescing",
            from_burst.len()
        );
        assert!(
            from_burst.windows(2).all(|w| w[0] < w[1]),
            "an older frame after a newer one"
        );
        assert!(same_stamp(
            *from_burst.last().unwrap(),
            *burst.last().unwrap()
        ));
    }
    h.stop().await.unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn duplicated_frames_are_counted_as_repeats_and_change_no_output() {
    let h = Harness::start(config(ControlMode::OnArrival), test_domain())
        .await
        .unwrap();
    let sender = stamped_glove(&h).await;
    let glove = glove();
    play_stamped(&h, &sender, &glove, 0.0, 0.3, 0).await;
    let before = counters_when(&h, |c| c["frames_new"].as_u64() >= Some(15)).await;
    let repeats = before["frames_repeated"].as_u64().unwrap();

    let frame = rows(&glove, 0.5);
    let stamp = h.clock.now_ns();
    sender.publish(&frame, stamp).await.unwrap();
    tokio::time::sleep(Duration::from_millis(20)).await;
    // The same sample again (a duplicate on the wire), then the same keypoints sent anew.
    sender.publish(&frame, stamp).await.unwrap();
    tokio::time::sleep(Duration::from_millis(20)).await;
    sender.publish(&frame, stamp + 20 * MS).await.unwrap();
    let after = counters_when(&h, |c| c["frames_repeated"].as_u64() >= Some(repeats + 2)).await;
    tokio::time::sleep(Duration::from_millis(300)).await;

    assert_eq!(after["frames_repeated"].as_u64().unwrap(), repeats + 2);
    assert_eq!(
        after["frames_new"].as_u64().unwrap(),
        before["frames_new"].as_u64().unwrap() + 1
    );
    {
        let heard = h.heard.lock().unwrap();
        let driven: Vec<&JointState> = heard
            .targets
            .iter()
            .map(|(_, m)| m)
            .filter(|m| same_stamp(stamp_ns(m), stamp) || same_stamp(stamp_ns(m), stamp + 20 * MS))
            .collect();
        assert_eq!(
            driven.len(),
            1,
            "one command for the frame, none for its duplicates"
        );
        assert!(same_stamp(stamp_ns(driven[0]), stamp));
        let position = &driven[0].position;
        let first = heard
            .targets
            .iter()
            .position(|(_, m)| same_stamp(stamp_ns(m), stamp))
            .unwrap();
        assert!(
            heard.targets[first..]
                .iter()
                .all(|(_, m)| &m.position == position),
            "a duplicate changed the output"
        );
    }
    h.stop().await.unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_frame_sent_before_the_newest_is_rejected_as_out_of_order() {
    let h = Harness::start(config(ControlMode::OnArrival), test_domain())
        .await
        .unwrap();
    let sender = stamped_glove(&h).await;
    let glove = glove();
    play_stamped(&h, &sender, &glove, 0.0, 0.3, 0).await;
    counters_when(&h, |c| c["frames_new"].as_u64() >= Some(15)).await;

    let a = h.clock.now_ns();
    let (b, c, d) = (a + 20 * MS, a + 10 * MS, a + 40 * MS);
    for (t, stamp) in [(0.30, a), (0.32, b), (0.31, c), (0.34, d), (0.30, a)] {
        sender.publish(&rows(&glove, t), stamp).await.unwrap();
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let counters = counters_when(&h, |c| c["rejected"]["out_of_order"] == 2).await;
    assert_eq!(counters["source_clock_jumps"], 0);
    tokio::time::sleep(Duration::from_millis(100)).await;

    {
        let heard = h.heard.lock().unwrap();
        let driven: Vec<i64> = heard
            .targets
            .iter()
            .map(|(_, m)| stamp_ns(m))
            .filter(|s| *s >= a - MS && *s <= d + MS)
            .collect();
        assert_eq!(driven.len(), 3, "{driven:?}");
        assert!(same_stamp(driven[0], a) && same_stamp(driven[1], b) && same_stamp(driven[2], d));
    }
    h.stop().await.unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn jumps_of_the_sender_clock_are_followed_and_freshness_runs_on_the_station_clock() {
    let h = Harness::start(config(ControlMode::Rate), test_domain())
        .await
        .unwrap();
    let sender = stamped_glove(&h).await;
    let glove = glove();
    let start = h.clock.now_ns();
    let phases = [0, HOUR, -2 * HOUR];
    let mut sent = Vec::new();
    for (k, offset) in phases.iter().enumerate() {
        sent.push(play_stamped(&h, &sender, &glove, k as f64 * 0.5, 0.5, *offset).await);
    }
    let stopped = h.clock.now_ns();
    // When the last frame was sent, on the station's clock (its stamp was 2 h behind).
    let last_sent = sent[2].last().unwrap() + 2 * HOUR;
    let counters = counters_when(&h, |c| c["source_clock_jumps"] == 2).await;
    assert_eq!(counters["rejected"]["out_of_order"], 0);
    h.wait_until(Duration::from_secs(3), |heard| {
        heard
            .status
            .iter()
            .any(|(t, s)| *t > stopped && s["state"] == "disengaged")
    })
    .await
    .unwrap();
    tokio::time::sleep(Duration::from_millis(200)).await;
    let end = h.clock.now_ns();

    {
        let heard = h.heard.lock().unwrap();
        // Engaged from the first frames to the last, whatever the stamps said.
        let states = states_between(&heard, start + 300 * MS, stopped);
        assert!(states.iter().all(|s| s == "engaged"), "{states:?}");
        // Commands kept coming in every phase, each stamped with its frame's source time.
        for (k, stamps) in sent.iter().enumerate() {
            let driven = heard
                .targets
                .iter()
                .filter(|(_, m)| stamps.iter().any(|s| same_stamp(*s, stamp_ns(m))))
                .count();
            assert!(driven >= 8, "phase {k}: {driven} commands from its frames");
        }
        // The watchdog measured age on the station's clock: held after the hold timeout, not at
        // once (the last stamp was 2 h old) and not never; disengaged after the disengage timeout.
        let first = |state: &str| {
            heard
                .status
                .iter()
                .find(|(t, s)| *t > stopped && s["state"] == state)
                .map(|(t, _)| t - last_sent)
                .unwrap()
        };
        let (held_after, disengaged_after) = (first("held"), first("disengaged"));
        println!(
            "held {} ms, disengaged {} ms after the last frame",
            held_after / MS,
            disengaged_after / MS
        );
        let watchdog = config(ControlMode::Rate).watchdog;
        let (hold, disengage) = (
            watchdog.hold_timeout_ms as i64 * MS,
            watchdog.disengage_timeout_ms as i64 * MS,
        );
        assert!((hold..disengage).contains(&held_after));
        assert!((disengage..2 * disengage).contains(&disengaged_after));
        // Held commands carry the station's clock.
        let late: Vec<i64> = heard
            .targets
            .iter()
            .filter(|(t, _)| *t > stopped + 300 * MS)
            .map(|(_, m)| stamp_ns(m))
            .collect();
        assert!(!late.is_empty());
        assert!(late.iter().all(|s| *s > stopped && *s <= end), "{late:?}");
    }
    h.stop().await.unwrap();
}
