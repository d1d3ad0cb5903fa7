//! The terminal pieces both operator consoles (the trial console, [`crate::console`], and the
//! calibration console, [`crate::calibrate`]) share: full-screen mode and keyboard input, the
//! panels and level colours, and the `--script` grammar and player.

mod error;
pub mod panels;
pub mod script;
pub mod script_player;
pub mod terminal;

pub use error::TuiError;
