//! The terminal: full-screen mode (raw input, alternate screen, restored on every exit
//! including a panic), the keyboard read on its own thread, and stdin lines for the line
//! console.

use std::io::{BufRead as _, IsTerminal as _};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use ratatui::crossterm::event::{self, Event, KeyCode, KeyEventKind, KeyModifiers};
use tokio::sync::mpsc;

use crate::tui::TuiError;

/// Input from the operator.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Input {
    /// A character key.
    Char(char),
    /// Enter.
    Enter,
    /// Escape.
    Escape,
    /// Backspace.
    Backspace,
    /// Ctrl-C.
    CtrlC,
    /// A line typed on stdin (line console).
    Line(String),
    /// stdin was closed (line console).
    Closed,
}

/// Whether a console should be full-screen: stdin and stdout are terminals and the operator
/// did not ask for `--plain`.
pub fn full_screen_wanted(plain: bool) -> bool {
    !plain && std::io::stdin().is_terminal() && std::io::stdout().is_terminal()
}

/// The full-screen terminal; restores the terminal when dropped.
pub struct FullScreen {
    terminal: ratatui::DefaultTerminal,
    stop_keys: Arc<AtomicBool>,
}

impl std::fmt::Debug for FullScreen {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("FullScreen")
    }
}

impl FullScreen {
    /// Enters full-screen mode and starts reading keys into `keys`.
    pub fn enter(keys: mpsc::UnboundedSender<Input>) -> Result<FullScreen, TuiError> {
        // ratatui::init restores the terminal on a panic as well.
        let terminal = ratatui::try_init().map_err(|source| TuiError::FullScreen { source })?;
        let stop_keys = Arc::new(AtomicBool::new(false));
        let stop = stop_keys.clone();
        std::thread::Builder::new()
            .name("console-keys".into())
            .spawn(move || read_keys(&keys, &stop))
            .map_err(|source| TuiError::InputThread {
                thread: "console-keys",
                source,
            })?;
        Ok(FullScreen {
            terminal,
            stop_keys,
        })
    }

    /// Draws a frame.
    pub fn draw(&mut self, render: impl FnOnce(&mut ratatui::Frame<'_>)) -> Result<(), TuiError> {
        self.terminal
            .draw(render)
            .map_err(|source| TuiError::Draw { source })?;
        Ok(())
    }
}

impl Drop for FullScreen {
    fn drop(&mut self) {
        self.stop_keys.store(true, Ordering::Relaxed);
        ratatui::restore();
    }
}

fn read_keys(keys: &mpsc::UnboundedSender<Input>, stop: &AtomicBool) {
    while !stop.load(Ordering::Relaxed) {
        match event::poll(Duration::from_millis(100)) {
            Ok(true) => {}
            Ok(false) => continue,
            Err(_) => return,
        }
        let Ok(Event::Key(key)) = event::read() else {
            continue;
        };
        if key.kind == KeyEventKind::Release {
            continue;
        }
        let input = match key.code {
            KeyCode::Char('c') if key.modifiers.contains(KeyModifiers::CONTROL) => Input::CtrlC,
            KeyCode::Char(c) => Input::Char(c),
            KeyCode::Enter => Input::Enter,
            KeyCode::Esc => Input::Escape,
            KeyCode::Backspace => Input::Backspace,
            _ => continue,
        };
        if keys.send(input).is_err() {
            return;
        }
    }
}

/// Reads stdin lines into `lines` on a thread (the line console); [`Input::Closed`] at the end.
pub fn read_stdin_lines(lines: mpsc::UnboundedSender<Input>) -> Result<(), TuiError> {
    std::thread::Builder::new()
        .name("console-stdin".into())
        .spawn(move || {
            for line in std::io::stdin().lock().lines() {
                let Ok(line) = line else { break };
                if lines.send(Input::Line(line)).is_err() {
                    return;
                }
            }
            lines.send(Input::Closed).ok();
        })
        .map_err(|source| TuiError::InputThread {
            thread: "console-stdin",
            source,
        })?;
    Ok(())
}
