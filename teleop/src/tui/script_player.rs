//! Playing a `--script` against the running console: each line when it is due, waits checked
//! against the console's state.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use super::script::{At, ScriptError, ScriptLine, ScriptState, Step};

/// A script being played: actions `A`, waits on states `S`.
#[derive(Debug)]
pub struct ScriptPlayer<A, S> {
    lines: VecDeque<ScriptLine<A, S>>,
    origin: Instant,
    previous: Instant,
    waiting_since: Option<Instant>,
}

impl<A: Clone, S: ScriptState> ScriptPlayer<A, S> {
    /// Starts playing `lines` now.
    pub fn new(lines: Vec<ScriptLine<A, S>>, now: Instant) -> ScriptPlayer<A, S> {
        ScriptPlayer {
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
    pub fn next(&mut self, state: S, now: Instant) -> Result<Option<A>, ScriptError> {
        while let Some(line) = self.lines.front() {
            let due = match line.at {
                At::Absolute(s) => self.origin + Duration::from_secs_f64(s),
                At::After(s) => self.previous + Duration::from_secs_f64(s),
            };
            if now < due {
                return Ok(None);
            }
            match &line.step {
                Step::Act(action) => {
                    let action = action.clone();
                    self.lines.pop_front();
                    self.previous = now;
                    return Ok(Some(action));
                }
                Step::Wait {
                    state: wanted,
                    timeout_s,
                } => {
                    if *wanted == state {
                        self.lines.pop_front();
                        self.previous = now;
                        self.waiting_since = None;
                        continue;
                    }
                    let since = *self.waiting_since.get_or_insert(now);
                    let waited = now.duration_since(since).as_secs_f64();
                    if waited > *timeout_s {
                        return Err(ScriptError::WaitTimedOut {
                            line: line.line,
                            waited_s: waited,
                            wanted: wanted.name(),
                            state: state.name(),
                        });
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
    use crate::console::keys::Action;
    use crate::console::trial_script::parse_script;
    use crate::console::view::Screen;

    #[test]
    fn lines_play_when_due_and_waits_follow_the_screen() {
        let t0 = Instant::now();
        let lines = parse_script("1 engage\nwait ready 2\n+0.5 start\n").unwrap_or_default();
        let mut p = ScriptPlayer::new(lines, t0);
        let at = |s: f64| t0 + Duration::from_secs_f64(s);
        assert_eq!(p.next(Screen::WaitingEngage, at(0.5)), Ok(None));
        assert_eq!(
            p.next(Screen::WaitingEngage, at(1.0)),
            Ok(Some(Action::Engage))
        );
        assert_eq!(p.next(Screen::WaitingEngage, at(1.2)), Ok(None));
        assert_eq!(p.next(Screen::Ready, at(1.4)), Ok(None));
        assert_eq!(p.next(Screen::Ready, at(1.9)), Ok(Some(Action::Start)));
        assert!(p.finished());

        let lines = parse_script("wait running 1\n").unwrap_or_default();
        let mut p = ScriptPlayer::new(lines, t0);
        assert_eq!(p.next(Screen::Ready, at(0.0)), Ok(None));
        let e = p.next(Screen::Ready, at(1.5)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "script line 1: waited 1.5 s for 'running', the console is still 'ready'"
        );
    }
}
