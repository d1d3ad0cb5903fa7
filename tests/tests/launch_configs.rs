//! Every file in `launch_configs/` parses and validates.

#![allow(clippy::unwrap_used, clippy::expect_used)] // in tests a panic is the failure report

use pomdar_tests::{files_with_extension, workspace_root};
use teleop::launch_config::check_file;

#[test]
fn every_launch_config_is_valid() {
    let all = files_with_extension(&workspace_root().join("launch_configs"), "toml").unwrap();
    assert!(!all.is_empty(), "no launch configs found");
    for path in &all {
        if let Err(e) = check_file(path) {
            panic!("{e:#}");
        }
    }
    println!("checked {} launch configs", all.len());
}

#[test]
fn a_broken_launch_config_is_reported_with_file_and_key() {
    let dir = std::env::temp_dir().join(format!("pomdar-launch-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("hands")).unwrap();
    let path = dir.join("hands/broken.toml");
    std::fs::write(&path, "strip_prefix = \"right_\"\nframe = {}\n").unwrap();
    let err = format!("{:#}", check_file(&path).unwrap_err());
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        err.contains("broken.toml") && err.contains("frame"),
        "{err}"
    );
}

#[test]
fn the_shipped_retarget_config_spells_out_the_defaults() {
    let path = workspace_root().join("launch_configs/retarget/orca_full_lab22.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let config = retarget::RetargetConfig::from_toml_str(&text).unwrap();
    assert_eq!(config, retarget::RetargetConfig::default());
}

#[test]
fn the_shipped_calibration_settings_spell_out_the_defaults() {
    let path = workspace_root().join("launch_configs/calibration/default_settings.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let settings = calibration::CalibrationSettings::from_toml_str(&text).unwrap();
    assert_eq!(settings, calibration::CalibrationSettings::default());
}
