//! The fit once the session is recorded: run in a blocking task over the finished log, its
//! progress sent back on a channel, cancelled on Ctrl-C or the shutdown (at its next
//! evaluation, writing no profile), and its outcome kept.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use calibration::FitProgress;
use tokio::sync::mpsc;

use crate::calibrate::CalibrateError;
use crate::calibrate::fit_session::{FitOptions, FitOutcome, fit_session_with};

/// The fit, once the session is recorded.
pub(super) struct FitRun {
    /// What to fit and where the profile goes (`session` is set to the log).
    pub(super) options: FitOptions,
    /// The fit's progress, from its blocking task.
    progress_tx: mpsc::UnboundedSender<FitProgress>,
    pub(super) progress_rx: mpsc::UnboundedReceiver<FitProgress>,
    /// The running fit.
    pub(super) task: Option<tokio::task::JoinHandle<Result<FitOutcome, CalibrateError>>>,
    /// Set on Ctrl-C or the shutdown: the running fit stops at its next evaluation and writes
    /// no profile.
    cancel: Arc<AtomicBool>,
    /// Its result.
    pub(super) outcome: Option<FitOutcome>,
}

impl FitRun {
    pub(super) fn new(options: FitOptions) -> FitRun {
        let (progress_tx, progress_rx) = mpsc::unbounded_channel();
        FitRun {
            options,
            progress_tx,
            progress_rx,
            task: None,
            cancel: Arc::new(AtomicBool::new(false)),
            outcome: None,
        }
    }

    /// Fits the finished log at `session` in a blocking task, its progress sent back.
    pub(super) fn start(&mut self, session: PathBuf) {
        self.options.session = session;
        let options = self.options.clone();
        let tx = self.progress_tx.clone();
        let cancel = Arc::clone(&self.cancel);
        self.task = Some(tokio::task::spawn_blocking(move || {
            fit_session_with(
                &options,
                &mut |p| {
                    tx.send(p).ok();
                },
                &|| cancel.load(Ordering::Relaxed),
            )
        }));
    }

    /// Asks the running fit to stop; whether it had been asked already.
    pub(super) fn cancel(&self) -> bool {
        self.cancel.swap(true, Ordering::Relaxed)
    }

    /// Whether the fit was asked to stop.
    pub(super) fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
}

/// The fit task's result, once it has ended (pending while there is none).
pub(super) async fn joined<T>(
    task: &mut Option<tokio::task::JoinHandle<T>>,
) -> Result<T, tokio::task::JoinError> {
    match task.as_mut() {
        Some(task) => task.await,
        None => std::future::pending().await,
    }
}
