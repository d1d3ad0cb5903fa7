//! The trial console's event loop: each turn waits for a tick, the station's status or
//! events, the simulated robot's progress, a key or line, or a signal; then the script's and
//! the operator's actions and the clock go to the session, its effects are carried out and the
//! console is shown. When it quits, the station stops and the session's state is printed.

use std::time::Instant;

use station::ros_tools::ServiceAction;

use super::health::Health;
use super::in_process_station::{StationHandles, send, station_stopped};
use super::keys::{Action, parse_action};
use super::operator_side::{OperatorSide, Prompt, typed};
use super::physics_link::{next_progress, progress_action};
use super::session_error::SessionError;
use super::session_report::review_lines;
use super::session_state::Session;
use super::test_pause::test_pause;
use super::trial_flow::{Effect, TrialPhase};
use super::view::Screen;
use crate::clock::StationClock;
use crate::disk_wait::without_holding_the_runtime;
use crate::station_node::recorder::RecordingOptions;
use crate::station_node::ros_node::{OperatorCommand, StationEvent};
use crate::tui::script_player::ScriptPlayer;
use crate::tui::terminal::Input;
use crate::tui::terminal_shell::{Next, TurnLoop, Wakeups};

/// What one wake-up of the trial console brought.
type Turn = crate::tui::terminal_shell::Turn<Action, Effect>;

/// How a console session ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SessionEnd {
    /// Ctrl-C, SIGTERM, q or stdin closed.
    pub interrupted: bool,
    /// Every planned trial is done.
    pub complete: bool,
}

/// How the console ends.
#[derive(Default)]
pub(super) struct ConsoleEnd {
    /// Ctrl-C, SIGTERM, q or stdin closed: exit status [`crate::tui::terminal_shell::EXIT_INTERRUPTED`].
    interrupted: bool,
    /// A script that failed (a wait timed out).
    failure: Option<SessionError>,
}

/// `pomdar trial` while it runs: the operator's side, the session, the station.
pub(super) struct TrialConsole {
    pub(super) operator: OperatorSide,
    pub(super) wakeups: Wakeups,
    pub(super) session: Session,
    pub(super) station: StationHandles,
    pub(super) clock: StationClock,
    pub(super) end: ConsoleEnd,
}

impl TurnLoop for TrialConsole {
    type Action = Action;
    type Effect = Effect;
    type Error = SessionError;

    /// Waits for a tick, the station's status or events, a key or line, or a signal; an
    /// error when the station stops.
    async fn wait(&mut self, turn: &mut Turn) -> Result<(), SessionError> {
        tokio::select! {
            _ = self.wakeups.tick.tick() => {}
            Ok(()) = self.station.status_rx.changed() => self.status_changed(),
            Some(input) = self.operator.input_rx.recv() => self.input(input, &mut turn.actions),
            Some(event) = self.station.events_rx.recv() => self.station_event(event, turn),
            Some(progress) = next_progress(&mut self.station.physics) => {
                // Marks count only in a running trial; between trials the physics is ignored.
                if matches!(self.session.flow.phase(), TrialPhase::Running { .. }) {
                    turn.actions.push(progress_action(&progress));
                }
            }
            result = &mut self.station.task => return Err(station_stopped(result)),
            () = self.wakeups.signals.interrupted() => turn.actions.push(Action::Interrupt),
        }
        Ok(())
    }

    /// The rest of a turn: the script's and the operator's actions and the clock go to the
    /// session, its effects are carried out, the report written when the plan is complete,
    /// the console shown.
    fn finish_turn(&mut self, mut turn: Turn) -> Result<Next, SessionError> {
        let now = self.clock.now_ns();
        // The newest status, even when this turn woke for something else: a turn that waited
        // on the disk must not take the station for silent.
        if self.station.status_rx.has_changed().unwrap_or(false) {
            self.status_changed();
        }
        self.session.health.latest_input_ns = self.station.latest_input.get();
        self.play_script(&mut turn.actions);
        self.act(turn.actions, &mut turn.effects, now);
        let session = &mut self.session;
        turn.effects.extend(session.flow.tick(&session.health, now));
        let mut next = self.carry_out(turn.effects);
        self.session.write_report_once_complete();
        if self.done_unattended() {
            next = Next::Quit;
        }
        let session = &mut self.session;
        session.message_log.append_new(&mut session.flow);
        self.operator.show(&self.session, now)?;
        Ok(next)
    }
}

impl TrialConsole {
    fn status_changed(&mut self) {
        if let Some(status) = self.station.status_rx.borrow_and_update().as_ref() {
            self.session.health = Health::from_status(status, self.clock.now_ns());
        }
    }

    /// A key or a line: an action, or a key typed into the prompt.
    fn input(&mut self, input: Input, actions: &mut Vec<Action>) {
        let flow = &mut self.session.flow;
        match input {
            Input::CtrlC => actions.push(Action::Interrupt),
            Input::Line(line) if !line.trim().is_empty() => match parse_action(&line) {
                Ok(action) => actions.push(action),
                Err(e) => flow.say(e.to_string()),
            },
            Input::Line(_) => {}
            Input::Closed => {
                flow.say("stdin closed: quitting (a running trial is set aside)");
                actions.push(Action::Interrupt);
            }
            key => {
                if let Some(action) = typed(&mut self.operator.prompt, key) {
                    actions.push(action);
                }
            }
        }
    }

