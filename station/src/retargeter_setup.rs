//! The station's retargeter built from a retargeting configuration, a hand model and a
//! user's calibration: the one set-up the station and `pomdar eval` (the retargeter alone)
//! share, so both retarget with the same solver, embodiment and transform.

use retarget::{CalibrationTransform, EmbodimentCatalog, HandModel, RetargetConfig, Retargeter};

/// Which part of the set-up the retargeter refused.
#[derive(Debug, thiserror::Error)]
pub enum RetargeterSetupError {
    /// The model or the configuration (the embodiment, the solver).
    #[error("retargeter: {0}")]
    Model(#[source] retarget::Error),
    /// The calibration's transform.
    #[error("calibration profile: {0}")]
    Calibration(#[source] retarget::Error),
}

impl RetargeterSetupError {
    /// The retargeter's own error.
    pub fn into_cause(self) -> retarget::Error {
        match self {
            RetargeterSetupError::Model(e) | RetargeterSetupError::Calibration(e) => e,
        }
    }
}

/// The retargeter for `model` and `config`, with `calibration` when given (else the
/// identity), the embodiment from the built-in catalog.
pub fn build_retargeter(
    model: HandModel,
    config: RetargetConfig,
    calibration: Option<CalibrationTransform>,
) -> Result<Retargeter, RetargeterSetupError> {
    let mut retargeter = Retargeter::new(model, config, &EmbodimentCatalog::builtin())
        .map_err(RetargeterSetupError::Model)?;
    if let Some(transform) = calibration {
        retargeter
            .set_calibration(transform)
            .map_err(RetargeterSetupError::Calibration)?;
    }
    Ok(retargeter)
}
