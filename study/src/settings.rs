//! The analysis settings and their allowed ranges.

use serde::{Deserialize, Serialize};

use crate::error::StudyError;

/// Longest segment accepted, seconds: a trial is a few seconds to a minute, and a
/// segment longer than that averages a whole strategy into one posture.
pub const MAX_SEGMENT_S: f64 = 60.0;

/// Analysis settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct StrategySettings {
    /// Segment length in seconds (the paper: 1.5 s).
    pub segment_s: f64,
    /// Principal components to keep (fewer when the data has fewer dimensions).
    pub components: usize,
    /// A window with fewer usable frames than this is dropped.
    pub min_frames_per_segment: usize,
}

impl Default for StrategySettings {
    fn default() -> Self {
        Self {
            segment_s: 1.5,
            components: 3,
            min_frames_per_segment: 5,
        }
    }
}

impl StrategySettings {
    /// `Err(BadSetting)` naming the first setting outside its range.
    pub fn validate(&self) -> Result<(), StudyError> {
        if !(self.segment_s.is_finite() && self.segment_s > 0.0 && self.segment_s <= MAX_SEGMENT_S)
        {
            return Err(StudyError::BadSetting {
                name: "segment_s",
                value: format!("{} s", self.segment_s),
                allowed: "above 0 s, at most 60 s",
            });
        }
        if self.components == 0 {
            return Err(StudyError::BadSetting {
                name: "components",
                value: self.components.to_string(),
                allowed: "at least 1",
            });
        }
        if self.min_frames_per_segment < 2 {
            return Err(StudyError::BadSetting {
                name: "min_frames_per_segment",
                value: self.min_frames_per_segment.to_string(),
                allowed: "at least 2: a segment's movement is a standard deviation over frames",
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_bad_values_are_named() {
        assert_eq!(StrategySettings::default().validate(), Ok(()));
        let bad = StrategySettings {
            segment_s: f64::NAN,
            ..StrategySettings::default()
        };
        let err = bad.validate().unwrap_err().to_string();
        assert!(
            err.starts_with("strategy setting segment_s = NaN s"),
            "{err}"
        );
        let bad = StrategySettings {
            min_frames_per_segment: 1,
            ..StrategySettings::default()
        };
        let err = bad.validate().unwrap_err().to_string();
        assert!(err.contains("min_frames_per_segment = 1"), "{err}");
        let bad = StrategySettings {
            components: 0,
            ..StrategySettings::default()
        };
        assert!(matches!(
            bad.validate(),
            Err(StudyError::BadSetting {
                name: "components",
                ..
            })
        ));
    }
}
