//! The files in `launch_configs/`, by kind, so every one of them can be checked by a test and
//! by the operator before a session.

use std::path::{Path, PathBuf};

use retarget::RetargetConfig;

use crate::hand_source::ImportFile;
use station::StationConfig;

/// A launch config file is of no known kind, cannot be read, or is not valid.
#[derive(Debug, thiserror::Error)]
pub enum LaunchConfigError {
    /// The file is not in one of the known folders.
    #[error(
        "{path}: not a known kind of launch config (expected under launch_configs/hands/, retarget/, station/, calibration/, tasks/, scoring/, baselines/, ingress/ or sim/)"
    )]
    UnknownKind {
        /// The file.
        path: PathBuf,
    },
    /// The file cannot be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// A hand import file, retargeting configuration or glove script is not valid (the error
    /// names the file).
    #[error(transparent)]
    Retarget {
        /// The error, in its file.
        #[from]
        source: retarget::Error,
    },
    /// A station preset is not valid.
    #[error("{path}: {source}")]
    Station {
        /// The file.
        path: PathBuf,
        /// What is wrong, by key.
        #[source]
        source: station::ConfigError,
    },
    /// Calibration settings are not valid.
    #[error("{path}: {source}")]
    Calibration {
        /// The file.
        path: PathBuf,
        /// What is wrong, by key.
        #[source]
        source: calibration::Error,
    },
    /// A task catalog, scoring rules or a baseline table is not valid (the error names the
    /// file).
    #[error(transparent)]
    Scoring {
        /// The error, with the file as its origin.
        #[from]
        source: scoring::ScoringError,
    },
    /// A practice file is not valid.
    #[error("{path}: {source}")]
    Practice {
        /// The file.
        path: PathBuf,
        /// What is wrong, by key.
        #[source]
        source: practice::PracticeError,
    },
    /// Glove ingress settings are not valid.
    #[error("{path}: {source}")]
    Ingress {
        /// The file.
        path: PathBuf,
        /// What is wrong, by key.
        #[source]
        source: Box<crate::ingress::IngressError>,
    },
}

/// The kinds of file under `launch_configs/`, by the folder they live in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LaunchConfigKind {
    /// `hands/*.toml`: URDF import files.
    HandImport,
    /// `retarget/*.toml`: retargeting configurations.
    Retarget,
    /// `station/*.toml`: station presets.
    Station,
    /// `calibration/*.toml`: calibration settings (`pomdar calibrate --settings`).
    CalibrationSettings,
    /// `tasks/*.toml`: task catalogs (`pomdar score --catalog`).
    TaskCatalog,
    /// `scoring/*.toml`: scoring rules (`pomdar score --rules`), checked against the built-in
    /// task catalog.
    ScoringRules,
    /// `baselines/*.toml`: human baseline tables (`pomdar score --baseline`), checked against
    /// the built-in task catalog.
    Baseline,
    /// `ingress/*.toml`: glove ingress settings (`pomdar ingress rokoko --config`).
    Ingress,
    /// `sim/*.toml`: the simulated glove's task scripts (`pomdar demo --glove-script`,
    /// `pomdar trial --simulate --simulate-glove-script`).
    GloveScript,
    /// `sim/practice.toml`: programmed practice's strategy families (`pomdar sim-bench
    /// --practice`), its tasks checked against the built-in catalog.
    Practice,
}

impl LaunchConfigKind {
    /// The kind of a file, from its folder under `launch_configs/` (`sim/tasks/` holds the
    /// glove task scripts of single tasks, not a task catalog).
    pub fn of(path: &Path) -> Option<LaunchConfigKind> {
        let folder = path.parent()?.file_name()?.to_str()?;
        let grandparent = path
            .parent()?
            .parent()
            .and_then(Path::file_name)
            .and_then(|n| n.to_str());
        if folder == "tasks" && grandparent == Some("sim") {
            return Some(LaunchConfigKind::GloveScript);
        }
        if folder == "sim" && path.file_name()? == "practice.toml" {
            return Some(LaunchConfigKind::Practice);
        }
        match folder {
            "hands" => Some(LaunchConfigKind::HandImport),
            "retarget" => Some(LaunchConfigKind::Retarget),
            "station" => Some(LaunchConfigKind::Station),
            "calibration" => Some(LaunchConfigKind::CalibrationSettings),
            "tasks" => Some(LaunchConfigKind::TaskCatalog),
            "scoring" => Some(LaunchConfigKind::ScoringRules),
            "baselines" => Some(LaunchConfigKind::Baseline),
            "ingress" => Some(LaunchConfigKind::Ingress),
            "sim" => Some(LaunchConfigKind::GloveScript),
            _ => None,
        }
    }
}

