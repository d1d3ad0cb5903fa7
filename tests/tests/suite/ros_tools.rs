//! What the station offers the lab's ROS tools, over real DDS on loopback from the
//! production station node:
//! - the joint names it publishes are the robot URDF's, and `/tf` + `/tf_static` composed from
//!   the root equal the URDF's forward kinematics computed by an independent implementation
//!   (the `k` crate reading `../shared/reference/orcahand_v1_right.urdf`) at the published
//!   joint positions, for the built-in model and for the model imported from that URDF (which
//!   also publishes the URDF text on `/robot_description`);
//! - the keypoint markers put the glove points where the retargeter compares them: frames made
//!   from the robot itself land on the robot's fingertips;
//! - `/diagnostics` names the glove, the hand and the arm, and the glove's level follows the
//!   frames;
//! - the `std_srvs/Trigger` services engage and disengage the station, and a trial service
//!   without a console says it cannot.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::time::Duration;

use msgs::{
    DiagnosticArray, DiagnosticStatus, JointState, Marker, MarkerArray, StringMsg, TFMessage,
    TransformStamped,
};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion};
use pomdar_tests::interop::reference_file;
use pomdar_tests::station_harness::{Harness, Inbox, test_domain, timing_independent_config};
use pomdar_tests::workspace_root;
use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove};
use retarget::{Finger, HandModel, JointMotion, KeypointLayout, PalmFrame};
use ros2_client::ServiceMapping;
use station::{ControlMode, StationConfig};
use teleop::hand_source::HandSource;
use teleop::ros::{QosConfig, TriggerRequest};
use teleop::station_node::operator::StationHooks;

const URDF: &str = "orcahand_v1_right.urdf";
const FK_TOLERANCE_M: f64 = 1e-6;
const FK_TOLERANCE_RAD: f64 = 1e-6;

/// Rate control (held commands repeat on every tick), engaging on fresh input, reliable deep
/// queues, status (and diagnostics) at 20 Hz.
fn config() -> StationConfig {
    let mut config = timing_independent_config();
    config.control.mode = ControlMode::Rate;
    config.output.status_rate_hz = 20.0;
    config
}

fn glove() -> SimGlove {
    let shape = HumanHandShape::average();
    let motion = Motion::new(MotionKind::OpenClose, 4.0, &shape).unwrap();
    SimGlove::new(shape, motion, KeypointLayout::Lab22).unwrap()
}

/// Play the simulated glove from `from_s` for `seconds` at 50 Hz (wrist still).
async fn play(h: &Harness, glove: &SimGlove, from_s: f64, seconds: f64) {
    let frames = (seconds * 50.0) as usize;
    for i in 0..frames {
        let t = from_s + i as f64 / 50.0;
        h.publish(&glove.frame(t).0, &Isometry3::identity())
            .await
            .unwrap();
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
}

fn status_state(h: &Harness) -> String {
    h.last_status()
        .and_then(|s| s["state"].as_str().map(str::to_string))
        .unwrap_or_default()
}

/// Wait until the station reports `state` in a status document received after `after_ns`.
async fn wait_for_state(h: &Harness, state: &str, after_ns: i64) {
    h.wait_until(Duration::from_secs(10), |heard| {
        heard
            .status
            .iter()
            .any(|(t, s)| *t > after_ns && s["state"] == state)
    })
    .await
    .unwrap_or_else(|_| panic!("the station never reported '{state}'"));
}

/// Play the glove, let the input go stale so the station holds (repeating its last command on
/// every tick) and wait for a few held commands. Returns the last joint target: the command
/// every later `/tf` is computed from.
async fn drive_then_hold(h: &Harness) -> JointState {
    let glove = glove();
    play(h, &glove, 0.0, 1.5).await;
    let stopped = h.clock.now_ns();
    wait_for_state(h, "held", stopped).await;
    let held = h.heard.lock().unwrap().targets.len();
    h.wait_until(Duration::from_secs(5), |heard| {
        heard.targets.len() >= held + 5
    })
    .await
    .unwrap();
    let heard = h.heard.lock().unwrap();
    let last: Vec<&JointState> = heard.targets.iter().rev().take(5).map(|(_, m)| m).collect();
    assert!(
        last.windows(2).all(|w| w[0].position == w[1].position),
        "held commands changed"
    );
    last[0].clone()
}

/// The transform tree the station published: per child frame its parent and its transform
/// (`/tf_static` once, then the latest `/tf` edge of each frame).
fn tf_edges(
    tf_static: &[(i64, TFMessage)],
    tf: &[(i64, TFMessage)],
) -> BTreeMap<String, (String, Isometry3<f64>)> {
    let all = tf_static.iter().chain(tf).flat_map(|(_, m)| &m.transforms);
    all.map(|t: &TransformStamped| {
        let (v, r) = (t.transform.translation, t.transform.rotation);
        let pose = Isometry3::from_parts(
            Translation3::new(v.x, v.y, v.z),
            UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(r.w, r.x, r.y, r.z)),
        );
        (t.child_frame_id.clone(), (t.header.frame_id.clone(), pose))
    })
    .collect()
}

