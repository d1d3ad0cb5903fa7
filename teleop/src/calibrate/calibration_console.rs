//! The calibration console's front: the full-screen console on a terminal (the trial
//! console's [`FullScreen`] and keys), the line console otherwise, and a `--script` played
//! against either. The session node asks it for the operator's actions and shows the
//! session through it.
//!
//! Keys: `r` retries the pose under review, space or Enter accepts a poor capture, `q` quits,
//! Ctrl-C interrupts. The line console does not read stdin: without a script nobody is there
//! to decide, so poor captures are accepted and bad ones retried automatically.

use std::time::Instant;

use calibration::FitProgress;
use tokio::sync::mpsc;

use crate::calibrate::CalibrateError;
use crate::calibrate::calibration_screen::draw_calibration;
use crate::calibrate::calibration_script::{CalScriptLine, CalScriptPlayer};
use crate::calibrate::calibration_view::{CalState, CalibrationView, PlainCalibrationOutput};
use crate::calibrate::pose_session::{
    AUTOMATIC_MAX_ATTEMPTS, CalibrationAction, Policy, PoseSession,
};
use crate::calibrate::progress_bar::ProgressBar;
use crate::tui::script::ScriptError;
use crate::tui::terminal::{FullScreen, Input, full_screen_wanted};

/// What the operator's side asks of the session.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrontAction {
    /// An action on the session.
    Act(CalibrationAction),
    /// Ctrl-C.
    Interrupt,
}

enum Display {
    Full(FullScreen),
    Plain {
        out: PlainCalibrationOutput,
        bar: Option<ProgressBar>,
        shown_progress: Option<FitProgress>,
    },
}

/// The console's front.
pub struct ConsoleFront {
    display: Display,
    inputs: mpsc::UnboundedReceiver<Input>,
    _keep_open: mpsc::UnboundedSender<Input>,
    player: Option<CalScriptPlayer>,
    started: Instant,
    setup: Vec<(String, String)>,
    results: Vec<String>,
}

impl std::fmt::Debug for ConsoleFront {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("ConsoleFront")
    }
}

impl ConsoleFront {
    /// Full-screen when stdin and stdout are terminals (and not `plain`), else lines on
    /// stderr; `script` plays timed actions; `setup` is shown beside the poses.
    pub fn open(
        plain: bool,
        script: Option<Vec<CalScriptLine>>,
        setup: Vec<(String, String)>,
    ) -> Result<ConsoleFront, CalibrateError> {
        let (tx, inputs) = mpsc::unbounded_channel();
        let full = full_screen_wanted(plain);
        let display = if full {
            Display::Full(FullScreen::enter(tx.clone())?)
        } else {
            Display::Plain {
                out: PlainCalibrationOutput::default(),
                bar: None,
                shown_progress: None,
            }
        };
        Ok(ConsoleFront {
            display,
            inputs,
            _keep_open: tx,
            player: script.map(|s| CalScriptPlayer::new(s, Instant::now())),
            started: Instant::now(),
            setup,
            results: Vec::new(),
        })
    }

    /// Who decides about captures that are not good: the operator when there are keys or a
    /// script, else nobody.
    pub fn policy(&self) -> Policy {
        match (&self.display, &self.player) {
            (Display::Full(_), _) | (_, Some(_)) => Policy::Operator,
            (Display::Plain { .. }, None) => Policy::Automatic {
                max_attempts: AUTOMATIC_MAX_ATTEMPTS,
            },
        }
    }

    /// Whether the console is full-screen.
    pub fn full_screen(&self) -> bool {
        matches!(self.display, Display::Full(_))
    }

    /// Whether a script was given and every line of it was played.
    pub fn script_finished(&self) -> Option<bool> {
        self.player.as_ref().map(CalScriptPlayer::finished)
    }

    /// The next key (never returns without a terminal).
    pub async fn next_input(&mut self) -> Option<Input> {
        self.inputs.recv().await
    }

    /// The action of a key.
    pub fn key_action(input: &Input) -> Option<FrontAction> {
        Some(match input {
            Input::CtrlC => FrontAction::Interrupt,
            Input::Char('r' | 'R') => FrontAction::Act(CalibrationAction::Retry),
            Input::Char(' ') | Input::Enter => FrontAction::Act(CalibrationAction::Accept),
            Input::Char('q' | 'Q') => FrontAction::Act(CalibrationAction::Quit),
            _ => return None,
        })
    }

    /// The script's due action in `state`; an error when a wait timed out.
    pub fn script_action(
        &mut self,
        state: CalState,
    ) -> Result<Option<CalibrationAction>, ScriptError> {
        match self.player.as_mut() {
            Some(p) => p.next(state, Instant::now()),
            None => Ok(None),
        }
    }

    /// The fit's table and where the profile went, for the results pane.
    pub fn set_results(&mut self, lines: Vec<String>) {
        self.results = lines;
    }

    /// Shows the session at `now_ns`.
    pub fn show(&mut self, session: &PoseSession, now_ns: i64) -> Result<(), CalibrateError> {
        let view = CalibrationView::build(session, &self.setup, &self.results, now_ns);
        match &mut self.display {
            Display::Full(screen) => screen.draw(|frame| draw_calibration(frame, &view))?,
            Display::Plain {
                out,
                bar,
                shown_progress,
            } => {
                out.update(&view, session.said(), self.started.elapsed().as_secs_f64());
                let progress = session.fit_progress();
                if progress != *shown_progress
                    && let Some(p) = progress
                {
                    bar.get_or_insert_with(ProgressBar::new).update(p);
                    *shown_progress = progress;
                }
                if view.state != CalState::Fitting
                    && let Some(mut b) = bar.take()
                {
                    b.finish();
                }
            }
        }
        Ok(())
    }
}
