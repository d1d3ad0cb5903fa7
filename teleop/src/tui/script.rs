//! `--script FILE`: timed operator actions, for tests and demos; the grammar both consoles
//! share (each brings its own actions and states: [`crate::console::trial_script`],
//! [`crate::calibrate::calibration_script`]).
//!
//! One action per line, after the time it happens at:
//!
//! ```text
//! # seconds since the console started, or "+S" after the previous line
//! 1.0    engage
//! +0.5   start
//! wait running 10        # wait (at most 10 s) until the console shows this state
//! +2     progress
//! +1.5   stop
//! wait summary 10
//! quit
//! ```
//!
//! A line without a time happens right after the previous one. `wait STATE [TIMEOUT_S]`
//! waits for a state of the console (`waiting_engage`, `ready`, `countdown`, `running`,
//! `summary`, `complete`; default timeout 30 s); a wait that times out stops the console with
//! an error naming the line. Blank lines and `#` comments are ignored.

use std::path::Path;

use crate::tui::TuiError;

/// A state of a console that a script can wait for.
pub trait ScriptState: Copy + PartialEq + std::fmt::Debug {
    /// The state of a name (`running`).
    fn from_name(name: &str) -> Option<Self>;
    /// The state's name.
    fn name(self) -> &'static str;
    /// Every name, for errors.
    fn names() -> String;
}

/// When a line happens.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum At {
    /// Seconds since the console started.
    Absolute(f64),
    /// Seconds after the previous line.
    After(f64),
}

/// What a line does.
#[derive(Debug, Clone, PartialEq)]
pub enum Step<A, S> {
    /// An operator action.
    Act(A),
    /// Wait until the console is in `state`, for at most `timeout_s`.
    Wait {
        /// The state waited for.
        state: S,
        /// Seconds.
        timeout_s: f64,
    },
}

/// One line of a script.
#[derive(Debug, Clone, PartialEq)]
pub struct ScriptLine<A, S> {
    /// 1-based line number in the file.
    pub line: usize,
    /// When.
    pub at: At,
    /// What.
    pub step: Step<A, S>,
}

/// Default `wait` timeout, seconds.
pub const DEFAULT_WAIT_S: f64 = 30.0;

/// A console's command word (in a script or typed on stdin) that it does not take.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum WordError {
    /// An unknown word.
    #[error("unknown command '{word}' (known: {known})")]
    Unknown {
        /// The word given.
        word: String,
        /// The known words.
        known: String,
    },
    /// A word that takes no argument, with one.
    #[error("'{word}' takes no argument (got '{rest}')")]
    TakesNoArgument {
        /// The word.
        word: String,
        /// What followed it.
        rest: String,
    },
}

/// A command line's word and the rest (trimmed): `progress 30` → (`progress`, `30`).
pub fn split_word(text: &str) -> (&str, &str) {
    let text = text.trim();
    text.split_once(char::is_whitespace)
        .map_or((text, ""), |(word, rest)| (word, rest.trim()))
}

/// `action` when nothing follows `word`.
pub fn without_argument<A>(word: &str, rest: &str, action: A) -> Result<A, WordError> {
    if rest.is_empty() {
        Ok(action)
    } else {
        Err(WordError::TakesNoArgument {
            word: word.to_string(),
            rest: rest.to_string(),
        })
    }
}

