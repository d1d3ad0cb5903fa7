//! What must hold for the station's own configuration files: whatever loads validates again
//! after a write and re-read; a station configuration that loads builds the station's core
//! and output stage, whose commands for real frames are finite and within the joint limits.
//!
//! Shared by the stable proptest fuzzing (`tests/fuzz_config.rs`) and the cargo-fuzz target
//! (`fuzz/fuzz_targets/station_files.rs`).

use nalgebra::Point3;
use retarget::HandModel;
use teleop::arm::ArmConfig;
use teleop::hand_source::ImportFile;
use teleop::ingress::ingress_config::IngressConfig;
use teleop::station::output_stage::OutputStage;
use teleop::station::ros_station::station_core;
use teleop::station::station_config::StationConfig;

/// `text` as each kind of station file; whatever loads is checked.
pub fn check_text(text: &str) {
    if let Ok(config) = StationConfig::from_toml_str(text) {
        assert!(config.validate().is_ok());
        let again = StationConfig::from_toml_str(&toml::to_string(&config).unwrap_or_default());
        assert_eq!(
            again.ok().as_ref(),
            Some(&config),
            "station config round trip"
        );
        check_station(&config);
    }
    if let Ok(config) = ArmConfig::from_toml_str(text) {
        assert!(config.validate().is_ok());
    }
    let _ = ImportFile::from_toml_str(text);
    if let Ok(config) = IngressConfig::from_toml_str(text) {
        assert!(config.validate().is_ok());
        let again = IngressConfig::from_toml_str(&toml::to_string(&config).unwrap_or_default());
        assert_eq!(
            again.ok().as_ref(),
            Some(&config),
            "ingress config round trip"
        );
    }
}

/// A configuration that loaded runs: the core and the output stage build (or say why not),
/// and two real frames give finite commands within the limits.
pub fn check_station(config: &StationConfig) {
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
