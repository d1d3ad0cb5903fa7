//! The arm configuration's error: found at set-up, it names the key (and the file).
//!
//! What the mapper refuses per step (an unusable pose, an engage outside the workspace) is not
//! an error of the configuration: it is an [`ArmRefusal`](super::ArmRefusal), data the caller
//! counts. A limited command (clamped, capped, constrained) is neither: it is data in
//! [`ArmCommand`](super::ArmCommand).

use std::path::PathBuf;

/// Malformed arm configuration.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum ArmConfigError {
    /// The problem was found in this file.
    #[error("{path}: {source}")]
    InFile {
        /// The file that was read.
        path: PathBuf,
        /// What is wrong with it.
        source: Box<ArmConfigError>,
    },
    /// The TOML does not parse, or has an unknown or mistyped key.
    #[error("invalid arm configuration: {reason}")]
    Syntax {
        /// The parser's message, with line, column and key.
        reason: String,
    },
    /// A configuration value out of its allowed range, or inconsistent with another key.
    #[error("config key '{key}' = {value}: {allowed}")]
    ConfigRange {
        /// Dotted key (`start_pose.position_m`).
        key: String,
        /// The value as read.
        value: String,
        /// The allowed range or the rule it breaks.
        allowed: String,
    },
}

impl ArmConfigError {
    /// Attach the file the error was found in.
    pub fn in_file(self, path: impl Into<PathBuf>) -> ArmConfigError {
        ArmConfigError::InFile {
            path: path.into(),
            source: Box::new(self),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_the_key_and_the_file() {
        let e = ArmConfigError::ConfigRange {
            key: "max_translation_step_m".into(),
            value: "0.5".into(),
            allowed: "must be in (0, 0.1]".into(),
        }
        .in_file("launch_configs/arm/lab.toml");
        let text = e.to_string();
        assert!(text.contains("launch_configs/arm/lab.toml"), "{text}");
        assert!(text.contains("max_translation_step_m"), "{text}");
        assert!(text.contains("(0, 0.1]"), "{text}");
    }
}
