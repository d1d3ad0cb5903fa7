//! The trial console's session (`pomdar trial`, each task of `pomdar study`) without its I/O:
//! the session as a state machine, the station's health and the start gate, the manifest's
//! data, the operator's actions and what the console shows. `teleop::console` runs it: the
//! station, the trial logs, the manifest's file, the terminal.

pub mod action;
pub mod health;
mod health_lines;
pub mod manifest;
pub mod trial_flow;
pub mod view;
