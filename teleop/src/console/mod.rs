//! The operator console: `pomdar trial` (timed trials). The session logic, the
//! health, the manifest and the script are plain data and state machines; the terminal, the
//! station and the files are handled by the command.

pub mod error;
pub mod health;
pub mod keys;
pub mod manifest;
pub mod message_log;
pub mod plain_output;
pub mod screen;
pub mod session_dir;
pub mod test_pause;
pub mod trial_flow;
pub mod trial_script;
pub mod view;

pub use error::ConsoleError;
