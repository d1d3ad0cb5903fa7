//! What must hold for the retargeting files the station loads: a configuration that loads
//! builds a retargeter whose command for a real frame is finite and within the joint limits;
//! a model that loads (TOML or URDF) has finite forward kinematics across its range; an
//! embodiment catalog that loads retargets to finite commands.
//!
//! Shared by the stable proptest fuzzing (`tests/fuzz_config.rs`) and the cargo-fuzz targets
//! (`fuzz/fuzz_targets/retarget_files.rs`, `urdf_import.rs`).

use nalgebra::Point3;
use retarget::{
    EmbodimentCatalog, HandModel, KeypointLayout, RetargetConfig, Retargeter, UrdfImport,
};

/// `text` as each kind of retargeting file; whatever loads is checked.
pub fn check_text(text: &str) {
    if let Ok(config) = RetargetConfig::from_toml_str(text) {
        assert!(config.validate().is_ok());
        check_config(&config);
    }
    if let Ok(model) = HandModel::from_toml_str(text) {
        check_model(&model);
    }
    if let Ok(catalog) = EmbodimentCatalog::from_toml_str(text) {
        check_embodiments(&catalog);
    }
}

/// `urdf` imported with `import`; a model that loads is checked.
pub fn check_urdf(urdf: &str, import: &UrdfImport) {
    if let Ok(model) = HandModel::from_urdf_str(urdf, import) {
        check_model(&model);
    }
}

/// The built-in hand's keypoints at a mid-range pose, in `layout`.
pub fn frame(layout: KeypointLayout) -> Vec<Point3<f64>> {
    let model = HandModel::orca_v1_right();
    let q: Vec<f64> = model
        .limits()
        .map(|l| 0.4 * l.lower_rad + 0.6 * l.upper_rad)
        .collect();
    model.synthetic_keypoints(&model.forward_new(&q).unwrap(), layout)
}

/// A configuration that loaded must retarget a real frame to a finite command within limits.
pub fn check_config(config: &RetargetConfig) {
    let model = HandModel::orca_v1_right();
    let Ok(mut retargeter) =
        Retargeter::new(model.clone(), config.clone(), &EmbodimentCatalog::builtin())
    else {
        return;
    };
    let points = frame(config.layout);
    for dt_s in [0.04, 1e-4] {
        let Ok(solution) = retargeter.retarget(&points, dt_s) else {
            continue;
        };
        for (q, limits) in solution.q.iter().zip(model.limits()) {
            assert!(q.is_finite(), "non-finite command {q}");
            assert!(
                *q >= limits.lower_rad - 1e-9 && *q <= limits.upper_rad + 1e-9,
                "command {q} outside [{}, {}]",
                limits.lower_rad,
                limits.upper_rad
            );
        }
    }
}

/// A model that loaded has finite forward kinematics across its range.
pub fn check_model(model: &HandModel) {
    for t in [0.0, 0.5, 1.0] {
        let q: Vec<f64> = model
            .limits()
            .map(|l| (1.0 - t) * l.lower_rad + t * l.upper_rad)
            .collect();
        if q.iter().any(|v| !v.is_finite()) {
            continue;
        }
        let Ok(state) = model.forward_new(&q) else {
            continue;
        };
        for layout in [KeypointLayout::Lab22, KeypointLayout::MediaPipe21] {
            for p in model.synthetic_keypoints(&state, layout) {
                assert!(p.coords.iter().all(|c| c.is_finite()), "FK gave {p}");
            }
        }
    }
}

/// Every built-in embodiment name retargets to finite commands with `catalog`, or is refused.
pub fn check_embodiments(catalog: &EmbodimentCatalog) {
    for name in ["orca_full", "orca_5", "orca_3", "orca_2"] {
        let config = RetargetConfig {
            embodiment: name.to_string(),
            ..RetargetConfig::default()
        };
        if let Ok(mut r) = Retargeter::new(HandModel::orca_v1_right(), config, catalog)
            && let Ok(s) = r.retarget(&frame(KeypointLayout::Lab22), 0.04)
        {
            assert!(s.q.iter().all(|q| q.is_finite()));
        }
    }
}
