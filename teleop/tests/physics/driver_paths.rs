//! The one station driver, checked across its loops: a calibration profile (scale ≠ 1, a
//! rotation) and a task's arm constraint (V1, `vertical_axis`) are honoured by the
//! re-simulation of a glove recording (`pomdar resim`), `pomdar eval`'s live path and the lock
//! step with the physics; for the same glove input each path's hand commands equal the others'
//! within 1e-9, frame by frame, and every arm target stays on the constraint's axis.

use std::path::{Path, PathBuf};

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use retarget::HandModel;
use retarget::human_hand::SimGlove;
use station::convert::{header, isometry_to_pose};
use station::{KeypointFormat, StationConfig, StationInput, StationOutputs};
use teleop::mcap_log::{TrialReader, TrialWriter, TrialWriterOptions};
use teleop::physics::lockstep::{LockstepObserver, LockstepPlay, play_lockstep};
use teleop::physics::setup::{ProjectScene, SceneSource, load_task};
use teleop::stand_ins::progress_message::ProgressMessage;
use teleop::stand_ins::sim_glove_node::SimGloveConfig;
use teleop::station_driver::constrain_for_task;

const TOLERANCE: f64 = 1e-9;
const DURATION_S: f64 = 3.0;

/// A profile with scale 1.08 and a rotation (roll, pitch, yaw all non-zero).
fn profile_toml() -> String {
    use calibration::test_support::{profile_text, scaled_and_rotated};
    profile_text("driver-paths", scaled_and_rotated()).unwrap()
}

/// A scratch directory removed on drop.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("pomdar-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

/// The station of every path: V1's arm constraint, keypoints as `PoseArray` (the log then
/// holds the glove's points in f64, as the lock step feeds them), the profile at `profile`.
fn station_config(profile: Option<&Path>) -> StationConfig {
    let catalog = scoring::TaskCatalog::builtin();
    let mut config = StationConfig::default();
    constrain_for_task(&mut config, catalog.get("V1").unwrap());
    config.input.keypoints_format = KeypointFormat::PoseArray;
    config.calibration_profile = profile.map(Path::to_path_buf);
    config
}

/// The simulated glove playing V1's script and its frame rate.
fn glove(config: &StationConfig) -> (SimGlove, f64) {
    let script = teleop::stand_ins::glove_script_file::load_glove_script(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../launch_configs/sim/tasks/V1.toml"),
    )
    .unwrap();
    let glove_config = SimGloveConfig {
        script: Some(script),
        layout: config.retarget.layout,
        ..SimGloveConfig::default()
    };
    (glove_config.glove().unwrap(), glove_config.rate_hz)
}

/// The glove's frames and wrist poses at the lock step's times, as a glove recording.
fn record_glove(path: &Path, config: &StationConfig, glove: &SimGlove, rate_hz: f64) {
    let mut writer = TrialWriter::create(path, TrialWriterOptions::default()).unwrap();
    let dt = 1.0 / rate_hz;
    for k in 0..(DURATION_S / dt).round() as u64 {
        let t = k as f64 * dt;
        let now_ns = (t * 1e9) as i64;
        if !glove.sends_at(t) {
            continue;
        }
        let (points, wrist) = glove.frame(t);
        let wrist = msgs::PoseStamped {
            header: header(now_ns, "glove"),
            pose: isometry_to_pose(&wrist),
        };
        let keypoints = msgs::PoseArray {
            header: header(now_ns, "glove"),
            poses: points.iter().map(point_pose).collect(),
        };
        let input = &config.input;
        writer
            .write(&input.wrist_topic, now_ns, now_ns, &wrist)
            .unwrap();
        writer
            .write(&input.keypoints_topic, now_ns, now_ns, &keypoints)
            .unwrap();
    }
    writer.finish().unwrap();
}

fn point_pose(p: &Point3<f64>) -> msgs::Pose {
    isometry_to_pose(&Isometry3::from_parts(
        Translation3::new(p.x, p.y, p.z),
        UnitQuaternion::identity(),
    ))
}

/// A path's hand command after each glove frame (by the frame's time) and its arm targets.
#[derive(Default)]
struct PathCommands {
    hand: Vec<(i64, Vec<f64>)>,
    arm: Vec<Point3<f64>>,
}

/// The lock step's observer: the command a keypoint frame's step gave, and every arm target.
#[derive(Default)]
struct Collect {
    after_keypoints: bool,
    commands: PathCommands,
}

impl LockstepObserver for Collect {
    fn input(&mut self, _now_ns: i64, input: &StationInput) {
        self.after_keypoints = matches!(input, StationInput::Keypoints(_));
    }

    fn outputs(&mut self, now_ns: i64, outputs: &StationOutputs) {
        if let (true, Some(hand)) = (self.after_keypoints, &outputs.hand) {
            let q = hand.joint_state.position.clone();
            self.commands.hand.push((now_ns, q));
        }
        if let Some(arm) = &outputs.arm {
            let p = &arm.pose.position;
            self.commands.arm.push(Point3::new(p.x, p.y, p.z));
        }
    }

    fn progress(&mut self, _event: &ProgressMessage) {}
}

