//! `pomdar calibrate --script FILE`: timed operator actions for the calibration console, for
//! tests and demos. The grammar of the trial console's scripts ([`crate::console::script`]),
//! with the calibration's words and states:
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

use std::collections::VecDeque;
use std::path::Path;
use std::time::{Duration, Instant};

use crate::calibrate::calibration_view::CalState;
use crate::calibrate::pose_session::CalibrationAction;
use crate::console::script::{At, DEFAULT_WAIT_S};

/// What a line does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CalStep {
    /// An operator action.
    Act(CalibrationAction),
    /// Wait until the console is in `state`, for at most `timeout_s`.
    Wait {
        /// The state waited for.
        state: CalState,
        /// Seconds.
        timeout_s: f64,
    },
}

/// One line of a script.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CalScriptLine {
    /// 1-based line number.
    pub line: usize,
    /// When.
    pub at: At,
    /// What.
    pub step: CalStep,
}

/// The words of script lines and what they do (for errors and `--help`).
pub const CALIBRATION_WORDS: &[(&str, &str)] = &[
    ("accept", "accept the poor capture under review"),
    ("retry", "capture the pose under review again"),
    ("quit", "quit (abandons a session in progress)"),
];

/// Parses a calibration action word.
pub fn parse_calibration_action(word: &str) -> Result<CalibrationAction, String> {
    match word.trim() {
        "accept" => Ok(CalibrationAction::Accept),
        "retry" => Ok(CalibrationAction::Retry),
        "quit" => Ok(CalibrationAction::Quit),
        other => Err(format!(
            "unknown command '{other}' (known: accept, retry, quit, wait STATE [TIMEOUT_S])"
        )),
    }
}

/// Reads and parses a script; errors name the file and the line.
pub fn load_calibration_script(path: &Path) -> anyhow::Result<Vec<CalScriptLine>> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| anyhow::anyhow!("cannot read the script {}: {e}", path.display()))?;
    parse_calibration_script(&text).map_err(|e| anyhow::anyhow!("{}:{e}", path.display()))
}

/// Parses a script's text; an error is `LINE: reason`.
pub fn parse_calibration_script(text: &str) -> Result<Vec<CalScriptLine>, String> {
    let mut out = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = raw.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let fail = |reason: String| format!("{line}: {reason} (line: {content:?})");
        let mut words = content.split_whitespace().peekable();
        let at = match words.peek() {
            Some(w)
                if w.starts_with('+')
                    || w.starts_with(|c: char| c.is_ascii_digit() || c == '.') =>
            {
                let at = parse_time(w).map_err(fail)?;
                words.next();
                at
            }
            _ => At::After(0.0),
        };
        let Some(word) = words.next() else {
            return Err(fail("a time without an action".into()));
        };
        let step = if word == "wait" {
            let name = words
                .next()
                .ok_or_else(|| fail("'wait' needs a state".into()))?;
            let state = CalState::from_name(name).ok_or_else(|| {
                fail(format!(
                    "unknown state '{name}' (known: {})",
                    CalState::ALL.map(CalState::name).join(", ")
                ))
            })?;
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
            CalStep::Wait { state, timeout_s }
        } else {
            CalStep::Act(parse_calibration_action(word).map_err(fail)?)
        };
        if let Some(extra) = words.next() {
            return Err(fail(format!("unexpected '{extra}'")));
        }
        out.push(CalScriptLine { line, at, step });
    }
    Ok(out)
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

/// A script being played.
#[derive(Debug)]
pub struct CalScriptPlayer {
    lines: VecDeque<CalScriptLine>,
    origin: Instant,
    previous: Instant,
    waiting_since: Option<Instant>,
}

impl CalScriptPlayer {
    /// Starts playing `lines` now.
    pub fn new(lines: Vec<CalScriptLine>, now: Instant) -> CalScriptPlayer {
        CalScriptPlayer {
            lines: lines.into(),
            origin: now,
            previous: now,
            waiting_since: None,
        }
    }

    /// Whether every line was played.
    pub fn finished(&self) -> bool {
        self.lines.is_empty()
    }

    /// The next due action at `now` with the console in `state`; an error when a wait timed
    /// out (naming its line).
    pub fn next(
        &mut self,
        state: CalState,
        now: Instant,
    ) -> Result<Option<CalibrationAction>, String> {
        while let Some(line) = self.lines.front().copied() {
            let due = match line.at {
                At::Absolute(s) => self.origin + Duration::from_secs_f64(s),
                At::After(s) => self.previous + Duration::from_secs_f64(s),
            };
            if now < due {
                return Ok(None);
            }
            match line.step {
                CalStep::Act(action) => {
                    self.lines.pop_front();
                    self.previous = now;
                    return Ok(Some(action));
                }
                CalStep::Wait {
                    state: wanted,
                    timeout_s,
                } => {
                    if wanted == state {
                        self.lines.pop_front();
                        self.previous = now;
                        self.waiting_since = None;
                        continue;
                    }
                    let since = *self.waiting_since.get_or_insert(now);
                    let waited = now.duration_since(since).as_secs_f64();
                    if waited > timeout_s {
                        return Err(format!(
                            "script line {}: waited {waited:.1} s for '{}', the console is still '{}'",
                            line.line,
                            wanted.name(),
                            state.name()
                        ));
                    }
                    return Ok(None);
                }
            }
        }
        Ok(None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_script_parses_and_errors_name_the_line() {
        let s = parse_calibration_script(
            "# retry the bad pose\nwait review 60\nretry\n+0.5 accept\nwait complete\n2 quit\n",
        )
        .unwrap();
        assert_eq!(s.len(), 5);
        assert_eq!(
            s[0].step,
            CalStep::Wait {
                state: CalState::Review,
                timeout_s: 60.0
            }
        );
        assert_eq!(s[1].step, CalStep::Act(CalibrationAction::Retry));
        assert_eq!(s[2].at, At::After(0.5));
        assert_eq!(s[3].line, 5);
        assert_eq!(s[4].at, At::Absolute(2.0));
        let e = parse_calibration_script("retry\nengage\n").unwrap_err();
        assert!(
            e.starts_with("2: ") && e.contains("unknown command 'engage'"),
            "{e}"
        );
        let e = parse_calibration_script("wait running").unwrap_err();
        assert!(
            e.contains("unknown state 'running'") && e.contains("review"),
            "{e}"
        );
        assert!(parse_calibration_script("1.5").is_err());
        assert!(parse_calibration_script("retry now").is_err());
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
        let e = p.next(CalState::Fitting, at(2.0)).unwrap_err();
        assert!(e.contains("line 1") && e.contains("'complete'"), "{e}");
    }
}
