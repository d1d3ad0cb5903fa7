//! Fuzzing of the station's own configuration loaders on stable Rust: the station presets
//! (`launch_configs/station/*.toml`), the arm settings, the URDF import file and the Rokoko
//! ingress settings, mutated key by key (`fuzz/support/toml_mutation.rs`) and as text. No
//! panic; errors are `Err`; what loads works — it validates again after a write and re-read,
//! and a station configuration that loads builds the station's core and output stage, whose
//! commands for real frames are finite and within the joint limits.
//!
//! CI budget: 1,000 station configurations, 1,500 of each other file; `PROPTEST_CASES=N` for
//! longer.

#![allow(clippy::unwrap_used, clippy::expect_used)] // in tests a panic is the failure report

#[path = "../../fuzz/support/toml_mutation.rs"]
mod toml_mutation;

use nalgebra::Point3;
use proptest::prelude::*;
use retarget::HandModel;
use teleop::arm::ArmConfig;
use teleop::hand_source::ImportFile;
use teleop::ingress::ingress_config::IngressConfig;
use teleop::station::output_stage::OutputStage;
use teleop::station::ros_station::station_core;
use teleop::station::station_config::StationConfig;
use toml_mutation::{budget, edits, mutate};

fn launch_config(path: &str) -> String {
    std::fs::read_to_string(format!(
        "{}/../launch_configs/{path}",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
}

const PRESETS: [&str; 4] = [
    "station/eth_lab.toml",
    "station/stamped_pose_array.toml",
    "station/multipanda.toml",
    "station/crisp_controllers.toml",
];

/// A configuration that loaded runs: the core and the output stage build (or say why not),
/// and two real frames give finite commands within the limits.
fn check_station(config: &StationConfig) {
    let mut config = config.clone();
    // Profiles are files; their loading is fuzzed in the calibration crate.
    config.calibration_profile = None;
    let model = HandModel::orca_v1_right();
    let (Ok(mut core), Ok(mut stage)) = (
        station_core(&config, model.clone()),
        OutputStage::new(&config, &model),
    ) else {
        return;
    };
    let layout = config.retarget.layout;
    let frame = |t: f64| -> Vec<Point3<f64>> {
        let q: Vec<f64> = model
            .limits()
            .map(|l| (0.5 - 0.1 * t) * l.lower_rad + (0.5 + 0.1 * t) * l.upper_rad)
            .collect();
        model.synthetic_keypoints(&model.forward_new(&q).unwrap(), layout)
    };
    const MS: i64 = 1_000_000;
    core.on_stamped_keypoints(&frame(0.0), Some(0), 0);
    core.engage(MS);
    core.on_stamped_keypoints(&frame(1.0), Some(20 * MS), 20 * MS);
    for now in [21 * MS, 60 * MS, 400 * MS, 2000 * MS] {
        let tick = core.tick(now);
        if let Some(hand) = &tick.hand {
            for (q, l) in hand.q.iter().zip(model.limits()) {
                assert!(q.is_finite() && *q >= l.lower_rad - 1e-9 && *q <= l.upper_rad + 1e-9);
            }
        }
        let outputs = stage.outputs(&tick, now, 20 * MS, None, None, false);
        if let Some(joints) = outputs.joint_state {
            assert!(joints.position.iter().all(|q| q.is_finite()));
        }
        if let Some(policy) = outputs.policy {
            assert!(policy.data.iter().all(|v| v.is_finite()));
        }
    }
}

proptest! {
    #![proptest_config(budget(1000))]

    #[test]
    fn mutated_station_configs_load_and_run_or_fail(
        preset in 0usize..5,
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        let seed = match PRESETS.get(preset) {
            Some(path) => launch_config(path),
            None => toml::to_string(&StationConfig::default()).unwrap(),
        };
        if let Ok(config) = StationConfig::from_toml_str(&mutate(&seed, &edits)) {
            prop_assert!(config.validate().is_ok());
            let again = StationConfig::from_toml_str(&toml::to_string(&config).unwrap());
            prop_assert_eq!(again.unwrap(), config.clone());
            check_station(&config);
        }
    }
}

proptest! {
    #![proptest_config(budget(1500))]

    #[test]
    fn mutated_arm_configs_load_and_validate_or_fail(
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        let seed = toml::to_string(&ArmConfig::default()).unwrap();
        if let Ok(config) = ArmConfig::from_toml_str(&mutate(&seed, &edits)) {
            prop_assert!(config.validate().is_ok());
        }
    }

    #[test]
    fn mutated_import_files_load_or_fail(edits in prop::collection::vec(edits(), 1..4)) {
        let seed = launch_config("hands/orca_v1_right_urdf.toml");
        let _ = ImportFile::from_toml_str(&mutate(&seed, &edits));
    }

    #[test]
    fn mutated_ingress_configs_load_and_validate_or_fail(
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        let seed = launch_config("ingress/rokoko.toml");
        if let Ok(config) = IngressConfig::from_toml_str(&mutate(&seed, &edits)) {
            prop_assert!(config.validate().is_ok());
            let again = IngressConfig::from_toml_str(&toml::to_string(&config).unwrap());
            prop_assert_eq!(again.unwrap(), config);
        }
    }
}
