//! The simulated benchmark's integration tests, one module per concern, linked into one test
//! binary: the dependency tree is linked once for all of them, not once per file.
//! Built only with the `physics` feature (`required-features` in Cargo.toml).

#![allow(clippy::unwrap_used, clippy::expect_used)] // in tests a panic is the failure report

mod driver_paths;
mod physics_demo;
mod physics_engine;
mod physics_hands;
mod physics_scenes;
mod physics_tasks;
mod physics_trial;
mod sim_bench;
