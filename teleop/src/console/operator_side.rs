//! The operator's side of the trial console: where it shows itself (full-screen, or lines
//! without a terminal), where the actions come from (keys, stdin lines, a `--script`), and the
//! prompt being typed for a progress value or a note.

use std::time::Instant;

use tokio::sync::mpsc;

use super::keys::{Action, key_action, parse_action};
use super::plain_output::PlainOutput;
use super::screen::draw;
use super::session_state::Session;
use super::trial_script::TrialScriptLine;
use super::view::{ConsoleView, Screen};
use crate::tui::TuiError;
use crate::tui::script_player::ScriptPlayer;
use crate::tui::terminal::{FullScreen, Input, full_screen_wanted, read_stdin_lines};

/// Where the console's actions come from and where it shows itself.
pub(super) enum Display {
    Full(FullScreen),
    Plain(PlainOutput),
}

/// A prompt being typed in the full-screen console.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Prompt {
    Progress,
    Note,
}

/// The operator's side: where the console shows itself and where its actions come from.
pub(super) struct OperatorSide {
    pub(super) display: Display,
    /// Whether the console is full-screen (a keyboard says q).
    pub(super) full_screen: bool,
    /// Keys, or lines of stdin.
    pub(super) input_rx: mpsc::UnboundedReceiver<Input>,
    _keep_open: mpsc::UnboundedSender<Input>,
    /// `--script`.
    pub(super) player: Option<ScriptPlayer<Action, Screen>>,
    pub(super) scripted: bool,
    /// A prompt being typed (full-screen).
    pub(super) prompt: Option<(Prompt, String)>,
    /// When the console started (the line console's time).
    started: Instant,
}

impl OperatorSide {
    /// Full-screen when wanted (not `plain`, on a terminal), else lines; the line console
    /// without a script reads commands from stdin.
    pub(super) fn open(
        plain: bool,
        script: Option<Vec<TrialScriptLine>>,
    ) -> Result<OperatorSide, TuiError> {
        let (input_tx, input_rx) = mpsc::unbounded_channel();
        let full_screen = full_screen_wanted(plain);
        let display = if full_screen {
            Display::Full(FullScreen::enter(input_tx.clone())?)
        } else {
            if script.is_none() {
                read_stdin_lines(input_tx.clone())?;
                eprintln!(
                    "pomdar trial: line console; type commands, one per line: {}",
                    super::keys::ACTION_WORDS
                        .iter()
                        .map(|(w, _)| *w)
                        .collect::<Vec<_>>()
                        .join(", ")
                );
            }
            Display::Plain(PlainOutput::default())
        };
        let player = script.map(|s| ScriptPlayer::new(s, Instant::now()));
        let scripted = player.is_some();
        Ok(OperatorSide {
            display,
            full_screen,
            input_rx,
            _keep_open: input_tx,
            player,
            scripted,
            prompt: None,
            started: Instant::now(),
        })
    }

    /// Draws the session full-screen (with the prompt being typed) or prints what changed.
    pub(super) fn show(&mut self, session: &Session, now: i64) -> Result<(), TuiError> {
        let flow = &session.flow;
        let view = ConsoleView::build(flow, &session.health, &session.info, now);
        match &mut self.display {
            Display::Full(screen) => {
                let typed_text = self.prompt.as_ref().map(|(kind, text)| match kind {
                    Prompt::Progress => {
                        format!("progress ({}): {text}", flow.kind().progress_unit())
                    }
                    Prompt::Note => format!("note: {text}"),
                });
                screen.draw(|frame| draw(frame, &view, typed_text.as_deref()))?;
            }
            Display::Plain(out) => {
                out.update(&view, flow.said(), self.started.elapsed().as_secs_f64());
            }
        }
        Ok(())
    }
}

/// A key in the full-screen console: typed into the prompt if one is open.
pub(super) fn typed(prompt: &mut Option<(Prompt, String)>, key: Input) -> Option<Action> {
    let Some((kind, text)) = prompt.as_mut() else {
        return match key {
            Input::Char(c) => key_action(c),
            _ => None,
        };
    };
    match key {
        Input::Char(c) => {
            text.push(c);
            None
        }
        Input::Backspace => {
            text.pop();
            None
        }
        Input::Escape => {
            *prompt = None;
            None
        }
        Input::Enter => {
            let (kind, text) = (*kind, text.trim().to_string());
            *prompt = None;
            if text.is_empty() {
                return None;
            }
            match kind {
                Prompt::Note => Some(Action::Note(text)),
                // A value that is not a number becomes a progress mark the session refuses
                // with a message, so a typo is seen, not dropped.
                Prompt::Progress => Some(
                    parse_action(&format!("progress {text}"))
                        .unwrap_or(Action::Progress(Some(f64::NAN))),
                ),
            }
        }
        _ => None,
    }
}
