//! Any text as a retargeting configuration, hand model or embodiment catalog:
//! retarget/tests/suite/config_oracle.
#![no_main]

#[allow(dead_code)]
#[path = "../../retarget/tests/suite/config_oracle/mod.rs"]
mod config_oracle;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    config_oracle::check_text(&String::from_utf8_lossy(data));
});
