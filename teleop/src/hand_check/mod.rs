//! # The hand check (`pomdar hand-check`): a table of a hand's command conventions, checked on
//! the hand, joint by joint
//!
//! The table is the station configuration's `[[policy_output.joints]]`
//! ([`station::hand_convention`]). From a neutral pose each joint in turn moves a small, slow
//! step and back through the table on the consumer's topic while the terminal names what the
//! operator should see; the operator confirms, reports the wrong direction (and flips the
//! sign), repeats or quits. Only when every joint is confirmed is the table written again,
//! every row verified, with who checked it and when.
//!
//! | file | what |
//! |---|---|
//! | `session`, `directions` | re-exported from the core crate `consoles` (`consoles/src/hand_check/`): the check as a pure state machine (time a parameter) and what each joint's motion looks like |
//! | `hand_check_script.rs` | `--script` files and typed words: yes / no / repeat / flip / keep / quit, `wait PHASE` |
//! | `check_node.rs` | the check over ROS 2 on the consoles' terminal shell: commands at a fixed rate (its tick), answers from the script or stdin, SIGINT and SIGTERM quit |
//! | `table_file.rs` | the verified table written into a copy of the station configuration (comments kept), checked to load back |
//! | `error.rs` | the one error type, [`HandCheckError`] |

pub mod check_node;
pub mod error;
pub mod hand_check_script;
pub mod table_file;

pub use consoles::hand_check::{directions, session};

pub use error::HandCheckError;
