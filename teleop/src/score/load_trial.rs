//! A trial file → [`scoring::TrialLog`]: the `pomdar_trial` metadata record and the trial
//! events parsed as JSON, read with [`read_trial_events`] (summary-indexed, fast).

use std::path::Path;

use scoring::{TRIAL_METADATA_NAME, TrialLog};

use super::TrialFileError;
use crate::mcap_log::read_trial_events;

/// Reads the trial at `path`; the error is the reason (the caller names the file).
pub fn load_trial_log(path: &Path) -> Result<TrialLog, TrialFileError> {
    let events = read_trial_events(path).map_err(|source| TrialFileError::Log {
        path: path.to_path_buf(),
        source: Box::new(source),
    })?;
    let metadata = events
        .metadata_named(TRIAL_METADATA_NAME)
        .cloned()
        .ok_or_else(|| TrialFileError::NotTrial {
            found: if events.metadata.is_empty() {
                "no metadata".to_string()
            } else {
                events
                    .metadata
                    .iter()
                    .map(|(n, _)| n.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            },
        })?;
    let base = events.events.first().map_or(0, |(t, _)| *t);
    let parsed = events
        .events
        .iter()
        .enumerate()
        .map(|(i, (t, text))| {
            serde_json::from_str(text)
                .map(|json| (*t, json))
                .map_err(|source| TrialFileError::EventNotJson {
                    number: i + 1,
                    offset_s: (t - base) as f64 * 1e-9,
                    text: text.clone(),
                    source,
                })
        })
        .collect::<Result<Vec<_>, TrialFileError>>()?;
    Ok(TrialLog {
        source: path.display().to_string(),
        metadata,
        events: parsed,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn the_error_is_the_reason_without_the_file() {
        let dir = std::env::temp_dir().join(format!("pomdar-load-trial-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("garbage.mcap");
        std::fs::write(&path, b"not a log").unwrap();
        let error = load_trial_log(&path).unwrap_err();
        std::fs::remove_dir_all(&dir).ok();
        let reason = error.to_string();
        assert!(reason.starts_with("not an MCAP file: "), "{reason}");
        assert_eq!(error.to_string(), reason);
    }
}