/// A script line that does not follow the grammar, or a `wait` that timed out while the
/// script played; every variant names its 1-based line.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ScriptError {
    /// A time with nothing after it.
    #[error("{line}: a time without an action (line: {content:?})")]
    TimeWithoutAction {
        /// 1-based line number.
        line: usize,
        /// The line without its comment.
        content: String,
    },
    /// A time that is not seconds in range.
    #[error(
        "{line}: time '{word}' must be seconds in [0, 86400], optionally after '+' (line: {content:?})"
    )]
    Time {
        /// 1-based line number.
        line: usize,
        /// The line without its comment.
        content: String,
        /// The time as written.
        word: String,
    },
    /// `wait` without a state.
    #[error("{line}: 'wait' needs a state (line: {content:?})")]
    WaitWithoutState {
        /// 1-based line number.
        line: usize,
        /// The line without its comment.
        content: String,
    },
    /// A state the console does not have.
    #[error("{line}: unknown state '{name}' (known: {known}) (line: {content:?})")]
    UnknownState {
        /// 1-based line number.
        line: usize,
        /// The line without its comment.
        content: String,
        /// The state as written.
        name: String,
        /// The console's states.
        known: String,
    },
    /// A wait timeout that is not seconds in range.
    #[error(
        "{line}: wait timeout '{timeout}' must be a number of seconds in (0, 3600] (line: {content:?})"
    )]
    WaitTimeout {
        /// 1-based line number.
        line: usize,
        /// The line without its comment.
        content: String,
        /// The timeout as written.
        timeout: String,
    },
    /// Words after a wait's timeout.
    #[error("{line}: unexpected '{extra}' after the wait timeout (line: {content:?})")]
    AfterWait {
        /// 1-based line number.
        line: usize,
        /// The line without its comment.
        content: String,
        /// The first extra word.
        extra: String,
    },
    /// An action the console's parser refused.
    #[error("{line}: {reason} (line: {content:?})")]
    Action {
        /// 1-based line number.
        line: usize,
        /// The line without its comment.
        content: String,
        /// The console's parser's message.
        reason: String,
    },
    /// A `wait` that timed out while the script played.
    #[error(
        "script line {line}: waited {waited_s:.1} s for '{wanted}', the console is still '{state}'"
    )]
    WaitTimedOut {
        /// 1-based line number.
        line: usize,
        /// Seconds waited.
        waited_s: f64,
        /// The state waited for.
        wanted: &'static str,
        /// The console's state.
        state: &'static str,
    },
}

/// Reads and parses a script whose actions `parse_action` reads; errors name the file and the
/// line.
pub fn load_script_with<A, S: ScriptState, E: std::fmt::Display>(
    path: &Path,
    parse_action: impl Fn(&str) -> Result<A, E>,
) -> Result<Vec<ScriptLine<A, S>>, TuiError> {
    let text = std::fs::read_to_string(path).map_err(|source| TuiError::ReadScript {
        path: path.to_path_buf(),
        source,
    })?;
    parse_script_with(&text, parse_action).map_err(|e| TuiError::Script {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })
}

/// Parses a script's text (the grammar above) with the console's actions and states; an
/// error's text is `LINE: reason`.
pub fn parse_script_with<A, S: ScriptState, E: std::fmt::Display>(
    text: &str,
    parse_action: impl Fn(&str) -> Result<A, E>,
) -> Result<Vec<ScriptLine<A, S>>, ScriptError> {
    let mut out = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = raw.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let (at, rest) = match content.split_once(char::is_whitespace) {
            Some((first, rest)) if starts_like_time(first) => {
                let at = parse_time(first).ok_or_else(|| ScriptError::Time {
                    line,
                    content: content.to_string(),
                    word: first.to_string(),
                })?;
                (at, rest.trim())
            }
            _ if starts_like_time(content) => {
                return Err(ScriptError::TimeWithoutAction {
                    line,
                    content: content.to_string(),
                });
            }
            _ => (At::After(0.0), content),
        };
        let step = match rest.strip_prefix("wait") {
            Some(args) => parse_wait(line, content, args)?,
            None => Step::Act(parse_action(rest).map_err(|e| ScriptError::Action {
                line,
                content: content.to_string(),
                reason: e.to_string(),
            })?),
        };
        out.push(ScriptLine { line, at, step });
    }
    Ok(out)
}

/// `wait STATE [TIMEOUT_S]`'s arguments on line `line` (`content`).
fn parse_wait<A, S: ScriptState>(
    line: usize,
    content: &str,
    args: &str,
) -> Result<Step<A, S>, ScriptError> {
    let content = content.to_string();
    let mut words = args.split_whitespace();
    let Some(name) = words.next() else {
        return Err(ScriptError::WaitWithoutState { line, content });
    };
    let Some(state) = S::from_name(name) else {
        return Err(ScriptError::UnknownState {
            line,
            content,
            name: name.to_string(),
            known: S::names(),
        });
    };
    let timeout_s = match words.next() {
        Some(t) => match t.parse::<f64>().ok().filter(|t| *t > 0.0 && *t <= 3600.0) {
            Some(timeout_s) => timeout_s,
            None => {
                return Err(ScriptError::WaitTimeout {
                    line,
                    content,
                    timeout: t.to_string(),
                });
            }
        },
        None => DEFAULT_WAIT_S,
    };
    if let Some(extra) = words.next() {
        return Err(ScriptError::AfterWait {
            line,
            content,
            extra: extra.to_string(),
        });
    }
    Ok(Step::Wait { state, timeout_s })
}

