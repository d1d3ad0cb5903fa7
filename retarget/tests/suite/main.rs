//! `retarget`'s integration tests, one module per concern, linked into one test
//! binary: the dependency tree is linked once for all of them, not once per file.

#![allow(clippy::unwrap_used, clippy::expect_used)] // in tests a panic is the failure report

mod common;
mod config_oracle;
#[path = "../../../fuzz/support/toml_mutation.rs"]
mod toml_mutation;

mod fk_crosscheck;
mod fuzz_config;
mod human_hand;
mod jacobian_properties;
mod malformed_models;
mod pinch;
mod quality_reference;
mod real_recording;
mod round_trip;
mod safety_properties;
