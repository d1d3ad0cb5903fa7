//! The `pomdar` commands: one file a command, each with its own clap `Args` and the function
//! that runs it. This is the binary's wiring: it reads the arguments, loads the files, starts
//! the nodes and prints; the work is in the modules below it. Nothing else in the crate imports
//! from here.
//!
//! The doc comments on each command's `Args` are its `--help` text, verbatim: TOML tables
//! (`[policy_output]`) and placeholders (`<task>`) are for the terminal, not links or HTML.
#![allow(rustdoc::broken_intra_doc_links, rustdoc::invalid_html_tags)]

pub mod baseline;
pub mod calibrate;
pub mod cli;
pub mod demo;
pub mod eval;
pub mod eval_set;
pub mod hand_check;
pub mod ingress;
pub mod mock_franka;
pub mod mock_hand;
pub mod model;
pub mod probe;
pub mod recover;
pub mod relay;
pub mod replay;
pub mod resim;
pub mod review;
pub mod score;
pub mod shared_args;
pub mod sim;
pub mod sim_bench;
pub mod sim_glove;
pub mod station;
pub mod study;
pub mod study_report;
pub mod tracking;
pub mod trial;
