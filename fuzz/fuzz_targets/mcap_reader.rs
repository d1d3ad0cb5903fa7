//! Any bytes as a complete trial log (`TrialReader::from_bytes`): teleop/tests/suite/mcap_oracle.
#![no_main]

#[allow(dead_code)]
#[path = "../../teleop/tests/suite/mcap_oracle/mod.rs"]
mod mcap_oracle;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    mcap_oracle::check_trial_reader(data);
});
