//! Where the station's hand model comes from: the built-in ORCA v1 right hand, a model file in
//! the project's TOML format, or a URDF with an import file naming its frames.
//!
//! All file reading happens here; errors name the file.

use std::path::{Path, PathBuf};

use retarget::{Error, FrameSpec, HandModel, UrdfImport};
use serde::Deserialize;

/// Loading a hand model failed.
#[derive(Debug, thiserror::Error)]
pub enum HandSourceError {
    /// A model, URDF or import file cannot be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// A file does not describe a valid hand (the error names the file).
    #[error(transparent)]
    Model {
        /// The model's error, in its file.
        #[from]
        source: Error,
    },
}

/// The hand to load.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum HandSource {
    /// The built-in ORCA v1 right hand.
    BuiltinOrcaV1Right,
    /// A model file in the project's TOML format.
    ModelFile(PathBuf),
    /// A URDF and the import file that names its frames.
    Urdf {
        /// The URDF.
        urdf: PathBuf,
        /// The import description (`launch_configs/hands/*.toml`).
        import: PathBuf,
    },
}

/// A URDF import file (`launch_configs/hands/*.toml`): how to read a URDF as a hand.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImportFile {
    /// Prefix removed from every joint and link name (`right_`).
    #[serde(default)]
    pub strip_prefix: String,
    /// Link names (after stripping) of the frames the station needs.
    pub frames: FrameSpec,
}

impl ImportFile {
    /// Parse an import file's text; errors name the key.
    pub fn from_toml_str(text: &str) -> Result<ImportFile, Error> {
        toml::from_str(text).map_err(|e| Error::Syntax {
            reason: e.to_string().trim_end().to_string(),
        })
    }
}

impl HandSource {
    /// Load and validate the model.
    pub fn load(&self) -> Result<HandModel, HandSourceError> {
        match self {
            HandSource::BuiltinOrcaV1Right => Ok(HandModel::orca_v1_right()),
            HandSource::ModelFile(path) => {
                let text = read(path)?;
                Ok(HandModel::from_toml_str(&text).map_err(|e| e.in_file(path))?)
            }
            HandSource::Urdf { urdf, import } => {
                let import_text = read(import)?;
                let import_file: ImportFile = toml::from_str(&import_text).map_err(|e| {
                    Error::Syntax {
                        reason: e.to_string().trim_end().to_string(),
                    }
                    .in_file(import)
                })?;
                let text = read(urdf)?;
                let import = UrdfImport {
                    strip_prefix: import_file.strip_prefix,
                    frames: import_file.frames,
                };
                Ok(HandModel::from_urdf_str(&text, &import).map_err(|e| e.in_file(urdf))?)
            }
        }
    }

    /// The robot's URDF text, for `/robot_description` (only a URDF source has one).
    pub fn robot_description(&self) -> Result<Option<String>, HandSourceError> {
        match self {
            HandSource::Urdf { urdf, .. } => read(urdf).map(Some),
            _ => Ok(None),
        }
    }

    /// One line saying where the model comes from.
    pub fn describe(&self) -> String {
        match self {
            HandSource::BuiltinOrcaV1Right => "built-in ORCA v1 right hand".into(),
            HandSource::ModelFile(p) => format!("model file {}", p.display()),
            HandSource::Urdf { urdf, import } => {
                format!("URDF {} (import {})", urdf.display(), import.display())
            }
        }
    }
}

fn read(path: &Path) -> Result<String, HandSourceError> {
    std::fs::read_to_string(path).map_err(|source| HandSourceError::Read {
        path: path.to_path_buf(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_file_is_named() {
        let path = PathBuf::from("/nonexistent/pomdar/hand.toml");
        let err = HandSource::ModelFile(path).load().unwrap_err().to_string();
        assert!(
            err.starts_with("cannot read /nonexistent/pomdar/hand.toml: "),
            "{err}"
        );
    }
}
