//! The words and keys that give the operator's actions (the [`Action`]s are the core crate's,
//! `consoles::console::action`, re-exported here): the same actions come from the keyboard, a
//! `--script` file or a line on stdin.

use super::ConsoleError;
use crate::tui::script::{WordError, split_word, without_argument};

pub use consoles::console::action::Action;

/// The words of `--script` lines and stdin commands, with what they do (for `--help` and
/// errors).
pub const ACTION_WORDS: &[(&str, &str)] = &[
    (
        "engage",
        "engage (drive the robot once glove input is fresh)",
    ),
    ("disengage", "disengage / clutch out (the robot holds)"),
    ("start", "start the next trial after the countdown"),
    ("stop", "stop the running trial (task finished)"),
    (
        "progress [V]",
        "a progress mark: one notch/curve, or V degrees / mm / grasp level",
    ),
    ("unmark", "take back one notch/curve"),
    ("drop", "the object fell"),
    (
        "abort",
        "abort the running trial (scored as aborted) or cancel the countdown",
    ),
    (
        "redo",
        "abort the running trial, or set the last one aside, and run it again",
    ),
    (
        "note TEXT",
        "a note for the trial log (or the session manifest between trials)",
    ),
    (
        "quit",
        "quit; a running trial is set aside and redone when the session resumes",
    ),
];

/// The keys of the full-screen console, as shown in its key bar.
pub const KEY_HELP: &str = "e engage/clutch · space start/stop · + mark · - unmark · p value · d drop · a abort · r redo · n note · q quit";

/// Parses a command word with its argument (`progress 30`, `note glove slipped`).
pub fn parse_action(text: &str) -> Result<Action, ConsoleError> {
    let (word, rest) = split_word(text);
    let no_argument = |action: Action| Ok(without_argument(word, rest, action)?);
    match word {
        "engage" => no_argument(Action::Engage),
        "disengage" | "clutch" => no_argument(Action::Disengage),
        "start" => no_argument(Action::Start),
        "stop" => no_argument(Action::Stop),
        "progress" | "mark" => {
            if rest.is_empty() {
                return Ok(Action::Progress(None));
            }
            let value: f64 = rest.parse().map_err(|_| ConsoleError::ProgressNotANumber {
                value: rest.to_string(),
            })?;
            if !value.is_finite() {
                return Err(ConsoleError::ProgressNotFinite {
                    value: rest.to_string(),
                });
            }
            Ok(Action::Progress(Some(value)))
        }
        "unmark" => no_argument(Action::Unmark),
        "drop" => no_argument(Action::Drop),
        "abort" => no_argument(Action::Abort),
        "redo" => no_argument(Action::Redo),
        "note" => {
            if rest.is_empty() {
                Err(ConsoleError::NoteWithoutText)
            } else {
                Ok(Action::Note(rest.to_string()))
            }
        }
        "quit" => no_argument(Action::Quit),
        other => Err(WordError::Unknown {
            word: other.to_string(),
            known: ACTION_WORDS
                .iter()
                .map(|(w, _)| w.split(' ').next().unwrap_or(w))
                .collect::<Vec<_>>()
                .join(", "),
        }
        .into()),
    }
}

/// The action of a key of the full-screen console (outside a prompt).
pub fn key_action(key: char) -> Option<Action> {
    Some(match key {
        'e' | 'E' => Action::ToggleEngage,
        ' ' => Action::StartStop,
        '+' | '=' => Action::Progress(None),
        '-' => Action::Unmark,
        'p' | 'P' => Action::PromptProgress,
        'd' | 'D' => Action::Drop,
        'a' | 'A' => Action::Abort,
        'r' | 'R' => Action::Redo,
        'n' | 'N' => Action::PromptNote,
        'q' | 'Q' => Action::Quit,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_parse_with_their_arguments_and_errors_name_the_word() {
        assert_eq!(parse_action("progress").ok(), Some(Action::Progress(None)));
        assert_eq!(
            parse_action(" progress 0.5 ").ok(),
            Some(Action::Progress(Some(0.5)))
        );
        assert_eq!(
            parse_action("note glove slipped").ok(),
            Some(Action::Note("glove slipped".into()))
        );
        let error = |text: &str| parse_action(text).map_err(|e| e.to_string()).err();
        assert_eq!(
            error("progress x").as_deref(),
            Some("progress value 'x' is not a number")
        );
        assert_eq!(
            error("progress inf").as_deref(),
            Some("progress value 'inf' is not finite")
        );
        assert_eq!(
            error("stop now").as_deref(),
            Some("'stop' takes no argument (got 'now')")
        );
        assert_eq!(
            error("jump").as_deref(),
            Some(
                "unknown command 'jump' (known: engage, disengage, start, stop, progress, unmark, drop, abort, redo, note, quit)"
            )
        );
        assert_eq!(
            error("note").as_deref(),
            Some("'note' needs a text: note TEXT")
        );
    }

    #[test]
    fn every_key_in_the_key_bar_has_an_action() {
        for key in ['e', ' ', '+', '-', 'p', 'd', 'a', 'r', 'n', 'q'] {
            assert!(key_action(key).is_some(), "{key:?}");
        }
        assert_eq!(key_action('x'), None);
    }
}
