//! What `pomdar calibrate` is asked to do, as plain values: the user, the way it runs (live,
//! `--from` a recorded session, `--simulate`d), the simulated user, the console, the files and
//! the network. The command fills it from its flags; [`super::calibrate_run`] runs it.

use std::path::PathBuf;

use calibration::CalibrationModel;
use retarget::human_hand::HandVariation;

/// One calibration, as asked for (see `pomdar calibrate --help` for each value's flag).
#[derive(Debug, Clone)]
pub struct CalibrateRequest {
    /// `--user`.
    pub user: String,
    /// `--from`: a recorded session to fit again.
    pub from: Option<PathBuf>,
    /// `--simulate`.
    pub simulate: bool,
    /// `--hand-scale`.
    pub hand_scale: f64,
    /// `--glove-rpy`, degrees.
    pub glove_rpy: Option<[f64; 3]>,
    /// `--seed`.
    pub seed: u64,
    /// `--simulate-bad-pose`.
    pub simulate_bad_pose: Option<String>,
    /// `--simulate-wrong-pose`.
    pub simulate_wrong_pose: Option<String>,
    /// `--simulate-hand`.
    pub simulate_hand: Option<HandVariation>,
    /// `--script`.
    pub script: Option<PathBuf>,
    /// `--plain`.
    pub plain: bool,
    /// `--glove`.
    pub glove: Option<String>,
    /// `--out`.
    pub out: Option<PathBuf>,
    /// `--session-out`.
    pub session_out: Option<PathBuf>,
    /// `--config`.
    pub config: Option<PathBuf>,
    /// `--settings`.
    pub settings: Option<PathBuf>,
    /// `--model`.
    pub model: Option<CalibrationModel>,
    /// `--domain-id`.
    pub domain_id: Option<u16>,
    /// `--glove-wait-s`.
    pub glove_wait_s: f64,
}
