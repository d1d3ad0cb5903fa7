//! Simulated parts for the demo and tests: the glove (the project's parametric human hand
//! model driven by periodic motions or a task script read from a file), a mock ORCA hand and a mock Franka arm, each a ROS 2
//! node on its own DDS participant, exactly as separate processes would be.

mod error;
pub mod glove_jitter;
pub mod glove_script_file;
pub mod mock_franka;
pub mod mock_hand;
pub mod mock_robot;
pub mod progress_message;
pub use crate::samples;
pub mod sim_glove_node;

pub use error::SimError;
