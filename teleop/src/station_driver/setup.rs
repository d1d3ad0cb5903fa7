//! The one place a station is set up from files: the configuration (`--config FILE`, else the
//! built-in ETH lab preset), the user's calibration profile over it (`--profile FILE`, else the
//! configuration's `calibration_profile`), and the [`Station`] built from both. Errors
//! ([`SetupError`]) name the file and the key.

use std::path::{Path, PathBuf};

use calibration::CalibrationProfile;
use retarget::{HandModel, KeypointLayout};
use station::{ConfigError, Station, StationConfig, StationError};

/// A station that cannot be set up from its files.
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    /// The configuration file cannot be read.
    #[error("cannot read {path}: {source}")]
    ReadConfig {
        /// The configuration file.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The configuration file does not parse or validate.
    #[error("{path}: {source}")]
    Config {
        /// The configuration file.
        path: PathBuf,
        /// What is wrong with it (names the key).
        #[source]
        source: ConfigError,
    },
    /// The calibration profile cannot be read.
    #[error("cannot read calibration profile {path}: {source}")]
    ReadProfile {
        /// The profile.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The calibration profile does not parse or validate, or was not made for this hand
    /// model and keypoint layout.
    #[error("calibration profile {path}: {source}")]
    Profile {
        /// The profile.
        path: PathBuf,
        /// What is wrong with it (names the key).
        #[source]
        source: calibration::Error,
    },
    /// The station refuses the configuration (or the hand model, or the calibration).
    #[error(transparent)]
    Station(#[from] StationError),
}

/// Read, parse and validate a station configuration file; errors name it. A relative
/// `calibration_profile` or `simulated_hand_mjcf` is resolved against the file's directory.
pub fn read_station_config(path: &Path) -> Result<StationConfig, SetupError> {
    let text = std::fs::read_to_string(path).map_err(|source| SetupError::ReadConfig {
        path: path.to_path_buf(),
        source,
    })?;
    let mut config = StationConfig::from_toml_str(&text).map_err(|source| SetupError::Config {
        path: path.to_path_buf(),
        source,
    })?;
    let dir = path.parent().unwrap_or(Path::new(""));
    for file in [
        &mut config.calibration_profile,
        &mut config.simulated_hand_mjcf,
    ] {
        if let Some(relative) = file.as_ref().filter(|f| f.is_relative()) {
            *file = Some(dir.join(relative));
        }
    }
    Ok(config)
}

/// The configuration of `config` (else the built-in default), with `profile` (when given) in
/// place of its calibration profile.
pub fn load_station_config(
    config: Option<&Path>,
    profile: Option<&Path>,
) -> Result<StationConfig, SetupError> {
    let mut loaded = match config {
        Some(path) => read_station_config(path)?,
        None => StationConfig::default(),
    };
    if let Some(profile) = profile {
        loaded.calibration_profile = Some(profile.to_path_buf());
    }
    Ok(loaded)
}

/// A station for `config` on `model`, with its calibration profile loaded (checked against the
/// model and the layout), and the profile's one-line description.
pub fn build_station(
    config: &StationConfig,
    model: HandModel,
) -> Result<(Station, Option<String>), SetupError> {
    let profile = match &config.calibration_profile {
        Some(path) => Some(load_profile(path, &model, config.retarget.layout)?),
        None => None,
    };
    let description = profile.as_ref().map(describe);
    let station = Station::new(config, model, profile.map(|p| p.parameters))?;
    Ok((station, description))
}

/// Read, parse and validate the profile at `path` and check that it was made for `model` and
/// `layout`; errors name the file (and the key, from the calibration crate's error).
pub fn load_profile(
    path: &Path,
    model: &HandModel,
    layout: KeypointLayout,
) -> Result<CalibrationProfile, SetupError> {
    let text = std::fs::read_to_string(path).map_err(|source| SetupError::ReadProfile {
        path: path.to_path_buf(),
        source,
    })?;
    let invalid = |source| SetupError::Profile {
        path: path.to_path_buf(),
        source,
    };
    let profile = CalibrationProfile::from_toml_str(&text).map_err(invalid)?;
    profile.check_fits(model, layout).map_err(invalid)?;
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

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn relative_files_are_relative_to_the_config_file() {
        let dir = std::env::temp_dir().join(format!("pomdar-station-cfg-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("station.toml");
        std::fs::write(
            &path,
            "calibration_profile = \"profiles/alice.toml\"\nsimulated_hand_mjcf = \"hands/orca.xml\"\n",
        )
        .unwrap();
        let config = read_station_config(&path).unwrap();
        let overridden = load_station_config(Some(&path), Some(Path::new("/p.toml"))).unwrap();
        std::fs::remove_dir_all(&dir).ok();
        assert_eq!(
            config.calibration_profile,
            Some(dir.join("profiles/alice.toml"))
        );
        assert_eq!(config.simulated_hand_mjcf, Some(dir.join("hands/orca.xml")));
        assert_eq!(
            overridden.calibration_profile,
            Some(Path::new("/p.toml").to_path_buf())
        );
    }

    #[test]
    fn a_missing_profile_is_named() {
        let err = load_profile(
            Path::new("/nonexistent/bob.toml"),
            &HandModel::orca_v1_right(),
            KeypointLayout::Lab22,
        )
        .unwrap_err();
        assert!(err.to_string().contains("/nonexistent/bob.toml"), "{err}");
    }
}
