//! Fuzzing of the station's own configuration loaders on stable Rust: the station presets
//! (`launch_configs/station/*.toml`), the arm settings, the URDF import file and the Rokoko
//! ingress settings, mutated key by key (`fuzz/support/toml_mutation.rs`) and as text. No
//! panic; errors are `Err`; what loads works — it validates again after a write and re-read,
//! and a station configuration that loads builds the station's core and output stage, whose
//! commands for real frames are finite and within the joint limits.
//!
//! CI budget: 1,000 station configurations, 1,500 of each other file; `PROPTEST_CASES=N` for
//! longer.

use crate::config_oracle;
use crate::toml_mutation;

use proptest::prelude::*;
use station::StationConfig;
use station::arm::ArmConfig;
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

proptest! {
    #![proptest_config(budget(1000))]

    // Each mutated file is tried as every kind of station file.

    #[test]
    fn mutated_station_configs_load_and_run_or_fail(
        preset in 0usize..5,
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        let seed = match PRESETS.get(preset) {
            Some(path) => launch_config(path),
            None => toml::to_string(&StationConfig::default()).unwrap(),
        };
        config_oracle::check_text(&mutate(&seed, &edits));
    }
}

proptest! {
    #![proptest_config(budget(1500))]

    #[test]
    fn mutated_arm_configs_load_and_validate_or_fail(
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        let seed = toml::to_string(&ArmConfig::default()).unwrap();
        config_oracle::check_text(&mutate(&seed, &edits));
    }

    #[test]
    fn mutated_import_files_load_or_fail(edits in prop::collection::vec(edits(), 1..4)) {
        config_oracle::check_text(&mutate(&launch_config("hands/orca_v1_right_urdf.toml"), &edits));
    }

    #[test]
    fn mutated_ingress_configs_load_and_validate_or_fail(
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        config_oracle::check_text(&mutate(&launch_config("ingress/rokoko.toml"), &edits));
    }
}
