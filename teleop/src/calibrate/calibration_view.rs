//! What the calibration console shows: the view as data is the core crate's
//! (`consoles::calibrate::calibration_view`, re-exported here); the full-screen console draws it
//! ([`super::calibration_screen`]), the line console prints its changes
//! ([`PlainCalibrationOutput`]).

pub use consoles::calibrate::calibration_view::{CalState, CalibrationView, quality_level};

/// The line console: a line for each change of state and each message, on stderr.
#[derive(Debug, Default)]
pub struct PlainCalibrationOutput {
    state: Option<CalState>,
    said: u64,
}

impl PlainCalibrationOutput {
    /// Prints what changed since the last call, with the console's time `t_s`; `said` is the
    /// number of messages said so far.
    pub fn update(&mut self, view: &CalibrationView, said: u64, t_s: f64) {
        let new = usize::try_from(said.saturating_sub(self.said)).unwrap_or(usize::MAX);
        let shown = view.messages.len();
        for message in &view.messages[shown.saturating_sub(new)..] {
            eprintln!("[{t_s:7.1} s] {message}");
        }
        self.said = said;
        if self.state != Some(view.state) {
            if matches!(
                view.state,
                CalState::Capturing | CalState::Review | CalState::Fitting | CalState::Failed
            ) {
                eprintln!(
                    "[{t_s:7.1} s]   {}{}",
                    view.state.banner(),
                    view.detail
                        .first()
                        .map(|d| format!(" · {d}"))
                        .unwrap_or_default()
                );
            }
            self.state = Some(view.state);
        }
    }
}
