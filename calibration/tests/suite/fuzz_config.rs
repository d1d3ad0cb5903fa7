//! Fuzzing of the calibration settings, profile and pose-set loaders on stable Rust: the
//! shipped settings, a profile as `pomdar calibrate` writes it and the built-in poses,
//! mutated key by key (`fuzz/support/toml_mutation.rs`) and as text. No panic; errors are
//! `Err`; what loads is consistent — it validates, it survives a write and re-read unchanged,
//! a profile that fits the station's hand applies to a retargeter whose command stays finite
//! and within the joint limits, and every loaded pose is a joint vector within the limits.
//!
//! CI budget: 1,500 cases per loader; `PROPTEST_CASES=N` for longer.

use crate::config_oracle;
use crate::toml_mutation;

use calibration::{CalibrationSettings, ORCA_V1_POSES_TOML};
use proptest::prelude::*;
use retarget::CalibrationTransform;
use toml_mutation::{budget, edits, mutate};

fn shipped_settings() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../launch_configs/calibration/default_settings.toml"
    ))
    .unwrap()
}

/// A profile as `pomdar calibrate` writes it.
fn profile_text() -> String {
    let transform = CalibrationTransform {
        scale: 1.08,
        roll_rad: 0.05,
        pitch_rad: -0.1,
        yaw_rad: 0.2,
        ..CalibrationTransform::IDENTITY
    };
    calibration::test_support::profile_text("alice", transform).unwrap()
}

proptest! {
    #![proptest_config(budget(1500))]

    // Each mutated file is tried as every kind of calibration file.

    #[test]
    fn mutated_settings_load_consistently_or_fail(
        base in any::<bool>(),
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        let seed = if base {
            shipped_settings()
        } else {
            toml::to_string(&CalibrationSettings::default()).unwrap()
        };
        config_oracle::check_text(&mutate(&seed, &edits));
    }

    #[test]
    fn mutated_profiles_load_and_apply_or_fail(edits in prop::collection::vec(edits(), 1..4)) {
        config_oracle::check_text(&mutate(&profile_text(), &edits));
    }

    #[test]
    fn mutated_pose_sets_load_as_joint_vectors_within_limits_or_fail(
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        config_oracle::check_text(&mutate(ORCA_V1_POSES_TOML, &edits));
    }
}
