//! `teleop`'s integration tests, one module per concern, linked into one test
//! binary: the dependency tree is linked once for all of them, not once per file.

#![allow(clippy::unwrap_used, clippy::expect_used)] // in tests a panic is the failure report

mod config_oracle;
mod mcap_oracle;
mod rokoko_oracle;
#[path = "../../../fuzz/support/toml_mutation.rs"]
mod toml_mutation;

mod crash_recovery;
mod dds_loopback;
mod fuzz_config;
mod fuzz_mcap_reader;
mod fuzz_rokoko_packet;
mod mcap_log;
mod recorder;
