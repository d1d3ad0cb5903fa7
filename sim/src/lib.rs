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
//!
//! ## Files
//!
//! | file | holds |
//! |---|---|
//! | `scene/vertical.rs` | V1–V3: a handle keyed through six slotted plates |
//! | `scene/horizontal.rs` | H1–H3: a carriage lifted over bumps along a rail; H4/H5: a rod slid through its supports |
//! | `scene/continuous.rs` | C1–C3: a rotor on a post; C4: a spinner |
//! | `scene/grasp.rs` | **G1–G6 built**: each free object (G4: the 30 mm cylinder across two posts) and its target region |
//! | `scene/world.rs`, `scene/start.rs`, `scene/mjcf.rs` | the world around a task (table, light, the hand welded under the arm's mocap body); a start moved from a seed; MJCF text helpers |
//! | `scene.rs` | the task → scene table, the contact classes and their measured settings |
//! | `hand_mjcf.rs`, `hand_mjcf/` | a hand model written as MJCF |
//! | `lab_hand.rs`, `lab_hand/` | a lab's hand MJCF (the manufacturer's) bound to the station's joints |
//! | `progress.rs`, `progress/` | progress from the physics state: marks along a joint, whole units of rotation or distance, a grasp's lift and rest |

pub mod hand_mjcf;
pub mod lab_hand;
pub mod progress;
pub mod scene;
