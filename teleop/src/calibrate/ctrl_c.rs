//! Ctrl-C during `pomdar calibrate`: the process's one SIGINT handler, as a watch channel.
//!
//! egobox (the calibration's Bayesian optimiser) installs a `ctrlc` handler the first time it
//! runs, and `ctrlc` allows one handler per process: installed after tokio's, it would replace
//! tokio's (tokio's Ctrl-C would never fire again); with nothing else installed, it swallows
//! SIGINT, so Ctrl-C would only cut the Bayesian search short and the fit would go on. So the
//! shell installs the `ctrlc` handler itself before anything else: egobox's attempt is then
//! refused (`MultipleHandlers`, which egobox accepts), and every Ctrl-C reaches
//! [`watch_ctrl_c`]'s receivers. A signal handler registered later (tokio's) chains to it.

use std::sync::OnceLock;

use tokio::sync::watch;

use crate::calibrate::CalibrateError;

/// Turns true at the first Ctrl-C.
static CTRL_C: OnceLock<watch::Sender<bool>> = OnceLock::new();

/// The handler's installation, once per process (its error as text: `ctrlc::Error` is not
/// `Clone`).
static INSTALLED: OnceLock<Result<(), String>> = OnceLock::new();

/// A receiver that turns true at the first Ctrl-C (SIGINT) after this process installed its
/// handler; the handler is installed at the first call. From then on Ctrl-C no longer ends the
/// process by itself: its owner must watch the receiver.
pub fn watch_ctrl_c() -> Result<watch::Receiver<bool>, CalibrateError> {
    let sender = CTRL_C.get_or_init(|| watch::channel(false).0);
    INSTALLED
        .get_or_init(|| {
            ctrlc::set_handler(|| {
                if let Some(sender) = CTRL_C.get() {
                    sender.send_replace(true);
                }
            })
            .map_err(|e| e.to_string())
        })
        .clone()
        .map_err(|reason| CalibrateError::CtrlC { reason })?;
    Ok(sender.subscribe())
}
