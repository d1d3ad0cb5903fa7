//! What can go wrong with the simulated benchmark's physics.

use thiserror::Error;

/// A physics error.
#[derive(Debug, Error)]
pub enum PhysicsError {
    /// MuJoCo could not load or compile a scene.
    #[error("MuJoCo could not load the scene {origin}: {message}")]
    Load {
        /// The file or the generated scene's name.
        origin: String,
        /// MuJoCo's message.
        message: String,
    },
    /// The scene lacks elements the binding names.
    #[error("the scene {origin} has no {kind} named {}", names.join(", "))]
    Missing {
        /// The file or the generated scene's name.
        origin: String,
        /// joint, actuator or mocap body.
        kind: &'static str,
        /// The names not found.
        names: Vec<String>,
    },
    /// Joining the DDS domain, or creating the node or an endpoint, failed.
    #[error(transparent)]
    Ros(#[from] crate::ros::RosError),
    /// The task's progress mapping does not fit the scene.
    #[error("progress: {message}")]
    Progress {
        /// What is wrong.
        message: String,
    },
    /// Targets of the wrong length, or not finite.
    #[error("expected {expected} finite values, got {got} (or a non-finite one)")]
    BadTargets {
        /// Values expected.
        expected: usize,
        /// Values given.
        got: usize,
    },
}
