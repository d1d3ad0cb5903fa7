//! `tests`'s integration tests, one module per concern, linked into one test
//! binary: the dependency tree is linked once for all of them, not once per file.

#![allow(clippy::unwrap_used, clippy::expect_used)] // in tests a panic is the failure report

mod avp_ingress;
mod calibrate_cli;
mod calibrate_console;
mod calibrate_interrupt;
mod calibrate_redo;
mod command_rule;
mod console_interrupt;
mod console_random_kills;
mod console_screen;
mod console_services;
mod console_session;
mod console_tampered_manifest;
mod datagram_guard_startup;
mod dds_crafted_datagrams;
mod demo_pipeline;
mod dependency_rule;
mod driver_paths_live;
mod eval_cli;
mod fault_injection;
mod fault_station_kill;
mod foxglove_layout;
mod fuzz_targets;
mod hand_check;
mod human_study;
mod interop_cyclonedds;
mod interop_cyclonedds_tools;
mod interop_foxglove;
mod interop_mcap;
mod launch_configs;
mod multi_host_dds;
mod multi_host_robot_link;
mod quiet_exit;
mod record_resim;
mod relay_clocks_and_robot;
mod relay_node;
mod replay_station;
mod resim;
mod rokoko_ingress;
mod ros_tools;
mod score_cli;
mod score_compare;
mod slow_disk;
mod stands_alone;
mod station_cli;
mod station_dds;
mod study_interrupt;
mod tracking_cli;
mod trial_review;
