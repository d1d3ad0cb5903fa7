//! What can stop `pomdar calibrate` besides the session and the fit themselves: its files,
//! its values and the async runtime.

use std::path::PathBuf;

use super::CalibrateError;

/// `pomdar calibrate` failed or was interrupted.
#[derive(Debug, thiserror::Error)]
pub enum CalibrateRunError {
    /// The session, the fit or the console.
    #[error(transparent)]
    Calibrate(#[from] CalibrateError),
    /// The station configuration.
    #[error(transparent)]
    Setup(#[from] crate::station_driver::setup::SetupError),
    /// `--user` is empty.
    #[error("--user must name the user")]
    NoUser,
    /// `--glove-wait-s` out of range.
    #[error("--glove-wait-s {seconds} must be in (0, 600] seconds")]
    GloveWait {
        /// The value given.
        seconds: f64,
    },
    /// A file cannot be read.
    #[error("cannot read {what} {path}")]
    Read {
        /// What the file is.
        what: &'static str,
        /// The file.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The calibration settings are not valid.
    #[error("calibration settings {path}")]
    Settings {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        #[source]
        source: calibration::Error,
    },
    /// The session log's directory cannot be created.
    #[error("cannot create {dir}")]
    CreateDir {
        /// The directory.
        dir: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The async runtime cannot start.
    #[error("cannot start the async runtime")]
    Runtime(#[source] std::io::Error),
    /// The simulated glove's task failed.
    #[error("simulated glove task")]
    GloveTask(#[source] tokio::task::JoinError),
}

impl CalibrateRunError {
    /// Whether this is (or is caused by) an interrupted session or fit.
    pub fn is_interrupted(&self) -> bool {
        let Self::Calibrate(inner) = self else {
            return false;
        };
        std::iter::successors(Some(inner as &(dyn std::error::Error + 'static)), |e| {
            e.source()
        })
        .any(|cause| {
            cause
                .downcast_ref::<CalibrateError>()
                .is_some_and(CalibrateError::is_interrupted)
        })
    }
}
