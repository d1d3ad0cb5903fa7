//! The hand check (`pomdar hand-check`) without its I/O: the check of a hand's command
//! conventions, joint by joint, as a state machine, and what each joint's motion looks like.
//! `teleop::hand_check` sends the commands, reads the answers and writes the table.

pub mod directions;
pub mod session;
#[cfg(test)]
mod session_tests;
