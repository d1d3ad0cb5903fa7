//! The operator console: `pomdar trial` (timed trials). The session logic is the core crate
//! `consoles` (`consoles/src/console/`, re-exported here as `trial_flow`, `health` and `view`;
//! the manifest's data and the actions are re-exported from `manifest` and `keys`); this module
//! is the console's runtime: its set-up ([`session_setup::run_session`]), its event loop
//! (`runner`), the operator's side (`operator_side`), the words and keys (`keys`), the
//! manifest's file (`manifest`) and the session directory (`session_dir`), the session's files
//! (`session_state`, `session_report`), the station in this process (`in_process_station`) and
//! the simulation beside it (`simulated_world`, `physics_link`).

pub mod error;
mod in_process_station;
pub mod keys;
pub mod manifest;
pub mod message_log;
mod operator_side;
mod physics_link;
pub mod plain_output;
mod runner;
pub mod screen;
mod session_check;
pub mod session_dir;
pub mod session_error;
mod session_info;
pub mod session_options;
mod session_report;
pub mod session_setup;
mod session_state;
mod simulated_world;
pub mod test_pause;
pub mod trial_script;

pub use consoles::console::{health, trial_flow, view};
pub use error::ConsoleError;
pub use runner::SessionEnd;
pub use session_error::SessionError;
pub use session_options::{ConsoleSettings, SessionOptions, SimulationOptions};
pub use session_setup::run_session;
