//! `pomdar hand-check --script FILE` (and words typed on stdin): the consoles' script grammar
//! and player ([`crate::tui::script`]) with the hand check's answers and phases:
//!
//! ```text
//! wait asking 30     # wait (at most 30 s) until the first joint has moved
//! yes                # it moved as named
//! wait asking 30
//! no                 # it moved the other way …
//! flip               # … flip its sign and move it again
//! wait asking 30
//! yes
//! quit
//! ```
//!
//! Words: `yes` (y), `no` (n), `repeat` (r), `flip` (f), `keep` (k), `quit` (q). Phases for
//! `wait`: `settling`, `moving`, `asking`, `offer_flip`, `complete`, `quit`.

use std::path::Path;

use crate::hand_check::HandCheckError;
use crate::hand_check::session::{Answer, CheckPhase};
use crate::tui::script::{
    ScriptError, ScriptLine, ScriptState, WordError, load_script_with, parse_script_with,
    split_word, without_argument,
};
use crate::tui::script_player::ScriptPlayer;

/// One line of a hand-check script.
pub type CheckScriptLine = ScriptLine<Answer, CheckPhase>;

/// A hand-check script being played.
pub type CheckScriptPlayer = ScriptPlayer<Answer, CheckPhase>;

impl ScriptState for CheckPhase {
    fn from_name(name: &str) -> Option<CheckPhase> {
        CheckPhase::from_name(name)
    }

    fn name(self) -> &'static str {
        CheckPhase::name(self)
    }

    fn names() -> String {
        CheckPhase::ALL.map(CheckPhase::name).join(", ")
    }
}

/// The words, their one-letter forms and what they do.
pub const ANSWER_WORDS: &[(&str, &str, Answer, &str)] = &[
    ("yes", "y", Answer::Yes, "the joint moved as named"),
    (
        "no",
        "n",
        Answer::No,
        "it moved the other way (then: flip or keep)",
    ),
    ("repeat", "r", Answer::Repeat, "move it again"),
    (
        "flip",
        "f",
        Answer::Flip,
        "after no: flip its sign and move it again",
    ),
    (
        "keep",
        "k",
        Answer::Keep,
        "after no: keep its sign and move it again",
    ),
    (
        "quit",
        "q",
        Answer::Quit,
        "stop (nothing is written unless every joint was confirmed)",
    ),
];

/// Parses an answer word.
pub fn parse_answer(text: &str) -> Result<Answer, WordError> {
    let (word, rest) = split_word(text);
    let Some((_, _, answer, _)) = ANSWER_WORDS
        .iter()
        .find(|(long, short, _, _)| word == *long || word == *short)
    else {
        let mut known: Vec<&str> = ANSWER_WORDS.iter().map(|w| w.0).collect();
        known.push("wait STATE [TIMEOUT_S]");
        return Err(WordError::Unknown {
            word: word.to_string(),
            known: known.join(", "),
        });
    };
    without_argument(word, rest, *answer)
}

/// Reads and parses a script; errors name the file and the line.
pub fn load_check_script(path: &Path) -> Result<Vec<CheckScriptLine>, HandCheckError> {
    Ok(load_script_with(path, parse_answer)?)
}

/// Parses a script's text; an error's text is `LINE: reason`.
pub fn parse_check_script(text: &str) -> Result<Vec<CheckScriptLine>, ScriptError> {
    parse_script_with(text, parse_answer)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tui::script::Step;

    #[test]
    fn answers_and_waits_parse_and_errors_name_the_line() {
        let s = parse_check_script("wait asking 30\ny\n+0.5 no\nflip\nwait offer_flip\nquit\n")
            .unwrap();
        assert_eq!(s.len(), 6);
        assert_eq!(
            s[0].step,
            Step::Wait {
                state: CheckPhase::Asking,
                timeout_s: 30.0
            }
        );
        assert_eq!(s[1].step, Step::Act(Answer::Yes));
        assert_eq!(s[2].step, Step::Act(Answer::No));
        assert_eq!(s[3].step, Step::Act(Answer::Flip));
        let e = parse_check_script("yes\nengage\n").unwrap_err().to_string();
        assert_eq!(
            e,
            "2: unknown command 'engage' (known: yes, no, repeat, flip, keep, quit, wait STATE [TIMEOUT_S]) (line: \"engage\")"
        );
        let e = parse_check_script("wait running").unwrap_err().to_string();
        assert!(
            e.contains("unknown state 'running'") && e.contains("offer_flip"),
            "{e}"
        );
    }
}
