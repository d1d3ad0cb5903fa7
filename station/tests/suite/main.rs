//! `station`'s integration tests, one module per concern, linked into one test
//! binary: the dependency tree is linked once for all of them, not once per file.

#![allow(clippy::unwrap_used, clippy::expect_used)] // in tests a panic is the failure report

mod arm_properties;
mod fuzz_station;
