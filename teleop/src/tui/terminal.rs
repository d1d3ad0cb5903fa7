//! The terminal: full-screen mode (raw input, alternate screen, restored on every exit
//! including a panic), the keyboard read on its own thread, and stdin lines for the line
//! console.

use std::io::{BufRead as _, IsTerminal as _};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
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

/// Where stdin's lines go: the console reading them now, and lines that came while none was
/// (between the tasks of a study), handed to the next.
#[derive(Default)]
struct StdinRoute {
    target: Option<mpsc::UnboundedSender<Input>>,
    pending: Vec<Input>,
}

impl StdinRoute {
    fn deliver(&mut self, input: Input) {
        match &self.target {
            Some(target) => {
                if let Err(unsent) = target.send(input) {
                    self.target = None;
                    self.pending.push(unsent.0);
                }
            }
            None => self.pending.push(input),
        }
    }
}

static STDIN_ROUTE: Mutex<Option<StdinRoute>> = Mutex::new(None);

/// Reads stdin lines into `lines` (the line console); [`Input::Closed`] at the end. stdin is
/// read by one thread for the whole process: a later console (the next task of a study) takes
/// the lines over, with any typed while no console was reading.
pub fn read_stdin_lines(lines: mpsc::UnboundedSender<Input>) -> Result<(), TuiError> {
    let mut route = STDIN_ROUTE
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let started = route.is_some();
    let route = route.get_or_insert_with(StdinRoute::default);
    route.target = Some(lines);
    for input in std::mem::take(&mut route.pending) {
        route.deliver(input);
    }
    if started {
        return Ok(());
    }
    let forward = |input: Input| {
        let mut route = STDIN_ROUTE
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(route) = route.as_mut() {
            route.deliver(input);
        }
    };
    std::thread::Builder::new()
        .name("console-stdin".into())
        .spawn(move || {
            for line in std::io::stdin().lock().lines() {
                let Ok(line) = line else { break };
                forward(Input::Line(line));
            }
            forward(Input::Closed);
        })
        .map_err(|source| TuiError::InputThread {
            thread: "console-stdin",
            source,
        })?;
    Ok(())
}
