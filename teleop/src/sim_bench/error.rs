//! What can go wrong in a benchmark run without a teleoperator.

use std::path::PathBuf;

use thiserror::Error;

/// A benchmark error: the file, the key or the item it concerns, and why.
#[derive(Debug, Error)]
pub enum BenchError {
    /// A file could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A file could not be written.
    #[error("cannot write {}: {reason}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// The practice file is not valid.
    #[error("{origin}: {source}")]
    Practice {
        /// The file.
        origin: String,
        /// What is wrong, by key.
        source: practice::PracticeError,
    },
    /// A glove script is not valid.
    #[error("glove script {origin}: {reason}")]
    Script {
        /// The script and the practice file naming it.
        origin: String,
        /// What is wrong, by key.
        reason: String,
    },
    /// A task's station file does not fit the station configuration.
    #[error("a task's station settings: {reason}")]
    Station {
        /// What is wrong.
        reason: String,
    },
    /// The benchmark asks for something that does not exist or does not fit.
    #[error("{0}")]
    Setup(String),
    /// The physics failed.
    #[error("{embodiment} on {task}: {source}")]
    Physics {
        /// The embodiment.
        embodiment: String,
        /// The task.
        task: String,
        /// What failed.
        source: Box<crate::physics::error::PhysicsError>,
    },
    /// A run's trial does not score (a bug: the runs write what the scoring reads).
    #[error("{embodiment} on {task}: the run does not score: {reason}")]
    Scoring {
        /// The embodiment.
        embodiment: String,
        /// The task.
        task: String,
        /// The scoring's words.
        reason: String,
    },
    /// A shard's item file is not one this pomdar writes.
    #[error("{}: not a sim-bench item ({reason})", path.display())]
    Item {
        /// The file.
        path: PathBuf,
        /// Why.
        reason: String,
    },
}
