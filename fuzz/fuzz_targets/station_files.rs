//! Any text as a station configuration, arm settings, URDF import file or ingress settings:
//! teleop/tests/suite/config_oracle.
#![no_main]

#[path = "../../teleop/tests/suite/config_oracle/mod.rs"]
mod config_oracle;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    config_oracle::check_text(&String::from_utf8_lossy(data));
});