/// Read and validate one launch config file; the error names the file and key.
pub fn check_file(path: &Path) -> Result<LaunchConfigKind, LaunchConfigError> {
    let Some(kind) = LaunchConfigKind::of(path) else {
        return Err(LaunchConfigError::UnknownKind {
            path: path.to_path_buf(),
        });
    };
    let text = std::fs::read_to_string(path).map_err(|source| LaunchConfigError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    match kind {
        LaunchConfigKind::HandImport => {
            ImportFile::from_toml_str(&text).map_err(|e| e.in_file(path))?;
        }
        LaunchConfigKind::Retarget => {
            RetargetConfig::from_toml_str(&text).map_err(|e| e.in_file(path))?;
        }
        LaunchConfigKind::Station => {
            StationConfig::from_toml_str(&text).map_err(|source| LaunchConfigError::Station {
                path: path.to_path_buf(),
                source,
            })?;
        }
        LaunchConfigKind::CalibrationSettings => {
            calibration::CalibrationSettings::from_toml_str(&text).map_err(|source| {
                LaunchConfigError::Calibration {
                    path: path.to_path_buf(),
                    source,
                }
            })?;
        }
        LaunchConfigKind::TaskCatalog => {
            scoring::TaskCatalog::from_toml_str(&text, &path.display().to_string())?;
        }
        LaunchConfigKind::ScoringRules => {
            scoring::ScoringRules::from_toml_str(
                &text,
                &path.display().to_string(),
                &scoring::TaskCatalog::builtin(),
            )?;
        }
        LaunchConfigKind::Baseline => {
            scoring::BaselineTable::from_toml_str(
                &text,
                &path.display().to_string(),
                &scoring::TaskCatalog::builtin(),
            )?;
        }
        LaunchConfigKind::Ingress => {
            // `avp*.toml`: the Vision Pro ingress's settings; any other: the Rokoko ingress's.
            let avp = path
                .file_stem()
                .and_then(|s| s.to_str())
                .is_some_and(|s| s.starts_with("avp"));
            let checked = match avp {
                true => crate::ingress::avp_config::AvpConfig::from_toml_str(&text).map(drop),
                false => {
                    crate::ingress::ingress_config::IngressConfig::from_toml_str(&text).map(drop)
                }
            };
            checked.map_err(|e| LaunchConfigError::Ingress {
                path: path.to_path_buf(),
                source: Box::new(e),
            })?;
        }
        LaunchConfigKind::GloveScript => {
            retarget::human_hand::GloveScript::from_toml_str(&text).map_err(|e| e.in_file(path))?;
        }
        LaunchConfigKind::Practice => {
            let catalog = scoring::TaskCatalog::builtin();
            let known: Vec<&str> = catalog.tasks.iter().map(|t| t.id.as_str()).collect();
            practice::PracticeFile::from_toml_str(&text, &known).map_err(|source| {
                LaunchConfigError::Practice {
                    path: path.to_path_buf(),
                    source,
                }
            })?;
        }
    }
    Ok(kind)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_glove_scripts_are_checked_as_scripts() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../launch_configs/sim");
        for name in ["grasp_place.toml", "grasp_miss.toml", "tasks/C4.toml"] {
            let kind = check_file(&dir.join(name)).unwrap();
            assert_eq!(kind, LaunchConfigKind::GloveScript, "{name}");
        }
    }

    #[test]
    fn a_broken_glove_script_is_reported_with_file_and_field() {
        let dir = std::env::temp_dir().join(format!("pomdar-launch-sim-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sim")).unwrap();
        let path = dir.join("sim/backwards.toml");
        let keyframe = |t: f64| {
            format!("[[keyframes]]\nt_s = {t:?}\nwrist_m = [0.0, 0.0, 0.0]\npose = \"open\"\n")
        };
        std::fs::write(&path, keyframe(0.0) + &keyframe(2.0) + &keyframe(1.0)).unwrap();
        let err = check_file(&path).unwrap_err().to_string();
        std::fs::remove_dir_all(&dir).ok();
        assert!(
            err.contains("backwards.toml") && err.contains("keyframes[2].t_s"),
            "{err}"
        );
    }
}
