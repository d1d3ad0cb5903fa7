//! A trial file → [`scoring::TrialLog`]: the `pomdar_trial` metadata record and the trial
//! events parsed as JSON, read with [`read_trial_events`] (summary-indexed, fast).

use std::path::Path;

use scoring::{TRIAL_METADATA_NAME, TrialLog};

use crate::mcap_log::read_trial_events;

/// Reads the trial at `path`; the error is the reason (the caller names the file).
pub fn load_trial_log(path: &Path) -> Result<TrialLog, String> {
    let shown = path.display().to_string();
    let events = read_trial_events(path).map_err(|e| {
        let message = e.to_string();
        message
            .strip_prefix(&format!("{shown}: "))
            .map_or(message.clone(), str::to_string)
    })?;
    let metadata = events
        .metadata_named(TRIAL_METADATA_NAME)
        .cloned()
        .ok_or_else(|| {
            format!(
                "no {TRIAL_METADATA_NAME} metadata record: not a POMDAR trial log (found {})",
                if events.metadata.is_empty() {
                    "no metadata".to_string()
                } else {
                    events
                        .metadata
                        .iter()
                        .map(|(n, _)| n.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                }
            )
        })?;
    let base = events.events.first().map_or(0, |(t, _)| *t);
    let parsed = events
        .events
        .iter()
        .enumerate()
        .map(|(i, (t, text))| {
            serde_json::from_str(text)
                .map(|json| (*t, json))
                .map_err(|e| {
                    format!(
                        "trial event {} (+{:.3} s) is not JSON ({e}): {text:?}",
                        i + 1,
                        (t - base) as f64 * 1e-9
                    )
                })
        })
        .collect::<Result<Vec<_>, String>>()?;
    Ok(TrialLog {
        source: shown,
        metadata,
        events: parsed,
    })
}
