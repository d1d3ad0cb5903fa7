//! The simulated benchmark's physics (feature `physics`): MuJoCo scenes from the `simulation`
//! crate (or a lab's own MJCF), stepped in real time by the simulated robot node.

pub mod engine;
pub mod error;
pub mod lockstep;
pub mod robot_config;
pub mod robot_node;
pub mod setup;
pub mod sim_state;
