//! The trial console's `--script` files: the shared grammar ([`crate::tui::script`]) with the
//! trial console's actions ([`super::keys`]) and states ([`super::view::Screen`]).

use std::path::Path;

use super::ConsoleError;
use super::keys::{Action, parse_action};
use super::view::Screen;
use crate::tui::script::{
    ScriptError, ScriptLine, ScriptState, load_script_with, parse_script_with,
};

impl ScriptState for Screen {
    fn from_name(name: &str) -> Option<Screen> {
        Screen::from_name(name)
    }

    fn name(self) -> &'static str {
        Screen::name(self)
    }

    fn names() -> String {
        Screen::ALL.map(Screen::name).join(", ")
    }
}

/// A line of the trial console's scripts.
pub type TrialScriptLine = ScriptLine<Action, Screen>;

/// Reads and parses a trial console script; errors name the file and the line.
pub fn load_script(path: &Path) -> Result<Vec<TrialScriptLine>, ConsoleError> {
    Ok(load_script_with(path, parse_action)?)
}

/// Parses a trial console script's text; an error's text is `LINE: reason`.
pub fn parse_script(text: &str) -> Result<Vec<TrialScriptLine>, ScriptError> {
    parse_script_with(text, parse_action)
}
