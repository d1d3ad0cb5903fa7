//! Ctrl-C during `pomdar calibrate`: the process's one SIGINT handler, as a watch channel.
//!
//! The fit is synchronous and asks before every evaluation whether it was cancelled; with
//! `--from` it runs with no async runtime at all, so tokio's Ctrl-C cannot be what it asks.
//! The shell installs a `ctrlc` handler (one per process) before anything else instead, and
//! every Ctrl-C reaches [`watch_ctrl_c`]'s receivers, in the console session as with
//! `--from`. A signal handler registered later (tokio's) chains to it.

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
