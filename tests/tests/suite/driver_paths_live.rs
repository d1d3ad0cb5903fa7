//! The live station node on loopback DDS honours a calibration profile (scale 1.08, a rotation)
//! and a task's arm constraint (V1, `vertical_axis`) as the re-simulation and `pomdar eval`'s
//! live path do: the simulated glove plays V1's script into the node, and the joint targets
//! it sends equal, within 1e-9, the re-simulation of its own recording and the eval live
//! path's commands on it; its arm targets stay on the vertical axis. (The lock step's side,
//! re-simulation against the physics' loop, is `teleop/tests/physics/driver_paths.rs`.)

use std::path::Path;
use std::time::Duration;

use msgs::JointState;
use pomdar_tests::scratch_dir;
use pomdar_tests::station_harness::{
    Harness, check_arm_targets, test_domain, timing_independent_config,
};
use retarget::HandModel;
use station::StationConfig;
use teleop::mcap_log::{TrialReader, TrialWriter, TrialWriterOptions};
use teleop::stand_ins::sim_glove_node::SimGloveConfig;
use teleop::station_node::recorder::RecordingOptions;

const TOLERANCE: f64 = 1e-9;
const FRAMES: u32 = 120;

/// A profile with scale 1.08 and a rotation (roll, pitch, yaw all non-zero).
fn profile_toml() -> String {
    use calibration::test_support::{profile_text, scaled_and_rotated};
    profile_text("driver-paths", scaled_and_rotated()).unwrap()
}

fn config(profile: Option<&Path>) -> StationConfig {
    let mut config = timing_independent_config();
    let catalog = scoring::TaskCatalog::builtin();
    teleop::station_driver::constrain_for_task(&mut config, catalog.get("V1").unwrap());
    config.calibration_profile = profile.map(Path::to_path_buf);
    config
}

fn resimulated(log: &TrialReader, config: &StationConfig, out: &Path) -> Vec<JointState> {
    let mut writer = TrialWriter::create(out, TrialWriterOptions::default()).unwrap();
    teleop::resim::resim(log, config, HandModel::orca_v1_right(), &mut writer).unwrap();
    writer.finish().unwrap();
    TrialReader::open(out)
        .unwrap()
        .decode_topic::<JointState>(&config.output.joint_targets_topic)
        .unwrap()
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_live_node_honours_a_profile_and_a_task_constraint_as_resim_and_eval_do() {
    let dir = scratch_dir("driver-paths-live");
    let profile = dir.join("profile.toml");
    std::fs::write(&profile, profile_toml()).unwrap();
    let config = config(Some(&profile));
    let script = teleop::stand_ins::glove_script_file::load_glove_script(
        &pomdar_tests::workspace_root().join("launch_configs/sim/tasks/V1.toml"),
    )
    .unwrap();
    let glove_config = SimGloveConfig {
        script: Some(script),
        layout: config.retarget.layout,
        ..SimGloveConfig::default()
    };
    let glove = glove_config.glove().unwrap();

    let live_log = dir.join("live.mcap");
    let recording = RecordingOptions {
        path: live_log.clone(),
        metadata: [("task".to_string(), "V1".to_string())].into(),
    };
    let h = Harness::start_recording(config.clone(), test_domain(), Some(recording))
        .await
        .unwrap();
    let period = 1.0 / glove_config.rate_hz;
    for k in 0..FRAMES {
        let (points, wrist) = glove.frame(f64::from(k) * period);
        h.publish(&points, &wrist).await.unwrap();
        tokio::time::sleep(Duration::from_secs_f64(period)).await;
    }
    let _ = h
        .wait_until(Duration::from_secs(5), |heard| {
            heard.targets.len() >= FRAMES as usize
        })
        .await;
    let live_targets = h.target_positions();
    let live_arm: Vec<_> = h
        .heard
        .lock()
        .unwrap()
        .arm
        .iter()
        .filter_map(|(_, m)| station::convert::pose_to_isometry(&m.pose))
        .collect();
    h.stop().await.unwrap();

    let live = TrialReader::open(&live_log).unwrap();
    let resim = resimulated(&live, &config, &dir.join("resim.mcap"));
    assert!(
        live_targets.len() > 50,
        "{} joint targets",
        live_targets.len()
    );
    assert_eq!(live_targets.len(), resim.len(), "joint targets");
    for (i, (l, r)) in live_targets.iter().zip(&resim).enumerate() {
        let d = max_difference(l, &r.position);
        assert!(
            d <= TOLERANCE,
            "joint target {i}: live and resim differ by {d}"
        );
    }

    // The eval live path's command after each frame is the one the node sent for it (held
    // repeats between frames left out on both sides).
    let eval =
        teleop::eval::live_path::commands_in_force(&live, &config, HandModel::orca_v1_right())
            .unwrap();
    let mut from_eval: Vec<Vec<f64>> = eval.into_iter().filter_map(|(_, q)| q).collect();
    from_eval.dedup();
    let mut sent = live_targets.clone();
    sent.dedup();
    assert_eq!(from_eval.len(), sent.len(), "distinct commands");
    for (i, (e, l)) in from_eval.iter().zip(&sent).enumerate() {
        let d = max_difference(e, l);
        assert!(
            d <= TOLERANCE,
            "command {i}: eval and the node differ by {d}"
        );
    }

    // The profile is honoured: without it the same frames give other commands.
    let plain = resimulated(&live, &self::config(None), &dir.join("plain.mcap"));
    let moved = plain
        .iter()
        .zip(&resim)
        .any(|(a, b)| max_difference(&a.position, &b.position) > 1e-3);
    assert!(moved, "the calibration profile changed no command");

    assert!(!live_arm.is_empty(), "the node sent no arm target");
    check_arm_targets(&live_arm, &config.arm, Some(config.arm.vertical_axis));
    std::fs::remove_dir_all(&dir).ok();
}
