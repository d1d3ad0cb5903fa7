//! The station over real DDS on loopback: a test node plays the glove and listens to every
//! output of a production station node (`teleop::station_node::ros_node::run_station`), on a test-unique
//! domain id with loopback-only discovery.

use std::time::Duration;

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion};
use pomdar_tests::station_harness::{Harness, check_arm_targets, test_domain};
use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove};
use retarget::{EmbodimentCatalog, HandModel, KeypointLayout, Retargeter};
use station::arm::Constraint;
use station::{ControlMode, StationConfig};
use teleop::ros::NetworkContext as _;
use teleop::ros::QosConfig;
use teleop::station_node::ros_node::OperatorCommand;

const MS: i64 = 1_000_000;

fn glove() -> SimGlove {
    let shape = HumanHandShape::average();
    let motion = Motion::new(MotionKind::OpenClose, 4.0, &shape).unwrap();
    SimGlove::new(shape, motion, KeypointLayout::Lab22).unwrap()
}

/// The glove wrist at time `t`: a slow circle in the horizontal plane plus a vertical bob, so
/// an axis constraint has something to remove.
fn wrist(t: f64) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(0.03 * t.sin(), 0.03 * t.cos(), 0.02 * (2.0 * t).sin()),
        UnitQuaternion::from_euler_angles(0.1 * t.sin(), 0.0, 0.0),
    )
}

fn frame(glove: &SimGlove, t: f64) -> Vec<Point3<f64>> {
    glove.frame(t).0
}

fn config(mode: ControlMode) -> StationConfig {
    let mut config = StationConfig::default();
    config.control.mode = mode;
    config.control.auto_engage = true;
    config.input.qos = QosConfig::reliable(1000);
    config.output.qos = QosConfig::reliable(1000);
    config.output.status_rate_hz = 20.0;
    config.arm.constraint = Constraint::VerticalAxis;
    config
}

