//! The simulated POMDAR benchmark as data, for MuJoCo.
//!
//! - [`hand_mjcf`]: a hand model (`retarget::HandModel`, the built-in ORCA or a URDF import)
//!   written as an MJCF body tree with collision geometry sized from its links, one position
//!   actuator per degree of freedom, limits and speeds like the real hand's.
//! - [`progress`]: how a task's progress is read from the physics state (a joint's position or
//!   an object's pose) and turned into the same progress events an operator's keys make.
//! - [`scene`]: the 18 task scenes written by the project (simplified scaffolds), each with its
//!   progress mapping, and the whole world (table, task, the hand under the arm's mocap body).
//!
//! Pure: text and numbers in, text and events out. `teleop` (feature `physics`) loads the
//! MJCF into MuJoCo, steps it and feeds the readings back here.

pub mod hand_mjcf;
pub mod lab_hand;
pub mod progress;
pub mod scene;
