//! The hand check's one error type: options and tables refused, the check not finished (naming
//! the joints not confirmed), DDS, scripts and the table file.

use std::path::PathBuf;

use crate::atomic_file::AtomicWriteError;
use crate::ros::RosError;
use crate::tui::TuiError;
use crate::tui::script::{ScriptError, WordError};

/// Why a hand check did not write a verified table.
#[derive(Debug, thiserror::Error)]
pub enum HandCheckError {
    /// A motion option outside its range.
    #[error("{option} = {value} must be in {allowed}")]
    Option {
        /// The option (`--step-rad`).
        option: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range.
        allowed: String,
    },
    /// The configuration has no `[[policy_output.joints]]` table to check.
    #[error(
        "the configuration's [policy_output] has no joints table to check (launch_configs/station/eth_lab.toml and orca_core.toml have one)"
    )]
    NoTable,
    /// The table does not resolve on the hand model.
    #[error("{0}")]
    Table(#[from] station::StationError),
    /// A joint whose URDF limits and the consumer's range leave no room to move.
    #[error(
        "{joint}: its URDF limits and the consumer's range leave [{lo:.3}, {hi:.3}] rad, too little to move it"
    )]
    NoRoom {
        /// The joint.
        joint: String,
        /// Lower end, radians.
        lo: f64,
        /// Upper end, radians.
        hi: f64,
    },
    /// The check ended before every joint was confirmed.
    #[error("no table written: not confirmed: {}", joints.join(", "))]
    Unconfirmed {
        /// The joints not confirmed, in the table's order.
        joints: Vec<String>,
    },
    /// The written table does not load back as the table checked.
    #[error("{path}: the table written would not load back as checked: {reason}")]
    Roundtrip {
        /// The output file.
        path: PathBuf,
        /// What differs, or the loader's error.
        reason: String,
    },
    /// The configuration file is not TOML the table can be written into.
    #[error("{path}: {reason}")]
    ConfigText {
        /// The configuration file.
        path: PathBuf,
        /// The parser's message.
        reason: String,
    },
    /// Writing the table failed.
    #[error(transparent)]
    Write(#[from] AtomicWriteError),
    /// DDS failed.
    #[error(transparent)]
    Ros(#[from] RosError),
    /// A script or the terminal failed.
    #[error(transparent)]
    Tui(#[from] TuiError),
    /// A script line or a typed word was refused.
    #[error(transparent)]
    Word(#[from] WordError),
    /// A `wait` in the script timed out.
    #[error(transparent)]
    Script(#[from] ScriptError),
}