async fn play(h: &Harness, glove: &SimGlove, from_s: f64, seconds: f64, rate_hz: f64) {
    let frames = (seconds * rate_hz) as usize;
    for i in 0..frames {
        let t = from_s + i as f64 / rate_hz;
        h.publish(&frame(glove, t), &wrist(t)).await.unwrap();
        tokio::time::sleep(Duration::from_secs_f64(1.0 / rate_hz)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn hand_and_arm_targets_arrive_at_the_configured_rate_within_the_arm_limits() {
    let h = Harness::start(config(ControlMode::Rate), test_domain())
        .await
        .unwrap();
    let glove = glove();
    let start = h.clock.now_ns();
    play(&h, &glove, 0.0, 2.5, 100.0).await;
    let end = h.clock.now_ns();
    check_rate_and_arm(&h, start, end);
    h.stop().await.unwrap();
}

fn check_rate_and_arm(h: &Harness, start: i64, end: i64) {
    let heard = h.heard.lock().unwrap();
    // Steady state: the last two seconds of glove input.
    let window = (end - 2000 * MS, end);
    let targets = heard
        .targets
        .iter()
        .filter(|(t, _)| *t > window.0 && *t <= window.1)
        .count();
    println!(
        "joint targets in the last 2 s: {targets} (25 Hz configured), first after {} ms",
        (heard.targets[0].0 - start) / MS
    );
    assert!(
        (40..=60).contains(&targets),
        "{targets} targets in 2 s at 25 Hz"
    );
    for (_, m) in &heard.targets {
        assert_eq!(m.name.len(), 17);
        assert!(m.position.iter().all(|v| v.is_finite()));
    }

    let arm = StationConfig::default().arm;
    let poses: Vec<_> = heard
        .arm
        .iter()
        .map(|(_, m)| station::convert::pose_to_isometry(&m.pose).unwrap())
        .collect();
    assert!(poses.len() > 40, "{} arm targets", poses.len());
    check_arm_targets(&poses, &arm, Some(arm.vertical_axis));
    let first = poses[0].translation.vector;
    let moved = poses
        .iter()
        .map(|p| (p.translation.vector.z - first.z).abs())
        .fold(0.0, f64::max);
    assert!(
        moved > 0.005,
        "the arm should follow the vertical bob ({moved} m)"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn joint_targets_equal_the_in_process_retargeter_for_the_same_frames() {
    // With the rate limit out of the way the result does not depend on the time steps: only the
    // far-away, inactive rate bounds differ (the station's receive gaps are not exactly 20 ms),
    // which moves an interior-point solution within its tolerance (1e-9 to 1e-8 rad measured).
    // So the station's targets must equal what the retargeter computes in process to 1e-6 rad;
    // a wrong frame, order, layout or configuration differs by orders of magnitude more.
    let mut config = config(ControlMode::OnArrival);
    config.retarget.solver.max_joint_speed_rad_s = 100.0;
    config.retarget.solver.max_rate_dt_s = 1.0;
    let h = Harness::start(config.clone(), test_domain()).await.unwrap();
    let glove = glove();
    let frames: Vec<Vec<Point3<f64>>> = (0..60)
        .map(|i| {
            // What the station receives: the f32 message values.
            frame(&glove, i as f64 * 0.02)
                .iter()
                .map(|p| {
                    Point3::new(
                        f64::from(p.x as f32),
                        f64::from(p.y as f32),
                        f64::from(p.z as f32),
                    )
                })
                .collect()
        })
        .collect();
    for (i, f) in frames.iter().enumerate() {
        h.publish(f, &wrist(i as f64 * 0.02)).await.unwrap();
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    h.wait_until(Duration::from_secs(10), |heard| {
        heard.targets.len() >= frames.len()
    })
    .await
    .unwrap();

    let model = HandModel::orca_v1_right();
    let mut reference = Retargeter::new(
        model,
        config.retarget.clone(),
        &EmbodimentCatalog::builtin(),
    )
    .unwrap();
    let heard = h.heard.lock().unwrap();
    assert_eq!(
        heard.targets.len(),
        frames.len(),
        "one target per new frame"
    );
    for (i, (f, (_, message))) in frames.iter().zip(&heard.targets).enumerate() {
        // Same input, same previous command: start each frame from the station's last output so
        // sub-nanoradian differences cannot accumulate.
        if i > 0 {
            reference
                .set_command(&heard.targets[i - 1].1.position)
                .unwrap();
        }
        let expected = reference.retarget(f, 0.02).unwrap().q;
        let worst = message
            .position
            .iter()
            .zip(&expected)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(worst <= 1e-6, "frame {i}: differs by {worst} rad");
    }
}

fn state(h: &Harness) -> String {
    h.last_status()
        .and_then(|s| s["state"].as_str().map(str::to_string))
        .unwrap_or_default()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn glove_loss_holds_then_disengages_and_only_engage_resumes() {
    let h = Harness::start(config(ControlMode::Rate), test_domain())
        .await
        .unwrap();
    let glove = glove();
    play(&h, &glove, 0.0, 1.0, 50.0).await;
    let stopped = h.clock.now_ns();
    h.wait_until(Duration::from_secs(2), |heard| {
        heard
            .status
            .iter()
            .any(|(t, s)| *t > stopped && s["state"] == "held")
    })
    .await
    .unwrap();
    h.wait_until(Duration::from_secs(3), |heard| {
        heard
            .status
            .iter()
            .any(|(t, s)| *t > stopped && s["state"] == "disengaged")
    })
    .await
    .unwrap();
    {
        // Hold within one tick: every target after the last frame plus one tick (and delivery)
        // repeats the last command.
        let heard = h.heard.lock().unwrap();
        let held: Vec<_> = heard
            .targets
            .iter()
            .filter(|(t, _)| *t > stopped + 80 * MS)
            .collect();
        assert!(!held.is_empty());
        assert!(
            held.windows(2).all(|w| w[0].1.position == w[1].1.position),
            "held targets changed"
        );
    }
    let held_q = h
        .heard
        .lock()
        .unwrap()
        .targets
        .last()
        .unwrap()
        .1
        .position
        .clone();

    // Input returns: still disengaged, the hand keeps its held command.
    play(&h, &glove, 2.0, 0.5, 50.0).await;
    assert_eq!(state(&h), "disengaged");
    assert_eq!(
        h.heard.lock().unwrap().targets.last().unwrap().1.position,
        held_q
    );

    // An explicit engage resumes.
    h.operator(OperatorCommand::Engage);
    play(&h, &glove, 2.5, 0.5, 50.0).await;
    h.wait_until(Duration::from_secs(2), |heard| {
        heard
            .targets
            .last()
            .is_some_and(|(_, m)| m.position != held_q)
    })
    .await
    .unwrap();
    assert_eq!(state(&h), "engaged");
    h.stop().await.unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn malformed_frames_are_rejected_counted_and_change_nothing() {
    let h = Harness::start(config(ControlMode::OnArrival), test_domain())
        .await
        .unwrap();
    let glove = glove();
    play(&h, &glove, 0.0, 0.5, 50.0).await;
    h.wait_until(Duration::from_secs(2), |heard| heard.targets.len() >= 20)
        .await
        .unwrap();
    let before = h.heard.lock().unwrap().targets.len();
    let good: Vec<[f32; 3]> = frame(&glove, 0.52)
        .iter()
        .map(|p| [p.x as f32, p.y as f32, p.z as f32])
        .collect();
    let mut nan = good.clone();
    nan[9][1] = f32::NAN;
    let short = good[..21].to_vec();
    let giant: Vec<[f32; 3]> = good
        .iter()
        .map(|r| [r[0] * 10.0, r[1] * 10.0, r[2] * 10.0])
        .collect();
    for rows in [&nan, &short, &giant] {
        h.publish_rows(rows).await.unwrap();
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    h.wait_until(Duration::from_secs(3), |heard| {
        heard.status.last().is_some_and(|(_, s)| {
            let r = &s["counters"]["rejected"];
            r["non_finite"] == 1 && r["wrong_size"] == 1 && r["bone_length"] == 1
        })
    })
    .await
    .unwrap();
    assert_eq!(
        h.heard.lock().unwrap().targets.len(),
        before,
        "a rejected frame produced a target"
    );
    h.stop().await.unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_restarted_glove_publisher_is_followed_again() {
    let h = Harness::start(config(ControlMode::OnArrival), test_domain())
        .await
        .unwrap();
    let glove = glove();
    play(&h, &glove, 0.0, 0.4, 50.0).await;
    let before = h.heard.lock().unwrap().targets.len();
    // A new glove process: its own participant, node and publishers.
    let context = h.network.context().unwrap();
    let mut node = teleop::ros::RosNode::new(&context, "/", "restarted_glove").unwrap();
    let publisher = node
        .publisher::<msgs::Float32MultiArray>("/ingress/mano", QosConfig::reliable(100))
        .unwrap();
    let start = std::time::Instant::now();
    while publisher.get_subscription_count(node.node()) == 0 {
        assert!(start.elapsed() < Duration::from_secs(10));
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    for i in 0..20 {
        let rows: Vec<[f32; 3]> = frame(&glove, 0.4 + i as f64 * 0.02)
            .iter()
            .map(|p| [p.x as f32, p.y as f32, p.z as f32])
            .collect();
        publisher
            .async_publish(msgs::Float32MultiArray::from_points(&rows).unwrap())
            .await
            .unwrap();
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    h.wait_until(Duration::from_secs(3), |heard| {
        heard.targets.len() >= before + 15
    })
    .await
    .unwrap();
    h.stop().await.unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_second_publisher_on_the_arm_command_topic_is_detected_and_the_arm_stops() {
    let mut h = Harness::start(config(ControlMode::Rate), test_domain())
        .await
        .unwrap();
    let glove = glove();
    play(&h, &glove, 0.0, 0.5, 50.0).await;
    assert!(!h.heard.lock().unwrap().arm.is_empty());
    let intruder = h
        .node
        .publisher::<msgs::PoseStamped>("/franka/end_effector_pose_cmd", QosConfig::reliable(10))
        .unwrap();
    let glove_task = {
        let seen = Duration::from_secs(5);
        h.wait_until(seen, |heard| {
            heard
                .status
                .iter()
                .any(|(_, s)| s["arm"]["second_publisher"] == true)
        })
    };
    // Keep the glove alive while the station notices.
    let (noticed, ()) = tokio::join!(glove_task, play(&h, &glove, 0.5, 1.0, 50.0));
    noticed.unwrap();
    let arm_before = h.heard.lock().unwrap().arm.len();
    play(&h, &glove, 1.5, 0.5, 50.0).await;
    let arm_after = h.heard.lock().unwrap().arm.len();
    assert!(
        arm_after <= arm_before + 1,
        "arm targets kept coming: {arm_before} -> {arm_after}"
    );
    drop(intruder);
    let summary = h.stop().await.unwrap();
    assert!(summary.second_publisher_seen);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn each_trial_is_recorded_to_its_own_log() {
    use teleop::mcap_log::{TRIAL_EVENTS_TOPIC, TrialReader};
    use teleop::station_node::recorder::RecordingOptions;
    let h = Harness::start(config(ControlMode::Rate), test_domain())
        .await
        .unwrap();
    let glove = glove();
    let dir = std::env::temp_dir().join(format!("pomdar-trials-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    let trial = |n: u32| RecordingOptions {
        path: dir.join(format!("trial{n}.mcap")),
        metadata: [("trial_index".to_string(), n.to_string())].into(),
    };
    h.operator(OperatorCommand::StartTrial(trial(1)));
    play(&h, &glove, 0.0, 0.5, 50.0).await;
    h.operator(OperatorCommand::TrialEvent(
        serde_json::json!({"event": "progress", "value": 1}),
    ));
    play(&h, &glove, 0.5, 0.2, 50.0).await;
    h.operator(OperatorCommand::StartTrial(trial(2))); // finishes trial 1
    play(&h, &glove, 0.7, 0.5, 50.0).await;
    h.operator(OperatorCommand::StopTrial);
    tokio::time::sleep(Duration::from_millis(200)).await;
    let summary = h.stop().await.unwrap();
    assert_eq!(
        summary.recorded,
        vec![dir.join("trial1.mcap"), dir.join("trial2.mcap")]
    );
    for (n, expected) in [
        (1, vec!["start", "progress", "stop"]),
        (2, vec!["start", "stop"]),
    ] {
        let log = TrialReader::open(&dir.join(format!("trial{n}.mcap"))).unwrap();
        let kinds: Vec<String> = log
            .decode_topic::<msgs::StringMsg>(TRIAL_EVENTS_TOPIC)
            .unwrap()
            .iter()
            .map(|m| {
                serde_json::from_str::<serde_json::Value>(&m.data).unwrap()["event"]
                    .as_str()
                    .unwrap()
                    .to_string()
            })
            .collect();
        assert_eq!(kinds, expected, "trial {n}");
        assert_eq!(
            log.metadata_named("pomdar_trial").unwrap()["trial_index"],
            n.to_string()
        );
        let targets = log
            .topic("/pomdar/hand/joint_targets")
            .map_or(0, |t| t.message_count);
        assert!(targets >= 8, "trial {n}: {targets} joint targets");
    }
    std::fs::remove_dir_all(&dir).ok();
}