fn lockstep_commands(config: &StationConfig, glove: &SimGlove, rate_hz: f64) -> PathCommands {
    let model = HandModel::orca_v1_right();
    let task = scoring::TaskCatalog::builtin().get("V1").unwrap().clone();
    let arm_start = config.arm.start_pose_isometry().unwrap();
    let scene = SceneSource::Project(ProjectScene::for_station(config));
    let loaded = load_task(&task, &model, scene, arm_start).unwrap();
    let mut collect = Collect::default();
    let play = LockstepPlay {
        config,
        model: &model,
        glove,
        rate_hz,
        duration_s: DURATION_S,
        until: None,
        observer: Some(&mut collect),
    };
    play_lockstep(play, loaded).unwrap();
    collect.commands
}

/// `pomdar resim` of the glove recording: the last hand command written at each frame's time.
fn resim_commands(log: &Path, out: &Path, config: &StationConfig) -> PathCommands {
    let reader = TrialReader::open(log).unwrap();
    let mut writer = TrialWriter::create(out, TrialWriterOptions::default()).unwrap();
    let stats =
        teleop::resim::resim(&reader, config, HandModel::orca_v1_right(), &mut writer).unwrap();
    writer.finish().unwrap();
    assert!(stats.profile.is_some() == config.calibration_profile.is_some());
    let frame_times: Vec<i64> = reader
        .messages_on(&config.input.keypoints_topic)
        .map(|m| m.log_time_ns)
        .collect();
    let written = TrialReader::open(out).unwrap();
    let mut commands = PathCommands::default();
    for message in written.messages_on(&config.output.joint_targets_topic) {
        let state: msgs::JointState = message.decode().unwrap();
        if frame_times.contains(&message.log_time_ns) {
            // A tick at a frame's time goes before the frame: the frame's command is the last.
            commands.hand.retain(|(t, _)| *t != message.log_time_ns);
            commands.hand.push((message.log_time_ns, state.position));
        }
    }
    for message in written.messages_on(&config.output.arm_target_topic) {
        let p = message.decode::<msgs::PoseStamped>().unwrap().pose.position;
        commands.arm.push(Point3::new(p.x, p.y, p.z));
    }
    commands
}

/// `pomdar eval`'s live path: the command in force after each frame.
fn eval_commands(log: &Path, config: &StationConfig) -> Vec<(i64, Vec<f64>)> {
    let reader = TrialReader::open(log).unwrap();
    teleop::eval::live_path::commands_in_force(&reader, config, HandModel::orca_v1_right())
        .unwrap()
        .into_iter()
        .filter_map(|(t, q)| q.map(|q| (t, q)))
        .collect()
}

fn assert_same_commands(name: &str, a: &[(i64, Vec<f64>)], b: &[(i64, Vec<f64>)]) {
    assert_eq!(a.len(), b.len(), "{name}: a different number of commands");
    assert!(a.len() > 50, "{name}: only {} commands", a.len());
    for ((ta, qa), (tb, qb)) in a.iter().zip(b) {
        assert_eq!(ta, tb, "{name}: commands at different times");
        let worst = qa
            .iter()
            .zip(qb)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        assert!(
            worst <= TOLERANCE,
            "{name}: at {ta} ns the commands differ by {worst}"
        );
    }
}

/// Every arm target on the vertical line through the first one.
fn assert_on_vertical_axis(name: &str, config: &StationConfig, targets: &[Point3<f64>]) {
    let axis = Vector3::from(config.arm.vertical_axis).normalize();
    let Some(first) = targets.first() else {
        return;
    };
    for target in targets {
        let off_axis = (target - first).cross(&axis).norm();
        assert!(
            off_axis <= TOLERANCE,
            "{name}: an arm target {off_axis} m off the axis"
        );
    }
}

#[test]
fn a_profile_and_a_task_constraint_give_the_same_commands_on_every_path() {
    let scratch = Scratch::new("driver-paths");
    let profile = scratch.0.join("profile.toml");
    std::fs::write(&profile, profile_toml()).unwrap();
    let config = station_config(Some(&profile));
    let (glove, rate_hz) = glove(&config);
    let log = scratch.0.join("glove.mcap");
    record_glove(&log, &config, &glove, rate_hz);

    let resim = resim_commands(&log, &scratch.0.join("resim.mcap"), &config);
    let eval = eval_commands(&log, &config);
    let lockstep = lockstep_commands(&config, &glove, rate_hz);
    assert_same_commands("resim vs eval live path", &resim.hand, &eval);
    assert_same_commands("resim vs lock step", &resim.hand, &lockstep.hand);

    // The profile is honoured: without it the same glove gives other commands.
    let uncalibrated = resim_commands(&log, &scratch.0.join("plain.mcap"), &station_config(None));
    let moved = resim
        .hand
        .iter()
        .zip(&uncalibrated.hand)
        .any(|((_, a), (_, b))| a.iter().zip(b).any(|(x, y)| (x - y).abs() > 1e-3));
    assert!(moved, "the calibration profile changed no command");

    assert!(!lockstep.arm.is_empty(), "the lock step sent no arm target");
    assert_on_vertical_axis("lock step", &config, &lockstep.arm);
    assert_on_vertical_axis("resim", &config, &resim.arm);
}
