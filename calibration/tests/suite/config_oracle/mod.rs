//! What must hold for the calibration files: whatever loads validates and survives a write and
//! re-read unchanged; a profile that fits the station's hand applies to a retargeter whose
//! command stays finite and within the joint limits; every loaded pose is a joint vector
//! within the limits.
//!
//! Shared by the stable proptest fuzzing (`tests/fuzz_config.rs`) and the cargo-fuzz target
//! (`fuzz/fuzz_targets/calibration_files.rs`).

use calibration::{CalibrationProfile, CalibrationSettings, PoseSet};
use retarget::{EmbodimentCatalog, HandModel, KeypointLayout, RetargetConfig, Retargeter};

/// `text` as each kind of calibration file; whatever loads is checked.
pub fn check_text(text: &str) {
    if let Ok(settings) = CalibrationSettings::from_toml_str(text) {
        assert!(settings.validate().is_ok());
        let again = CalibrationSettings::from_toml_str(&toml::to_string(&settings).unwrap());
        assert_eq!(again.ok().as_ref(), Some(&settings), "settings round trip");
    }
    if let Ok(profile) = CalibrationProfile::from_toml_str(text) {
        check_profile(&profile);
    }
    if let Ok(set) = PoseSet::from_toml_str(text) {
        check_poses(&set);
    }
}

fn check_profile(profile: &CalibrationProfile) {
    let again = CalibrationProfile::from_toml_str(&profile.to_toml_string().unwrap());
    assert_eq!(again.ok().as_ref(), Some(profile), "profile round trip");
    let model = HandModel::orca_v1_right();
    if profile.check_fits(&model, KeypointLayout::Lab22).is_err() {
        return;
    }
    let mut retargeter = Retargeter::new(
        model.clone(),
        RetargetConfig::default(),
        &EmbodimentCatalog::builtin(),
    )
    .unwrap();
    // A validated profile is a valid transform.
    retargeter.set_calibration(profile.parameters).unwrap();
    let q: Vec<f64> = model
        .limits()
        .map(|l| 0.5 * (l.lower_rad + l.upper_rad))
        .collect();
    let frame = model.synthetic_keypoints(&model.forward_new(&q).unwrap(), KeypointLayout::Lab22);
    if let Ok(solution) = retargeter.retarget(&frame, 0.04) {
        for (q, l) in solution.q.iter().zip(model.limits()) {
            assert!(q.is_finite() && *q >= l.lower_rad - 1e-9 && *q <= l.upper_rad + 1e-9);
        }
    }
}

fn check_poses(set: &PoseSet) {
    let model = HandModel::orca_v1_right();
    for pose in &set.poses {
        if let Ok(q) = pose.joint_vector(&model) {
            for (v, l) in q.iter().zip(model.limits()) {
                assert!(
                    v.is_finite() && *v >= l.lower_rad && *v <= l.upper_rad,
                    "{} = {v}",
                    pose.name
                );
            }
        }
    }
}
