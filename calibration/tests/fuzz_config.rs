//! Fuzzing of the calibration settings, profile and pose-set loaders on stable Rust: the
//! shipped settings, a profile as `pomdar calibrate` writes it and the built-in poses,
//! mutated key by key (`fuzz/support/toml_mutation.rs`) and as text. No panic; errors are
//! `Err`; what loads is consistent — it validates, it survives a write and re-read unchanged,
//! a profile that fits the station's hand applies to a retargeter whose command stays finite
//! and within the joint limits, and every loaded pose is a joint vector within the limits.
//!
//! CI budget: 1,500 cases per loader; `PROPTEST_CASES=N` for longer.

#![allow(clippy::unwrap_used, clippy::expect_used)] // in tests a panic is the failure report

#[path = "../../fuzz/support/toml_mutation.rs"]
mod toml_mutation;

use calibration::{
    CalibrationProfile, CalibrationSettings, ORCA_V1_POSES_TOML, ObjectiveSummary, POSE_NAMES,
    PoseReport, PoseSet,
};
use proptest::prelude::*;
use retarget::{
    CalibrationTransform, EmbodimentCatalog, HandModel, KeypointLayout, RetargetConfig, Retargeter,
};
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
    let model = HandModel::orca_v1_right();
    CalibrationProfile {
        user: "alice".into(),
        date: "2026-11-21T10:32:05Z".into(),
        glove: "rokoko #12".into(),
        model: model.name().to_string(),
        layout: KeypointLayout::Lab22,
        source: "profiles/alice-session.mcap".into(),
        parameters: CalibrationTransform {
            scale: 1.08,
            roll_rad: 0.05,
            pitch_rad: -0.1,
            yaw_rad: 0.2,
        },
        objective: ObjectiveSummary {
            before_rad: 0.4,
            after_rad: 0.15,
            evaluations: 140,
        },
        poses: POSE_NAMES
            .iter()
            .enumerate()
            .map(|(i, name)| PoseReport {
                name: (*name).to_string(),
                joint_rms_before_rad: 0.4,
                joint_rms_after_rad: 0.1,
                pinch_gap_before_mm: (i < 4).then_some(12.0),
                pinch_gap_after_mm: (i < 4).then_some(4.0),
            })
            .collect(),
    }
    .to_toml_string()
    .unwrap()
}

proptest! {
    #![proptest_config(budget(1500))]

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
        if let Ok(settings) = CalibrationSettings::from_toml_str(&mutate(&seed, &edits)) {
            prop_assert!(settings.validate().is_ok());
            let again = CalibrationSettings::from_toml_str(&toml::to_string(&settings).unwrap());
            prop_assert_eq!(again.unwrap(), settings);
        }
    }

    #[test]
    fn mutated_profiles_load_and_apply_or_fail(edits in prop::collection::vec(edits(), 1..4)) {
        let Ok(profile) = CalibrationProfile::from_toml_str(&mutate(&profile_text(), &edits))
        else {
            return Ok(());
        };
        let again = CalibrationProfile::from_toml_str(&profile.to_toml_string().unwrap());
        prop_assert_eq!(again.unwrap(), profile.clone());
        let model = HandModel::orca_v1_right();
        if profile.check_fits(&model, KeypointLayout::Lab22).is_err() {
            return Ok(());
        }
        let mut retargeter = Retargeter::new(
            model.clone(),
            RetargetConfig::default(),
            &EmbodimentCatalog::builtin(),
        )
        .unwrap();
        // A validated profile is a valid transform.
        retargeter.set_calibration(profile.parameters).unwrap();
        let q: Vec<f64> = model.limits().map(|l| 0.5 * (l.lower_rad + l.upper_rad)).collect();
        let frame = model.synthetic_keypoints(&model.forward_new(&q).unwrap(), KeypointLayout::Lab22);
        if let Ok(solution) = retargeter.retarget(&frame, 0.04) {
            for (q, l) in solution.q.iter().zip(model.limits()) {
                prop_assert!(q.is_finite() && *q >= l.lower_rad - 1e-9 && *q <= l.upper_rad + 1e-9);
            }
        }
    }

    #[test]
    fn mutated_pose_sets_load_as_joint_vectors_within_limits_or_fail(
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        let Ok(set) = PoseSet::from_toml_str(&mutate(ORCA_V1_POSES_TOML, &edits)) else {
            return Ok(());
        };
        let model = HandModel::orca_v1_right();
        for pose in &set.poses {
            if let Ok(q) = pose.joint_vector(&model) {
                for (v, l) in q.iter().zip(model.limits()) {
                    prop_assert!(v.is_finite() && *v >= l.lower_rad && *v <= l.upper_rad, "{} = {v}", pose.name);
                }
            }
        }
    }
}