/// `frame`'s pose in `root`, composed along the published edges; `None` when its chain does
/// not reach `root`.
fn compose(
    edges: &BTreeMap<String, (String, Isometry3<f64>)>,
    frame: &str,
    root: &str,
) -> Option<Isometry3<f64>> {
    let mut pose = Isometry3::identity();
    let mut at = frame;
    for _ in 0..=edges.len() {
        if at == root {
            return Some(pose);
        }
        let (parent, local) = edges.get(at)?;
        pose = local * pose;
        at = parent;
    }
    None
}

/// The URDF's joints by name, read by `k` (movable or not).
fn urdf_joints(chain: &k::Chain<f64>) -> BTreeMap<String, bool> {
    chain
        .iter()
        .map(|node| {
            let joint = node.joint();
            (joint.name.clone(), joint.is_movable())
        })
        .collect()
}

/// Every joint name the station publishes is one of the URDF's movable joints, each once,
/// and every movable joint of the URDF is published.
fn assert_joint_names_are_the_urdfs(target: &JointState, chain: &k::Chain<f64>) {
    let joints = urdf_joints(chain);
    let published: BTreeSet<&str> = target.name.iter().map(String::as_str).collect();
    assert_eq!(
        published.len(),
        target.name.len(),
        "a joint published twice"
    );
    for name in &target.name {
        assert_eq!(
            joints.get(name),
            Some(&true),
            "published joint {name} is not a movable joint of the URDF"
        );
    }
    for (name, movable) in &joints {
        assert!(
            !movable || published.contains(name.as_str()),
            "the URDF's movable joint {name} is not published"
        );
    }
    assert_eq!(target.position.len(), target.name.len());
}

/// Set `k`'s joints to the published positions (by name; within the URDF's limits, which
/// `set_joint_positions` checks).
fn set_published_positions(chain: &k::Chain<f64>, target: &JointState) {
    let by_name: BTreeMap<&str, f64> = target
        .name
        .iter()
        .map(String::as_str)
        .zip(target.position.iter().copied())
        .collect();
    let positions: Vec<f64> = chain
        .iter_joints()
        .map(|j| by_name[j.name.as_str()])
        .collect();
    chain
        .set_joint_positions(&positions)
        .unwrap_or_else(|e| panic!("published positions outside the URDF's limits: {e}"));
    chain.update_transforms();
}

/// A `k` pose (its own nalgebra version) as ours.
fn from_k(pose: &k::Isometry3<f64>) -> Isometry3<f64> {
    let (t, q) = (pose.translation.vector, pose.rotation.quaternion());
    Isometry3::from_parts(
        Translation3::new(t.x, t.y, t.z),
        UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q.w, q.i, q.j, q.k)),
    )
}

