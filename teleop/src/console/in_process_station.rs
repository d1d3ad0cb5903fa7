//! The station the trial console runs in this process: started with the console's hooks
//! (status, trial-log events, the newest input's time, the live view's tap), and with
//! `--simulate` the simulated glove and robot beside it; what the console holds of it.

use retarget::HandModel;
use retarget::human_hand::GloveScript;
use scoring::TaskSpec;
use station::StationConfig;
use tokio::sync::{mpsc, watch};
use tokio::task::JoinHandle;

use super::physics_link::PhysicsLink;
use super::session_error::SessionError;
use super::session_options::SessionOptions;
use super::simulated_world::{SimulatedRobot, spawn_simulation};
use crate::clock::StationClock;
use crate::station_node::ros_node::{
    LatestInput, OperatorCommand, StationEvent, StationHooks, StationSummary, run_station_observed,
};

/// How often a trial's log is flushed (and synced) at least, ns of log time: a kill or a
/// crash loses at most this much of the running trial, plus the writes in flight, well within
/// the second the console promises (the writer's default, 1 s, left no margin for them).
const TRIAL_LOG_FLUSH_INTERVAL_NS: i64 = 500_000_000;

/// The station running in this process (and, with `--simulate`, the glove and the robot):
/// what the console holds of it.
pub(super) struct StationHandles {
    /// The station's task; its summary when it stops.
    pub(super) task: JoinHandle<Result<StationSummary, crate::station_node::NodeError>>,
    /// Commands to the station.
    pub(super) operator_tx: mpsc::UnboundedSender<OperatorCommand>,
    /// The station's status, as published.
    pub(super) status_rx: watch::Receiver<Option<serde_json::Value>>,
    /// Trial log starts and ends, and messages for the operator.
    pub(super) events_rx: mpsc::UnboundedReceiver<StationEvent>,
    /// The newest glove frame's receive time, kept by the station at every frame.
    pub(super) latest_input: LatestInput,
    /// Stops the station and the simulation.
    pub(super) shutdown_tx: watch::Sender<bool>,
    _shutdown_rx: watch::Receiver<bool>,
    /// `--simulate`: the hand's, the arm's and the glove's tasks.
    pub(super) simulated: Vec<JoinHandle<Result<(), crate::stand_ins::SimError>>>,
    /// `--physics`: the simulated robot's progress events and resets.
    pub(super) physics: Option<PhysicsLink>,
}

/// Starts the station (status and trial-log events back to the console) and, with
/// `--simulate`, the glove (playing `glove_script` if given) and the robot.
pub(super) fn spawn_station(
    options: &SessionOptions,
    (config, task): (&StationConfig, &TaskSpec),
    model: &HandModel,
    clock: StationClock,
    tap: Option<crate::station_node::tap::Tap>,
    glove_script: Option<GloveScript>,
) -> Result<StationHandles, SessionError> {
    let (shutdown_tx, shutdown_rx) = watch::channel(false);
    let (operator_tx, operator_rx) = mpsc::unbounded_channel();
    let (status_tx, status_rx) = watch::channel(None);
    let (events_tx, events_rx) = mpsc::unbounded_channel();
    let latest_input = LatestInput::default();
    let station = tokio::spawn(run_station_observed(
        config.clone(),
        model.clone(),
        clock,
        shutdown_rx.clone(),
        operator_rx,
        None,
        StationHooks {
            status: Some(status_tx),
            events: Some(events_tx),
            latest_input: Some(latest_input.clone()),
            tap,
            trial_log_flush_interval_ns: Some(TRIAL_LOG_FLUSH_INTERVAL_NS),
            ..StationHooks::default()
        },
    ));
    let mut simulated = Vec::new();
    let mut physics = None;
    if let Some(simulation) = &options.simulation {
        let robot = SimulatedRobot {
            config,
            model,
            task,
        };
        (simulated, physics) = spawn_simulation(
            options,
            simulation,
            &robot,
            clock,
            &shutdown_rx,
            glove_script,
        )?;
    }
    Ok(StationHandles {
        task: station,
        operator_tx,
        status_rx,
        events_rx,
        latest_input,
        shutdown_tx,
        _shutdown_rx: shutdown_rx,
        simulated,
        physics,
    })
}

/// Why the station's task ended while the console ran.
pub(super) fn station_stopped(
    result: Result<Result<StationSummary, crate::station_node::NodeError>, tokio::task::JoinError>,
) -> SessionError {
    match result {
        Ok(Ok(_)) => SessionError::StationStoppedUnexpectedly,
        Ok(Err(e)) => SessionError::StationStopped(e),
        Err(e) => SessionError::StationTaskFailed(e),
    }
}

pub(super) fn send(tx: &mpsc::UnboundedSender<OperatorCommand>, command: OperatorCommand) {
    tx.send(command).ok();
}
