//! The turn loop the operator consoles share (the trial console, [`crate::console`], the
//! calibration console, [`crate::calibrate`], and the hand check, [`crate::hand_check`]): what wakes a console besides its own sources (a
//! tick and the signals), what one wake-up brought (a [`Turn`]), whether it goes on
//! ([`Next`]), and the exit status of an interrupted console.

use std::time::Duration;

use tokio::signal::unix::{Signal, SignalKind, signal};

use super::TuiError;

/// Exit status after Ctrl-C (or SIGTERM).
pub const EXIT_INTERRUPTED: u8 = 130;

/// How often a console wakes with nothing else to do, to redraw and run its clock.
pub const TICK: Duration = Duration::from_millis(50);

/// What happens after a turn of a console's loop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Next {
    /// Wait for the next tick, key or event.
    Continue,
    /// Leave the console.
    Quit,
}

/// What one wake-up of a console's loop brought: the operator's actions and the session's
/// effects so far.
#[derive(Debug)]
pub struct Turn<A, E> {
    /// The operator's (or the script's) actions.
    pub actions: Vec<A>,
    /// What the session asks to be done.
    pub effects: Vec<E>,
}

impl<A, E> Default for Turn<A, E> {
    fn default() -> Self {
        Turn {
            actions: Vec::new(),
            effects: Vec::new(),
        }
    }
}

/// A console run by [`run_turns`]: each turn it waits for what wakes it, then finishes the
/// turn (acts on it, shows itself) and says whether it goes on.
pub trait TurnLoop {
    /// The operator's actions.
    type Action;
    /// What the session asks to be done.
    type Effect;
    /// What stops the console.
    type Error;
    /// Waits for a tick, a key, an event or a signal, and notes what it brought in `turn`.
    fn wait(
        &mut self,
        turn: &mut Turn<Self::Action, Self::Effect>,
    ) -> impl Future<Output = Result<(), Self::Error>>;
    /// Acts on what the turn brought and shows the console.
    fn finish_turn(&mut self, turn: Turn<Self::Action, Self::Effect>) -> Result<Next, Self::Error>;
}

/// Turns until the console quits: wait for something, then act on it.
pub async fn run_turns<L: TurnLoop>(console: &mut L) -> Result<(), L::Error> {
    loop {
        let mut turn = Turn::default();
        console.wait(&mut turn).await?;
        if console.finish_turn(turn)? == Next::Quit {
            return Ok(());
        }
    }
}

/// What wakes a console besides its station or node and its operator: its tick and, when it
/// watches them itself, SIGINT and SIGTERM.
pub struct Wakeups {
    /// The console's tick.
    pub tick: tokio::time::Interval,
    /// SIGINT and SIGTERM, when watched.
    pub signals: Signals,
}

/// SIGINT and SIGTERM, when a console watches them itself.
pub struct Signals(Option<(Signal, Signal)>);

impl Wakeups {
    /// The tick only (the console learns of Ctrl-C otherwise).
    pub fn tick_only() -> Wakeups {
        Wakeups {
            tick: tokio::time::interval(TICK),
            signals: Signals(None),
        }
    }

    /// The tick, SIGINT and SIGTERM, listened to from now on, so a signal between two turns
    /// of the loop is not missed.
    pub fn with_signals() -> Result<Wakeups, TuiError> {
        let watch = |kind, signal_name| {
            signal(kind).map_err(|source| TuiError::Signal {
                signal: signal_name,
                source,
            })
        };
        let terminate = watch(SignalKind::terminate(), "SIGTERM")?;
        let interrupt = watch(SignalKind::interrupt(), "SIGINT")?;
        Ok(Wakeups {
            tick: tokio::time::interval(TICK),
            signals: Signals(Some((interrupt, terminate))),
        })
    }
}

impl Wakeups {
    /// The same wake-ups with the tick every `period` instead (a console whose clock is
    /// another rate: the hand check's command rate).
    pub fn ticking_every(self, period: Duration) -> Wakeups {
        Wakeups {
            tick: tokio::time::interval(period),
            signals: self.signals,
        }
    }
}

impl Signals {
    /// The next SIGINT or SIGTERM (never, without them).
    pub async fn interrupted(&mut self) {
        match &mut self.0 {
            Some((interrupt, terminate)) => {
                tokio::select! {
                    _ = interrupt.recv() => {}
                    _ = terminate.recv() => {}
                }
            }
            None => std::future::pending().await,
        }
    }
}

/// A shutdown signal that turns true on Ctrl-C (for the nodes that watch no terminal).
pub fn ctrl_c_shutdown() -> tokio::sync::watch::Receiver<bool> {
    let (tx, rx) = tokio::sync::watch::channel(false);
    tokio::spawn(async move {
        if tokio::signal::ctrl_c().await.is_ok() {
            tx.send(true).ok();
        }
    });
    rx
}