/// `/tf` + `/tf_static` composed from the URDF's root equal `k`'s forward kinematics at the
/// published positions, for every published frame; every published frame (but the arm
/// target's) is a URDF link, and they include the fingertips, the child link of each of the
/// model's revolute joints (`revolute_children`, URDF names) and every link the URDF draws.
fn assert_tf_is_the_urdf_kinematics(
    edges: &BTreeMap<String, (String, Isometry3<f64>)>,
    chain: &k::Chain<f64>,
    arm_target_frame: &str,
    revolute_children: &[String],
) {
    let root_node = chain.iter().next().unwrap();
    let root = root_node.link().as_ref().unwrap().name.clone();
    let mut compared = BTreeSet::new();
    let (mut worst_m, mut worst_rad) = ((0.0_f64, String::new()), 0.0_f64);
    for (frame, (parent, _)) in edges {
        if frame == arm_target_frame {
            continue;
        }
        let Some(node) = chain.find_link(frame) else {
            panic!("published frame {frame} (child of {parent}) is not a link of the URDF");
        };
        let ours = compose(edges, frame, &root)
            .unwrap_or_else(|| panic!("frame {frame}: its /tf chain does not reach {root}"));
        let theirs = from_k(&node.world_transform().unwrap());
        let error_m = (ours.translation.vector - theirs.translation.vector).norm();
        let error_rad = ours.rotation.angle_to(&theirs.rotation);
        if error_m >= worst_m.0 {
            worst_m = (error_m, frame.clone());
        }
        worst_rad = worst_rad.max(error_rad);
        assert!(error_m <= FK_TOLERANCE_M, "{frame}: {error_m} m from k");
        assert!(
            error_rad <= FK_TOLERANCE_RAD,
            "{frame}: {error_rad} rad from k"
        );
        compared.insert(frame.clone());
    }
    println!(
        "/tf vs k on {URDF}: {} frames, worst {:.2e} m ({}), rotations within {:.2e} rad",
        compared.len(),
        worst_m.0,
        worst_m.1,
        worst_rad
    );
    for finger in ["thumb", "index", "middle", "ring", "pinky"] {
        let tip = format!("right_{finger}_fingertip");
        assert!(compared.contains(&tip), "{tip} is not on /tf");
    }
    for child in revolute_children {
        assert!(
            compared.contains(child),
            "{child} (a revolute joint's child) is not on /tf"
        );
    }
    // Every link the URDF draws (a visual) has its frame, so RViz can place its mesh; only
    // the URDF's helper frames without one may be left out (the built-in model folds its
    // `*_jointbody` frames into the joints).
    for node in chain.iter() {
        let link = node.link();
        let link = link.as_ref().unwrap();
        assert!(
            link.visuals.is_empty() || compared.contains(&link.name) || link.name == root,
            "{} has a visual but no /tf frame",
            link.name
        );
    }
}

