//! The terminal pieces both operator consoles (the trial console, [`crate::console`], and the
//! calibration console, [`crate::calibrate`]) share: full-screen mode and keyboard input, the
//! panels and level colours, the `--script` grammar and player, and the turn loop's shell (tick,
//! signals, turns).

mod error;
pub mod panels;
pub mod script;
pub mod script_player;
pub mod terminal;
pub mod terminal_shell;

pub use error::TuiError;
