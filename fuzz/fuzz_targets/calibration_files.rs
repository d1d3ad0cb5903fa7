//! Any text as calibration settings, a calibration profile or a pose set:
//! calibration/tests/suite/config_oracle.
#![no_main]

#[path = "../../calibration/tests/suite/config_oracle/mod.rs"]
mod config_oracle;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    config_oracle::check_text(&String::from_utf8_lossy(data));
});