fn starts_like_time(word: &str) -> bool {
    word.starts_with('+') || word.starts_with(|c: char| c.is_ascii_digit() || c == '.')
}

/// `S` or `+S`, seconds in [0, 86400].
fn parse_time(word: &str) -> Option<At> {
    let (relative, number) = match word.strip_prefix('+') {
        Some(n) => (true, n),
        None => (false, word),
    };
    let seconds: f64 = number
        .parse()
        .ok()
        .filter(|s: &f64| s.is_finite() && *s >= 0.0 && *s <= 86_400.0)?;
    Some(if relative {
        At::After(seconds)
    } else {
        At::Absolute(seconds)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::console::keys::Action;
    use crate::console::trial_script::parse_script;
    use crate::console::view::Screen;

    #[test]
    fn a_script_parses_times_actions_and_waits() {
        let script = parse_script(
            "# a session\n1.0 engage\n+0.5 start\nwait running 10\n+2 progress # one notch\nprogress 0.5\nwait summary\nquit\n",
        )
        .unwrap_or_default();
        assert_eq!(script.len(), 7);
        assert_eq!(script[0].at, At::Absolute(1.0));
        assert_eq!(script[0].step, Step::Act(Action::Engage));
        assert_eq!(script[1].at, At::After(0.5));
        assert_eq!(
            script[2].step,
            Step::Wait {
                state: Screen::Running,
                timeout_s: 10.0
            }
        );
        assert_eq!(script[3].line, 5);
        assert_eq!(script[4].step, Step::Act(Action::Progress(Some(0.5))));
        assert_eq!(script[4].at, At::After(0.0));
        assert_eq!(
            script[5].step,
            Step::Wait {
                state: Screen::Summary,
                timeout_s: DEFAULT_WAIT_S
            }
        );
    }

    #[test]
    fn errors_name_the_line_and_what_is_allowed() {
        let error = |text: &str| parse_script(text).unwrap_err().to_string();
        let e = error("engage\n\n-1 start\n");
        assert!(e.starts_with("3: "), "{e}");
        assert_eq!(
            error("+x stop"),
            "1: time '+x' must be seconds in [0, 86400], optionally after '+' (line: \"+x stop\")"
        );
        let e = error("+x stop");
        assert!(e.contains("time '+x'"), "{e}");
        let e = error("wait flying");
        assert!(
            e.contains("unknown state 'flying'") && e.contains("running"),
            "{e}"
        );
        assert!(e.starts_with("1: unknown state 'flying' (known: "), "{e}");
        assert!(e.ends_with(") (line: \"wait flying\")"), "{e}");
        let e = error("wait running 0");
        assert_eq!(
            e,
            "1: wait timeout '0' must be a number of seconds in (0, 3600] (line: \"wait running 0\")"
        );
        assert_eq!(error("wait"), "1: 'wait' needs a state (line: \"wait\")");
        assert_eq!(
            error("wait running 2 x"),
            "1: unexpected 'x' after the wait timeout (line: \"wait running 2 x\")"
        );
        let e = error("2.5");
        assert_eq!(e, "1: a time without an action (line: \"2.5\")");
        let e = error("1 fly");
        assert!(e.starts_with("1: unknown command 'fly' (known: "), "{e}");
        assert!(e.ends_with(") (line: \"1 fly\")"), "{e}");
        assert!(matches!(
            parse_script("1 fly"),
            Err(ScriptError::Action { line: 1, .. })
        ));
    }

    #[test]
    fn file_errors_name_the_file_and_the_line() {
        let dir = std::env::temp_dir().join(format!("pomdar-script-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bad.script");
        std::fs::write(&path, "engage\n1 fly\n").unwrap();
        let e = crate::console::trial_script::load_script(&path).unwrap_err();
        assert!(
            e.to_string()
                .starts_with(&format!("{}:2: unknown command 'fly'", path.display())),
            "{e}"
        );
        let missing = dir.join("missing.script");
        let e = crate::console::trial_script::load_script(&missing).unwrap_err();
        assert!(
            e.to_string()
                .starts_with(&format!("cannot read the script {}: ", missing.display())),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
