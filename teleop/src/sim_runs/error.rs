//! What can stop `pomdar sim`: the catalog, the station's configuration, the scene, the glove
//! script, the physics, or a value out of range.

use std::path::PathBuf;

/// `pomdar sim` failed.
#[derive(Debug, thiserror::Error)]
pub enum SimRunError {
    /// The catalog.
    #[error(transparent)]
    Scoring(#[from] crate::score::ScoreFileError),
    /// The `--task` is not in the catalog.
    #[error("no task {task} in the catalog (known: {ids})")]
    UnknownTask {
        /// The task asked for.
        task: String,
        /// The catalog's IDs.
        ids: String,
    },
    /// The station's configuration.
    #[error(transparent)]
    Setup(#[from] crate::station_driver::setup::SetupError),
    /// The arm's start pose.
    #[error(transparent)]
    ArmStart(#[from] station::arm::ArmConfigError),
    /// The scene, the engine or the simulated robot.
    #[error(transparent)]
    Physics(#[from] crate::physics::error::PhysicsError),
    /// The scene cannot be written (`--write-scene`).
    #[error("cannot write {path}")]
    WriteScene {
        /// The file.
        path: PathBuf,
        /// What failed.
        #[source]
        source: crate::atomic_file::AtomicWriteError,
    },
    /// `--perturb-start` or `--hand-mjcf` with a lab's `--scene`.
    #[error(
        "--perturb-start and --hand-mjcf change the project's scenes only: a lab's own --scene is loaded as written"
    )]
    LabSceneAsWritten,
    /// `--runs` out of range.
    #[error("--runs {runs} must be in [1, 1000]")]
    Runs {
        /// The value given.
        runs: u64,
    },
    /// The glove script or the simulated glove.
    #[error(transparent)]
    Glove(#[from] crate::stand_ins::SimError),
    /// The physics' events do not give a correctness.
    #[error("the physics' marks do not score: {reason}")]
    Marks {
        /// Why.
        reason: String,
    },
}
