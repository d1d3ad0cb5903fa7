//! What must hold for the station's own configuration files: whatever loads validates again
//! after a write and re-read; a station configuration that loads builds the station's core
//! and output stage, whose commands for real frames are finite and within the joint limits.
//!
//! Shared by the stable proptest fuzzing (`tests/fuzz_config.rs`) and the cargo-fuzz target
//! (`fuzz/fuzz_targets/station_files.rs`).

use retarget::HandModel;
use station::arm::ArmConfig;
use station::convert::isometry_to_pose;
use station::{ControlInput, KeypointFrame, Station, StationConfig, StationInput};
use teleop::hand_source::ImportFile;
use teleop::ingress::ingress_config::IngressConfig;

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

/// A configuration that loaded runs: the station builds (or says why not), and real frames,
/// ticks and a wrist pose give finite commands within the limits.
pub fn check_station(config: &StationConfig) {
    let mut config = config.clone();
    // Profiles are files; their loading is fuzzed in the calibration crate.
    config.calibration_profile = None;
    let model = HandModel::orca_v1_right();
    let Ok(mut station) = Station::new(&config, model.clone(), None) else {
        return;
    };
    let layout = config.retarget.layout;
    let frame = |t: f64, source_ns: i64| -> StationInput {
        let q: Vec<f64> = model
            .limits()
            .map(|l| (0.5 - 0.1 * t) * l.lower_rad + (0.5 + 0.1 * t) * l.upper_rad)
            .collect();
        let points = model.synthetic_keypoints(&model.forward_new(&q).unwrap(), layout);
        StationInput::Keypoints(KeypointFrame { points, source_ns })
    };
    const MS: i64 = 1_000_000;
    let tick = || StationInput::Control(ControlInput::Tick);
    let wrist = StationInput::Wrist(isometry_to_pose(&nalgebra::Isometry3::identity()));
    let inputs = [
        (frame(0.0, 0), 0),
        (wrist, MS),
        (StationInput::Control(ControlInput::Engage), MS),
        (frame(1.0, 20 * MS), 20 * MS),
        (tick(), 21 * MS),
        (tick(), 60 * MS),
        (tick(), 400 * MS),
        (tick(), 2000 * MS),
    ];
    for (input, now) in inputs {
        let outputs = station.step(input, now);
        if let Some(hand) = &outputs.hand {
            for (q, l) in hand.joint_state.position.iter().zip(model.limits()) {
                assert!(q.is_finite() && *q >= l.lower_rad - 1e-9 && *q <= l.upper_rad + 1e-9);
            }
            if let Some(policy) = &hand.policy {
                assert!(policy.data.iter().all(|v| v.is_finite()));
            }
        }
        if let Some(arm) = &outputs.arm {
            let p = &arm.pose.position;
            assert!([p.x, p.y, p.z].iter().all(|v| v.is_finite()));
        }
    }
}
