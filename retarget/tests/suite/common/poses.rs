//! Seeded random robot poses and a default ORCA retargeter, shared by tests and benchmarks.

use rand::{Rng, rngs::StdRng};
use retarget::{EmbodimentCatalog, HandModel, RetargetConfig, Retargeter};

/// A joint vector drawn uniformly within every joint's limits.
pub fn random_pose(model: &HandModel, rng: &mut StdRng) -> Vec<f64> {
    model
        .limits()
        .map(|l| rng.random_range(l.lower_rad..=l.upper_rad))
        .collect()
}

/// The built-in ORCA model and a retargeter for it with `config` and the built-in catalog.
pub fn orca_retargeter(config: RetargetConfig) -> (HandModel, Retargeter) {
    let model = HandModel::orca_v1_right();
    let retargeter = Retargeter::new(model.clone(), config, &EmbodimentCatalog::builtin())
        .unwrap_or_else(|e| panic!("retargeter: {e}"));
    (model, retargeter)
}
