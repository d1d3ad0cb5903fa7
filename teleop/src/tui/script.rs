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

/// Reads and parses a script whose actions `parse_action` reads; errors name the file and the
/// line.
pub fn load_script_with<A, S: ScriptState>(
    path: &Path,
    parse_action: impl Fn(&str) -> Result<A, String>,
) -> Result<Vec<ScriptLine<A, S>>, TuiError> {
    let text = std::fs::read_to_string(path).map_err(|source| TuiError::ReadScript {
        path: path.to_path_buf(),
        source,
    })?;
    parse_script_with(&text, parse_action).map_err(|reason| TuiError::Script {
        path: path.to_path_buf(),
        reason,
    })
}

/// Parses a script's text (the grammar above) with the console's actions and states; an error
/// is `LINE: reason`.
pub fn parse_script_with<A, S: ScriptState>(
    text: &str,
    parse_action: impl Fn(&str) -> Result<A, String>,
) -> Result<Vec<ScriptLine<A, S>>, String> {
    let mut out = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = raw.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let fail = |reason: String| format!("{line}: {reason} (line: {content:?})");
        let (at, rest) = match content.split_once(char::is_whitespace) {
            Some((first, rest)) if starts_like_time(first) => {
                (parse_time(first).map_err(fail)?, rest.trim())
            }
            _ if starts_like_time(content) => {
                return Err(fail("a time without an action".into()));
            }
            _ => (At::After(0.0), content),
        };
        let step = if let Some(args) = rest.strip_prefix("wait") {
            let mut words = args.split_whitespace();
            let name = words
                .next()
                .ok_or_else(|| fail("'wait' needs a state".into()))?;
            let state = S::from_name(name)
                .ok_or_else(|| fail(format!("unknown state '{name}' (known: {})", S::names())))?;
            let timeout_s = match words.next() {
                Some(t) => t
                    .parse::<f64>()
                    .ok()
                    .filter(|t| *t > 0.0 && *t <= 3600.0)
                    .ok_or_else(|| {
                        fail(format!(
                            "wait timeout '{t}' must be a number of seconds in (0, 3600]"
                        ))
                    })?,
                None => DEFAULT_WAIT_S,
            };
            if let Some(extra) = words.next() {
                return Err(fail(format!("unexpected '{extra}' after the wait timeout")));
            }
            Step::Wait { state, timeout_s }
        } else {
            Step::Act(parse_action(rest).map_err(fail)?)
        };
        out.push(ScriptLine { line, at, step });
    }
    Ok(out)
}

fn starts_like_time(word: &str) -> bool {
    word.starts_with('+') || word.starts_with(|c: char| c.is_ascii_digit() || c == '.')
}

fn parse_time(word: &str) -> Result<At, String> {
    let (relative, number) = match word.strip_prefix('+') {
        Some(n) => (true, n),
        None => (false, word),
    };
    let seconds: f64 = number
        .parse()
        .ok()
        .filter(|s: &f64| s.is_finite() && *s >= 0.0 && *s <= 86_400.0)
        .ok_or_else(|| {
            format!("time '{word}' must be seconds in [0, 86400], optionally after '+'")
        })?;
    Ok(if relative {
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
        let e = parse_script("engage\n\n-1 start\n").unwrap_err();
        assert!(e.starts_with("3: "), "{e}");
        let e = parse_script("+x stop").unwrap_err();
        assert!(e.contains("time '+x'"), "{e}");
        let e = parse_script("wait flying").unwrap_err();
        assert!(
            e.contains("unknown state 'flying'") && e.contains("running"),
            "{e}"
        );
        let e = parse_script("wait running 0").unwrap_err();
        assert!(e.contains("(0, 3600]"), "{e}");
        let e = parse_script("2.5").unwrap_err();
        assert!(e.contains("without an action"), "{e}");
        let e = parse_script("1 fly").unwrap_err();
        assert!(e.contains("unknown command 'fly'"), "{e}");
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
