//! Any text as a task catalog, scoring rules or a baseline table, and any JSON as a trial
//! log (`{"metadata": {..}, "events": [[ns, {..}], ..]}`) to check and score:
//! scoring/tests/suite/config_oracle.
#![no_main]

#[path = "../../scoring/tests/suite/config_oracle/mod.rs"]
mod config_oracle;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    config_oracle::check_text(&String::from_utf8_lossy(data));
    if let Some(log) = config_oracle::trial_log_from_json(data) {
        config_oracle::check_trial(&log);
    }
});
