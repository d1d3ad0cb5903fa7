//! The crate's error: a value out of its range, or a file that does not parse.

/// What is wrong with a practice file or a setting.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PracticeError {
    /// A value outside what is allowed.
    #[error("{key} = {value}: allowed {allowed}")]
    Range {
        /// The key (`bounds.time_scale`, `task[3].grips`).
        key: String,
        /// The value given.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// The text is not the format.
    #[error("{reason}")]
    Syntax {
        /// The parser's words.
        reason: String,
    },
}

impl PracticeError {
    /// `key = value: allowed …` for a number.
    pub fn range(key: &str, value: f64, allowed: String) -> PracticeError {
        PracticeError::Range {
            key: key.to_string(),
            value: value.to_string(),
            allowed,
        }
    }
}