/// Drive a station with `model`, hold, and check its joint names and `/tf` against the URDF;
/// returns what arrived on `/robot_description`.
async fn check_tf_against_urdf(
    urdf: &Path,
    model: HandModel,
    hooks: StationHooks,
) -> Inbox<StringMsg> {
    let config = config();
    let revolute_children: Vec<String> = model
        .joints()
        .iter()
        .filter(|j| matches!(j.motion, JointMotion::Revolute { .. }))
        .map(|j| model.ros_link_names()[j.child.index()].clone())
        .collect();
    assert_eq!(revolute_children.len(), model.dof());
    let mut h = Harness::start_with(config.clone(), model, hooks, test_domain(), None)
        .await
        .unwrap();
    let tf = h
        .listen::<TFMessage>("/tf", QosConfig::reliable(1000))
        .unwrap();
    let tf_static = h.listen_latched::<TFMessage>("/tf_static").unwrap();
    let description = h
        .listen_latched::<StringMsg>(&config.ros_tools.robot_description_topic)
        .unwrap();
    let target = drive_then_hold(&h).await;
    tf_static
        .wait_until(Duration::from_secs(10), |m| !m.is_empty())
        .await
        .expect("no /tf_static arrived (latched)");
    let edges = tf_edges(&tf_static.all(), &tf.all());
    h.stop().await.unwrap();

    let chain = k::Chain::<f64>::from_urdf_file(urdf).unwrap();
    assert_joint_names_are_the_urdfs(&target, &chain);
    set_published_positions(&chain, &target);
    let arm_target = &config.ros_tools.arm_target_frame;
    assert_tf_is_the_urdf_kinematics(&edges, &chain, arm_target, &revolute_children);
    description
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn builtin_model_publishes_urdf_joint_names_and_its_tf_is_the_urdf_kinematics() {
    let Some(urdf) = reference_file(URDF) else {
        return;
    };
    let description =
        check_tf_against_urdf(&urdf, HandModel::orca_v1_right(), StationHooks::default()).await;
    assert!(
        description.is_empty(),
        "a station without a URDF published a robot description"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn urdf_imported_model_publishes_its_names_its_tf_and_the_robot_description() {
    let Some(urdf) = reference_file(URDF) else {
        return;
    };
    let source = HandSource::Urdf {
        urdf: urdf.clone(),
        import: workspace_root().join("launch_configs/hands/orca_v1_right_urdf.toml"),
    };
    let model = source.load().unwrap();
    let text = source.robot_description().unwrap().unwrap();
    let hooks = StationHooks {
        robot_description: Some(text.clone()),
        ..StationHooks::default()
    };
    let description = check_tf_against_urdf(&urdf, model, hooks).await;
    description
        .wait_until(Duration::from_secs(5), |m| !m.is_empty())
        .await
        .expect("no /robot_description arrived (latched)");
    let received = description.all();
    assert_eq!(received.len(), 1, "one robot description");
    assert_eq!(
        received[0].1.data, text,
        "/robot_description is the URDF's text"
    );
}

/// A pose of the robot well inside its limits, wrist straight (the wrist is no finger joint of
/// the default embodiment, so the retargeter keeps it where it is).
fn inner_pose(model: &HandModel) -> Vec<f64> {
    let mut q: Vec<f64> = model
        .limits()
        .map(|l| 0.6 * l.lower_rad + 0.4 * l.upper_rad)
        .collect();
    q[model.dof_index("wrist").unwrap()] = 0.0;
    q
}

fn point(p: &msgs::Point) -> Point3<f64> {
    Point3::new(p.x, p.y, p.z)
}

/// The joint vector (model order) of a published joint target.
fn model_q(model: &HandModel, target: &JointState) -> Vec<f64> {
    model
        .ros_dof_names()
        .iter()
        .map(|name| {
            let i = target.name.iter().position(|n| n == name).unwrap();
            target.position[i]
        })
        .collect()
}

/// The three keypoint markers, their kinds, sizes and frame.
fn assert_marker_layout(markers: &[Marker], layout: KeypointLayout) {
    let ids: Vec<(i32, i32)> = markers.iter().map(|m| (m.id, m.kind)).collect();
    assert_eq!(
        ids,
        [
            (0, Marker::SPHERE_LIST),
            (1, Marker::LINE_LIST),
            (2, Marker::SPHERE_LIST)
        ]
    );
    for m in markers {
        assert_eq!(m.header.frame_id, "world", "marker {}", m.id);
        assert_eq!(m.ns, "pomdar");
        assert_eq!(m.action, Marker::ADD);
    }
    assert_eq!(markers[0].points.len(), layout.len());
    // Wrist to each digit's base, then each digit's three bones: two points a line.
    assert_eq!(markers[1].points.len(), 5 * 2 * 4);
    assert_eq!(markers[2].points.len(), 5);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn keypoint_markers_put_the_robots_own_fingertips_on_its_fingertips() {
    let model = HandModel::orca_v1_right();
    let layout = KeypointLayout::Lab22;
    let mut config = timing_independent_config();
    // The key vectors alone (as retarget/tests/suite/round_trip.rs): pinch and separation terms
    // depart from them on purpose when tips are close.
    config.retarget.pinch.weight = 0.0;
    config.retarget.pinch.separation_weight = 0.0;
    let mut h = Harness::start_with(
        config.clone(),
        model.clone(),
        StationHooks::default(),
        test_domain(),
        None,
    )
    .await
    .unwrap();
    let markers = h
        .listen::<MarkerArray>(
            &config.ros_tools.keypoint_markers_topic,
            QosConfig::reliable(1000),
        )
        .unwrap();
    let state = model.forward_new(&inner_pose(&model)).unwrap();
    let frame = model.synthetic_keypoints(&state, layout);
    // An identical frame is a repeat (not solved again); a shifted copy is new and, the palm
    // frame being translation-invariant, asks for the same pose.
    let shifted: Vec<Point3<f64>> = frame
        .iter()
        .map(|p| p + nalgebra::Vector3::x() * 1e-3)
        .collect();
    for i in 0..60 {
        let points = if i % 2 == 0 { &frame } else { &shifted };
        h.publish(points, &Isometry3::identity()).await.unwrap();
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    // Every frame taken; the last one is always solved (frames arriving together are solved
    // once, for the newest), and after it the held command repeats unchanged.
    h.wait_until(Duration::from_secs(10), |heard| {
        heard
            .status
            .last()
            .is_some_and(|(_, s)| s["counters"]["frames_new"] == 60)
    })
    .await
    .unwrap();
    tokio::time::sleep(Duration::from_millis(500)).await;
    assert!(markers.len() >= 10, "{} marker arrays", markers.len());
    let target = h.heard.lock().unwrap().targets.last().unwrap().1.clone();
    let summary = h.stop().await.unwrap();
    assert_eq!(summary.counters.frames_new, 60, "{:?}", summary.counters);
    check_converged_markers(
        &model,
        layout,
        &markers.last().unwrap().markers,
        &target,
        &shifted,
    );
}

/// The last markers: the robot fingertips are the forward kinematics of the published
/// command; the glove points are the frame's points in its own palm frame set on the robot's
/// palm at that command (identity calibration); and having converged on the robot's own
/// pose, each glove fingertip sits on the robot's fingertip.
fn check_converged_markers(
    model: &HandModel,
    layout: KeypointLayout,
    markers: &[Marker],
    target: &JointState,
    last_frame: &[Point3<f64>],
) {
    assert_marker_layout(markers, layout);
    let state = model.forward_new(&model_q(model, target)).unwrap();
    for (i, finger) in Finger::ALL.into_iter().enumerate() {
        let fk = state.position(model.frames().tip(finger));
        let drawn = point(&markers[2].points[i]);
        assert!(
            (fk - drawn).norm() < 1e-9,
            "{finger:?}: robot tip marker is not FK"
        );
    }
    // What the station received: f32 keypoints.
    let received: Vec<Point3<f64>> = last_frame
        .iter()
        .map(|p| p.map(|c| f64::from(c as f32)))
        .collect();
    let human = PalmFrame::from_landmarks(&layout.palm_landmarks(&received)).unwrap();
    let robot = model.palm_frame(&state).unwrap();
    for (i, p) in received.iter().enumerate() {
        let placed = point(&markers[0].points[i]);
        let in_robot_palm = robot.rotation.inverse() * (placed - robot.origin);
        let error = (in_robot_palm - human.point_to_palm(p)).norm();
        assert!(
            error < 1e-9,
            "glove point {i} is {error} m off its palm position"
        );
    }
    let mut worst = 0.0_f64;
    for (i, finger) in Finger::ALL.into_iter().enumerate() {
        let glove_tip = point(&markers[0].points[layout.tip(finger)]);
        let robot_tip = point(&markers[2].points[i]);
        let gap = (glove_tip - robot_tip).norm();
        worst = worst.max(gap);
        assert!(
            gap < 3e-3,
            "{finger:?}: the glove tip is {:.2} mm from the robot's",
            gap * 1e3
        );
    }
    println!("glove tips on robot tips: worst {:.3} mm", worst * 1e3);
}

fn glove_status(array: &DiagnosticArray) -> &DiagnosticStatus {
    &array.status[0]
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn diagnostics_name_glove_hand_and_arm_and_the_glove_goes_stale_without_frames() {
    let mut config = config();
    // Frames every 20 ms are never this old, even on a loaded machine.
    config.watchdog.hold_timeout_ms = 1000;
    config.watchdog.disengage_timeout_ms = 3000;
    let mut h = Harness::start(config.clone(), test_domain()).await.unwrap();
    let diagnostics = h
        .listen::<DiagnosticArray>(
            &config.ros_tools.diagnostics_topic,
            QosConfig::reliable(100),
        )
        .unwrap();
    diagnostics
        .wait_until(Duration::from_secs(10), |m| !m.is_empty())
        .await
        .expect("no /diagnostics arrived");
    let before = diagnostics.last().unwrap();
    assert_eq!(
        glove_status(&before).level,
        DiagnosticStatus::STALE,
        "before any frame: {:?}",
        glove_status(&before)
    );

    let glove = glove();
    play(&h, &glove, 0.0, 0.3).await;
    let flowing = h.clock.now_ns();
    play(&h, &glove, 0.3, 1.2).await;
    let stopped = h.clock.now_ns();
    let while_flowing: Vec<DiagnosticArray> = diagnostics
        .all()
        .into_iter()
        .filter(|(t, _)| *t > flowing && *t <= stopped)
        .map(|(_, m)| m)
        .collect();
    assert!(
        while_flowing.len() >= 5,
        "{} diagnostics in 1.2 s at 20 Hz",
        while_flowing.len()
    );
    for array in &while_flowing {
        let names: Vec<&str> = array.status.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "pomdar_station: glove",
                "pomdar_station: hand",
                "pomdar_station: arm"
            ]
        );
        assert_eq!(
            glove_status(array).level,
            DiagnosticStatus::OK,
            "{:?}",
            glove_status(array)
        );
        let state = array.status[1].values.iter().find(|v| v.key == "state");
        assert_eq!(state.map(|v| v.value.as_str()), Some("engaged"));
    }

    // Frames stop: the glove warns (holding), then goes stale.
    for level in [DiagnosticStatus::WARN, DiagnosticStatus::STALE] {
        diagnostics
            .wait_until(Duration::from_secs(10), |m| {
                m.iter()
                    .any(|(t, a)| *t > stopped && glove_status(a).level == level)
            })
            .await
            .unwrap_or_else(|_| panic!("the glove never reached level {level} without frames"));
    }
    h.stop().await.unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn trigger_services_disengage_and_engage_and_trial_start_needs_a_console() {
    let config = config();
    let mut h = Harness::start(config.clone(), test_domain()).await.unwrap();
    let services = &config.ros_tools.services;
    let mut clients = Vec::new();
    for name in [&services.disengage, &services.engage, &services.trial_start] {
        clients.push(
            h.node
                .trigger_client(name, ServiceMapping::Enhanced)
                .unwrap(),
        );
    }
    for client in &clients {
        tokio::time::timeout(
            Duration::from_secs(15),
            client.wait_for_service(h.node.node()),
        )
        .await
        .expect("the station's service did not match in 15 s");
    }
    let call = |index: usize| {
        let client = &clients[index];
        async move {
            tokio::time::timeout(
                Duration::from_secs(10),
                client.async_call_service(TriggerRequest::default()),
            )
            .await
            .expect("no answer in 10 s")
            .map_err(|e| format!("{e:?}"))
            .unwrap()
            .0
        }
    };
    let glove = glove();
    play(&h, &glove, 0.0, 0.5).await;
    assert_eq!(status_state(&h), "engaged");

    // Disengage while the glove keeps going: the station stays disengaged.
    let asked = h.clock.now_ns();
    let (answer, ()) = tokio::join!(call(0), play(&h, &glove, 0.5, 0.6));
    assert!(answer.success, "{answer:?}");
    assert!(answer.message.contains("disengaged"), "{answer:?}");
    wait_for_state(&h, "disengaged", asked).await;
    play(&h, &glove, 1.1, 0.3).await;
    assert_eq!(status_state(&h), "disengaged");

    // Engage with fresh input: engaged, and the answer says so.
    let asked = h.clock.now_ns();
    let (answer, ()) = tokio::join!(call(1), play(&h, &glove, 1.4, 0.6));
    assert!(answer.success, "{answer:?}");
    assert!(answer.message.contains("is engaged"), "{answer:?}");
    wait_for_state(&h, "engaged", asked).await;

    // No console: a trial cannot start.
    let answer = call(2).await;
    assert!(!answer.success, "{answer:?}");
    assert!(answer.message.contains("console"), "{answer:?}");
    h.stop().await.unwrap();
}
