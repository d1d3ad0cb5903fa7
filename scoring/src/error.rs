//! The scoring crate's one error type.
//!
//! Every variant names where the problem is: the file a configuration came from (`origin`,
//! the text the caller passed in: a path, or `built-in`), or the trial log (`file`), and says
//! what is wrong in words an operator can act on.

/// Loading a catalog, baseline or rules file, or scoring a trial, failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ScoringError {
    /// A TOML file does not parse or has unknown keys.
    #[error("{origin}: {reason}")]
    Syntax {
        /// Where the text came from.
        origin: String,
        /// The parser's message (with line and column).
        reason: String,
    },
    /// A configuration value is out of range or inconsistent.
    #[error("{origin}: {key} = {value}: {allowed}")]
    Invalid {
        /// Where the text came from.
        origin: String,
        /// The key, with the entry it belongs to (`task V1: correctness.count`).
        key: String,
        /// The value found.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// A trial log cannot be scored.
    #[error("{file}: {reason}")]
    Trial {
        /// The trial log (its path, as the caller named it).
        file: String,
        /// What is wrong with it.
        reason: String,
    },
    /// Trials cannot be compared by a metadata field (fewer than two groups, an unknown
    /// reference group, no recorded trials).
    #[error("comparison by {field:?}: {reason}")]
    Comparison {
        /// The metadata field the trials are grouped by.
        field: String,
        /// What is wrong.
        reason: String,
    },
    /// A figure could not be drawn.
    #[error("figure {figure}: {reason}")]
    Figure {
        /// The figure's file stem (`radar_manipulation`).
        figure: String,
        /// The plotting error.
        reason: String,
    },
}

impl ScoringError {
    /// A [`ScoringError::Invalid`].
    pub(crate) fn invalid(
        origin: &str,
        key: impl Into<String>,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> ScoringError {
        ScoringError::Invalid {
            origin: origin.to_string(),
            key: key.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }

    /// A [`ScoringError::Syntax`] from a TOML parse error.
    pub(crate) fn syntax(origin: &str, error: &toml::de::Error) -> ScoringError {
        ScoringError::Syntax {
            origin: origin.to_string(),
            reason: error.to_string().trim_end().to_string(),
        }
    }

    /// A [`ScoringError::Trial`].
    pub(crate) fn trial(file: &str, reason: impl Into<String>) -> ScoringError {
        ScoringError::Trial {
            file: file.to_string(),
            reason: reason.into(),
        }
    }
}