    /// A trial log started, finished or failed, or a message from the station.
    fn station_event(&mut self, event: StationEvent, turn: &mut Turn) {
        let effects = &mut turn.effects;
        let flow = &mut self.session.flow;
        let inputs = &self.session.inputs;
        match event {
            StationEvent::TrialStarted(path) => flow.say(format!("recording {}", path.display())),
            StationEvent::TrialStartFailed { path, error } => {
                effects.extend(flow.trial_start_failed(&format!("{}: {error}", path.display())));
            }
            StationEvent::TrialFinished(path) => {
                test_pause(&format!("{} finished: scoring it", path.display()));
                let (said, scored) = without_holding_the_runtime(|| {
                    let said = review_lines(&path, &self.session.dir, &self.session.config);
                    (said, inputs.score_file(&path).map_err(|e| e.to_string()))
                });
                effects.extend(flow.trial_logged(scored));
                for line in said {
                    flow.say(line);
                }
            }
            StationEvent::TrialFinishFailed { path, error } => {
                effects.extend(flow.trial_logged(Err(format!(
                    "the log {} could not be finished: {error} (its .part is kept for pomdar recover)",
                    path.display()
                ))));
            }
            StationEvent::Message(text) => flow.say(text),
            StationEvent::ServiceRequest(action) => turn.actions.push(match action {
                ServiceAction::Engage => Action::Engage,
                ServiceAction::Disengage => Action::Disengage,
                ServiceAction::TrialStart => Action::Start,
                ServiceAction::TrialStop => Action::Stop,
                ServiceAction::TrialAbort => Action::Abort,
            }),
        }
    }

    /// The script's due action in the current screen; a script that failed interrupts.
    fn play_script(&mut self, actions: &mut Vec<Action>) {
        let screen_now = Screen::of(&self.session.flow, &self.session.health);
        if let Some(p) = self.operator.player.as_mut() {
            match p.next(screen_now, Instant::now()) {
                Ok(Some(action)) => actions.push(action),
                Ok(None) => {}
                Err(e) => {
                    self.session.flow.say(e.to_string());
                    self.end.failure = Some(e.into());
                    actions.push(Action::Interrupt);
                }
            }
        }
    }

    /// The actions: prompts open, the rest go to the session.
    fn act(&mut self, actions: Vec<Action>, effects: &mut Vec<Effect>, now: i64) {
        let session = &mut self.session;
        for action in actions {
            if action == Action::Interrupt {
                self.end.interrupted = true;
            }
            match action {
                Action::PromptProgress => {
                    self.operator.prompt = Some((Prompt::Progress, String::new()));
                }
                Action::PromptNote => self.operator.prompt = Some((Prompt::Note, String::new())),
                other => effects.extend(session.flow.act(other, &session.health, now)),
            }
        }
    }

    /// Carries out the session's effects: commands to the station, the manifest, trials set
    /// aside, quitting.
    fn carry_out(&mut self, effects: Vec<Effect>) -> Next {
        let operator_tx = &self.station.operator_tx;
        let mut next = Next::Continue;
        for effect in effects {
            match effect {
                Effect::Engage => send(operator_tx, OperatorCommand::Engage),
                Effect::Disengage => send(operator_tx, OperatorCommand::Disengage),
                Effect::TrialEvent(event) => send(operator_tx, OperatorCommand::TrialEvent(event)),
                Effect::StopTrial => send(operator_tx, OperatorCommand::StopTrial),
                Effect::StartTrial { file, slot } => {
                    if let Some(physics) = &self.station.physics {
                        physics.trial_started(self.clock.now_ns());
                    }
                    let metadata = self.session.trial_metadata(&slot);
                    let dir = &self.session.dir;
                    send(
                        operator_tx,
                        OperatorCommand::StartTrial(RecordingOptions {
                            path: dir.join(&file),
                            metadata,
                        }),
                    );
                }
                // The disk's waits must not hold up the station this loop has just woken.
                Effect::SaveManifest => {
                    without_holding_the_runtime(|| self.session.save_manifest());
                }
                Effect::SetAside { from, to } => {
                    without_holding_the_runtime(|| self.session.set_aside(&from, &to));
                }
                Effect::Quit => next = Next::Quit,
            }
        }
        next
    }

    /// Without a keyboard to say q, a finished plan (and script) ends the console.
    fn done_unattended(&self) -> bool {
        let operator = &self.operator;
        *self.session.flow.phase() == TrialPhase::Complete
            && !operator.full_screen
            && (!operator.scripted || operator.player.as_ref().is_some_and(ScriptPlayer::finished))
    }

    /// The console has quit: the station disengages and stops, the console is left, the
    /// session's state printed; the exit status says whether it was interrupted.
    pub(super) async fn finish(self) -> Result<SessionEnd, SessionError> {
        let TrialConsole {
            operator,
            session,
            station,
            end,
            ..
        } = self;
        let StationHandles {
            task: station,
            operator_tx,
            shutdown_tx,
            simulated,
            ..
        } = station;
        // The station stops commanding: the robot holds its last target.
        send(&operator_tx, OperatorCommand::Disengage);
        shutdown_tx.send(true).ok();
        let summary = station.await.map_err(SessionError::StationTask)??;
        for task in simulated {
            task.await.ok();
        }
        drop(operator.display);
        session.print_summary();
        let complete = session.flow.manifest.next_slot().is_none();
        if summary.counters.frames_new == 0 {
            eprintln!("note: the station received no glove frames");
        }
        if let Some(error) = end.failure {
            return Err(error);
        }
        Ok(SessionEnd {
            interrupted: end.interrupted,
            complete,
        })
    }
}
