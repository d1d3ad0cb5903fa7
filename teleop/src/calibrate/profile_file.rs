//! Calibration profiles on disk: loading one for the station (errors name the file and the
//! key), the one-line description the station prints, and writing a new one atomically
//! (`FILE.part`, fsync, rename), so a profile is either the old one or the complete new one.

pub use crate::atomic_file::write_atomically;
pub use crate::station_setup::{describe, load_profile};

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use std::path::Path;

    use retarget::{HandModel, KeypointLayout};

    use super::*;

    #[test]
    fn a_missing_profile_is_named() {
        let err = load_profile(
            Path::new("/nonexistent/bob.toml"),
            &HandModel::orca_v1_right(),
            KeypointLayout::Lab22,
        )
        .unwrap_err();
        assert!(
            format!("{err:#}").contains("/nonexistent/bob.toml"),
            "{err:#}"
        );
    }
}
