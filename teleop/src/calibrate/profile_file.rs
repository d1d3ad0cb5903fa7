//! Calibration profiles on disk: loading one for the station (errors name the file and the
//! key), the one-line description the station prints, and writing a new one atomically
//! (`FILE.part`, fsync, rename), so a profile is either the old one or the complete new one.

use std::path::Path;

use anyhow::Context as _;
use calibration::CalibrationProfile;
use retarget::{HandModel, KeypointLayout};

/// Read, parse and validate the profile at `path` and check that it was made for `model` and
/// `layout`; errors name the file (and the key, from the calibration crate's error).
pub fn load_profile(
    path: &Path,
    model: &HandModel,
    layout: KeypointLayout,
) -> anyhow::Result<CalibrationProfile> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read calibration profile {}", path.display()))?;
    let profile = CalibrationProfile::from_toml_str(&text)
        .map_err(|e| anyhow::anyhow!("calibration profile {}: {e}", path.display()))?;
    profile
        .check_fits(model, layout)
        .map_err(|e| anyhow::anyhow!("calibration profile {}: {e}", path.display()))?;
    Ok(profile)
}

/// One line: who, when, and the transform (scale, roll/pitch/yaw in degrees).
pub fn describe(profile: &CalibrationProfile) -> String {
    let p = &profile.parameters;
    format!(
        "calibration profile: user {}, date {}, scale {:.3}, roll {:.1}°, pitch {:.1}°, yaw {:.1}°",
        profile.user,
        profile.date,
        p.scale,
        p.roll_rad.to_degrees(),
        p.pitch_rad.to_degrees(),
        p.yaw_rad.to_degrees()
    )
}

pub use crate::atomic_file::write_atomically;

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

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
