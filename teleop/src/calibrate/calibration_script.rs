//! `pomdar calibrate --script FILE`: timed operator actions for the calibration console, for
//! tests and demos. The consoles' script grammar and player ([`crate::tui::script`],
//! [`crate::tui::script_player`]) with the calibration's words and states:
//!
//! ```text
//! # seconds since the console started, or "+S" after the previous line
//! wait review 60        # wait (at most 60 s) until a capture waits for a decision
//! retry                 # capture that pose again
//! wait review 60
//! +0.5 accept           # accept a poor capture
//! wait complete 300
//! quit
//! ```
//!
//! Words: `accept` (space / Enter), `retry` (r), `quit` (q). States for `wait`:
//! `waiting_glove`, `settling`, `capturing`, `review`, `fitting`, `complete`, `failed`
//! (default timeout 30 s; a wait that times out stops the session with an error naming the
//! line). A line without a time happens right after the previous one; blank lines and `#`
//! comments are ignored.

use std::path::Path;

use crate::calibrate::CalibrateError;
use crate::calibrate::calibration_view::CalState;
use crate::calibrate::pose_session::CalibrationAction;
use crate::tui::script::{
    ScriptError, ScriptLine, ScriptState, WordError, load_script_with, parse_script_with,
    split_word, without_argument,
};
use crate::tui::script_player::ScriptPlayer;

/// One line of a calibration script.
pub type CalScriptLine = ScriptLine<CalibrationAction, CalState>;

/// A calibration script being played.
pub type CalScriptPlayer = ScriptPlayer<CalibrationAction, CalState>;

impl ScriptState for CalState {
    fn from_name(name: &str) -> Option<CalState> {
        CalState::from_name(name)
    }

    fn name(self) -> &'static str {
        CalState::name(self)
    }

    fn names() -> String {
        CalState::ALL.map(CalState::name).join(", ")
    }
}

/// The words of script lines and what they do.
pub const CALIBRATION_WORDS: &[(&str, &str)] = &[
    ("accept", "accept the poor capture under review"),
    ("retry", "capture the pose under review again"),
    ("quit", "quit (abandons a session in progress)"),
];

/// Parses a calibration action word.
pub fn parse_calibration_action(text: &str) -> Result<CalibrationAction, CalibrateError> {
    let (word, rest) = split_word(text);
    let action = match word {
        "accept" => CalibrationAction::Accept,
        "retry" => CalibrationAction::Retry,
        "quit" => CalibrationAction::Quit,
        other => {
            let mut known: Vec<&str> = CALIBRATION_WORDS.iter().map(|(w, _)| *w).collect();
            known.push("wait STATE [TIMEOUT_S]");
            return Err(WordError::Unknown {
                word: other.to_string(),
                known: known.join(", "),
            }
            .into());
        }
    };
    Ok(without_argument(word, rest, action)?)
}

/// Reads and parses a script; errors name the file and the line.
pub fn load_calibration_script(path: &Path) -> Result<Vec<CalScriptLine>, CalibrateError> {
    Ok(load_script_with(path, parse_calibration_action)?)
}

/// Parses a script's text; an error's text is `LINE: reason`.
pub fn parse_calibration_script(text: &str) -> Result<Vec<CalScriptLine>, ScriptError> {
    parse_script_with(text, parse_calibration_action)
}

#[cfg(test)]
mod tests {
    use std::time::{Duration, Instant};

    use super::*;
    use crate::tui::script::{At, Step};

    #[test]
    fn a_script_parses_and_errors_name_the_line() {
        let s = parse_calibration_script(
            "# retry the bad pose\nwait review 60\nretry\n+0.5 accept\nwait complete\n2 quit\n",
        )
        .unwrap();
        assert_eq!(s.len(), 5);
        assert_eq!(
            s[0].step,
            Step::Wait {
                state: CalState::Review,
                timeout_s: 60.0
            }
        );
        assert_eq!(s[1].step, Step::Act(CalibrationAction::Retry));
        assert_eq!(s[2].at, At::After(0.5));
        assert_eq!(s[3].line, 5);
        assert_eq!(s[4].at, At::Absolute(2.0));
        let e = parse_calibration_script("retry\nengage\n")
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "2: unknown command 'engage' (known: accept, retry, quit, wait STATE [TIMEOUT_S]) (line: \"engage\")"
        );
        let e = parse_calibration_script("wait running")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("unknown state 'running'") && e.contains("review"),
            "{e}"
        );
        assert!(parse_calibration_script("1.5").is_err());
        let e = parse_calibration_script("retry now")
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "1: 'retry' takes no argument (got 'now') (line: \"retry now\")"
        );
    }

    #[test]
    fn lines_play_when_due_and_waits_follow_the_state() {
        let t0 = Instant::now();
        let at = |s: f64| t0 + Duration::from_secs_f64(s);
        let lines = parse_calibration_script("wait review 5\n+1 retry\n").unwrap();
        let mut p = CalScriptPlayer::new(lines, t0);
        assert_eq!(p.next(CalState::Capturing, at(1.0)), Ok(None));
        assert_eq!(p.next(CalState::Review, at(2.0)), Ok(None));
        assert_eq!(
            p.next(CalState::Review, at(3.0)),
            Ok(Some(CalibrationAction::Retry))
        );
        assert!(p.finished());
        let lines = parse_calibration_script("wait complete 1\n").unwrap();
        let mut p = CalScriptPlayer::new(lines, t0);
        assert_eq!(p.next(CalState::Fitting, at(0.0)), Ok(None));
        let e = p.next(CalState::Fitting, at(2.0)).unwrap_err().to_string();
        assert!(e.contains("line 1") && e.contains("'complete'"), "{e}");
    }
}
