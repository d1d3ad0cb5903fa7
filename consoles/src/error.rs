//! The crate's one error type: what the pure session parts refuse (a hand check's options,
//! its table, a joint with no room to move, a check not finished).

/// What a session's pure part refuses.
#[derive(Debug, thiserror::Error)]
pub enum ConsolesError {
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
}
