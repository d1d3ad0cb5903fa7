//! What can stop a trial console session: its files, the station, the simulation, the
//! terminal or the script. Each variant carries its cause; most are the cause itself.

use std::path::PathBuf;

/// A trial console session could not start, or stopped with an error.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    /// A human-study session was given a calibration profile.
    #[error(
        "--profile: a human-study session (--embodiment human) drives no robot and uses no calibration profile"
    )]
    ProfileForHuman,
    /// A setting outside its range.
    #[error("{flag} {value} is outside the allowed range [{low}, {high}] {unit}")]
    OutOfRange {
        /// The flag.
        flag: &'static str,
        /// The value given.
        value: f64,
        /// The lowest allowed.
        low: f64,
        /// The highest allowed.
        high: f64,
        /// The unit.
        unit: &'static str,
    },
    /// The baseline, catalog or rules, or a report file.
    #[error(transparent)]
    Scoring(#[from] crate::score::ScoreFileError),
    /// The `--task` is not in the catalog.
    #[error("--task {task:?} is not in the {origin} ({ids})")]
    UnknownTask {
        /// The task asked for.
        task: String,
        /// Where the catalog came from.
        origin: String,
        /// The catalog's IDs.
        ids: String,
    },
    /// The station's configuration, profile or embodiment.
    #[error(transparent)]
    Setup(#[from] crate::station_driver::setup::SetupError),
    /// The station's configuration after the session's changes.
    #[error(transparent)]
    Config(#[from] station::ConfigError),
    /// The session directory, its manifest or the `--script`.
    #[error(transparent)]
    Console(#[from] super::ConsoleError),
    /// The DDS domain.
    #[error(transparent)]
    Ros(#[from] crate::ros::RosError),
    /// The simulated glove or robot.
    #[error(transparent)]
    Sim(#[from] crate::stand_ins::SimError),
    /// The live view.
    #[error(transparent)]
    View(#[from] crate::view::live_view::LiveViewError),
    /// The terminal, the keyboard or the signals.
    #[error(transparent)]
    Terminal(#[from] crate::tui::TuiError),
    /// A `--script` wait timed out.
    #[error(transparent)]
    Script(#[from] crate::tui::script::ScriptError),
    /// `--physics` in a build without the simulator.
    #[error(
        "--physics: this pomdar was built without the simulator: run `bash sim/setup_mujoco.sh` once, then build with `--features physics`"
    )]
    NoPhysics,
    /// The arm's start pose in the station's configuration (`--physics`).
    #[error(transparent)]
    ArmStart(#[from] station::arm::ArmConfigError),
    /// The simulated robot could not start (`--physics`).
    #[cfg(feature = "physics")]
    #[error(transparent)]
    Physics(#[from] crate::physics::error::PhysicsError),
    /// The station stopped with nothing asked of it.
    #[error("the station stopped unexpectedly")]
    StationStoppedUnexpectedly,
    /// The station stopped with an error.
    #[error("the station stopped")]
    StationStopped(#[source] crate::station_node::NodeError),
    /// The station's task failed (it panicked or was cancelled).
    #[error("the station task failed")]
    StationTaskFailed(#[source] tokio::task::JoinError),
    /// The station's task failed after the console asked it to stop.
    #[error("station task")]
    StationTask(#[source] tokio::task::JoinError),
    /// The station's error after the console asked it to stop.
    #[error(transparent)]
    Station(#[from] crate::station_node::NodeError),
    /// The session report's Markdown cannot be read back.
    #[error("cannot read {path}")]
    ReadReport {
        /// The report.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The session report's Markdown cannot be written.
    #[error(transparent)]
    WriteReport(#[from] crate::atomic_file::AtomicWriteError),
}

/// An error and its causes on one line, `outer: inner: …`, as the console says it.
pub fn error_chain(error: &(dyn std::error::Error + 'static)) -> String {
    let mut text = error.to_string();
    let mut cause = error.source();
    while let Some(c) = cause {
        text.push_str(": ");
        text.push_str(&c.to_string());
        cause = c.source();
    }
    text
}
