//! # station: the POMDAR station core
//!
//! One pure state machine, [`Station`], driven by [`Station::step`]`(input, now)`: a glove
//! keypoint frame, a wrist pose, arm feedback, or a control input (a timer tick, the
//! operator's engage or disengage, the application's word that another publisher drives the
//! arm), each with its receive time in nanoseconds on the application's one clock. It gives back
//! the messages to send (`sensor_msgs/JointState` hand targets, the lab's
//! `/hand/policy_output`, a `geometry_msgs/PoseStamped` arm target) and notices for the
//! operator. No I/O and no clock: the `teleop` application's ROS node, its re-simulation of a
//! log, `pomdar eval` and the operator consoles drive this one core and keep no station state
//! of their own, so a recorded run re-simulates to the same commands, byte for byte.
//!
//! ## Hand commands
//!
//! With `control.mode = "on_arrival"` (the default) a hand command is computed when a new,
//! plausible glove frame arrives, unless it is stamped less than `1 / max_command_rate_hz`
//! after the last commanded frame (then the next frame or tick takes it). The retargeter's time
//! step is the difference of the two frames' source stamps `Δt = s_k − s_{k−1}`, clamped to
//! `[0.1 ms, 0.5 s]`: the spacing at which the glove captured them, whatever the network did
//! to their delivery. With `mode = "rate"` a command is computed on every tick from the newest
//! frame, and repeated when none came.
//!
//! ## Ticks
//!
//! The timer (`control.rate_hz`, 25 Hz by default) advances the watchdog (`watchdog.rs`: hold after
//! `hold_timeout_ms` without a new frame, disengage after `disengage_timeout_ms`), repeats the
//! held command while held or disengaged, and steps the arm mapping ([`arm`]): its step caps
//! are per tick, so the tick rate sets the arm speeds they allow.
//!
//! ## Files
//!
//! | file | holds |
//! |---|---|
//! | `station.rs` | [`Station`]: the state machine and its one entry, [`Station::step`]; its status and totals (`station_tests.rs`: driven step by step as every loop drives it) |
//! | `station_input.rs` | what drives a step ([`StationInput`], [`ControlInput`]) and what it gives back ([`StationOutputs`], [`Notice`]) |
//! | `station_config.rs`, `config_error.rs`, `station_error.rs` | the configuration (TOML, every key checked with its range) and why a station could not be built |
//! | `frame_gate.rs`, `outlier_check.rs`, `source_order.rs` | **where a glove frame is rejected**: repeats, wrong size, non-finite points, bone lengths, jumps, frames out of their sender's order ([`Rejection`]); a tracker's one-frame outlier put back where its digit predicts it |
//! | `hand_control.rs` | which accepted frames are retargeted and when (on arrival or at the control rate), and the hand command |
//! | `watchdog.rs` | **where the watchdog decides hold and disengage**: the glove stream's freshness sets the drive state ([`DriveState`]) |
//! | `input_gap.rs`, `rate_meter.rs` | which side stalled (the longest gap as received against as sent); event rates for the status |
//! | `arm/` | the Franka wrist: the clutch and mapper (`mapper.rs`: [`arm::ArmMapper`]), **a task's arm constraint applied** (`constraint.rs`: fixed, vertical or horizontal axis), step caps, the workspace box, pose checks |
//! | `output_stage.rs`, `policy_output.rs`, `joint_names.rs`, `hand_convention.rs` (presets in `hand_convention_presets.rs`), `convert.rs` | from commands to the messages sent: hand joint targets under the published names, the lab's `/hand/policy_output` through a hand's command convention, the arm target |
//! | `network_config.rs`, `robot_link.rs`, `link_clock.rs` | the DDS side of the configuration (domain, interfaces, QoS); the link to the robot's computer and its age check; the relay's clock-offset view |
//! | `ros_tools/`, `ros_tools_config.rs` | what the lab's ROS tools see: `/tf`, markers, diagnostics |
//! | `simulated_physics_config.rs` | `[simulated_physics]`: the MuJoCo twin's contact, servo and mount settings |
//! | `fuzz/` (feature `fuzzing`) | the whole core fuzzed: a seeded hostile world, a reference drive model, invariants checked after every step |

pub mod arm;
mod config_error;
pub mod convert;
mod frame_gate;
#[cfg(feature = "fuzzing")]
pub mod fuzz;
mod hand_control;
pub mod hand_convention;
#[cfg(test)]
mod hand_convention_presets;
mod input_gap;
pub mod joint_names;
pub mod link_clock;
mod network_config;
mod outlier_check;
mod output_stage;
pub mod policy_output;
mod rate_meter;
pub mod retargeter_setup;
pub mod robot_link;
pub mod ros_tools;
mod ros_tools_config;
mod simulated_physics_config;
mod source_order;
#[allow(clippy::module_inception)]
mod station;
mod station_config;
mod station_error;
mod station_input;
mod watchdog;

pub use config_error::ConfigError;
pub use frame_gate::{GateConfig, GateDecision, Rejection, repeats};
pub use hand_control::{Counters, HandCommand, KeypointFrame, QpReport, time_step_between};
pub use input_gap::InputGap;
pub use network_config::{NetworkConfig, QosConfig, Reliability};
pub use output_stage::{HandMessages, policy_array};
pub use simulated_physics_config::SimulatedPhysicsConfig;
pub use station::{ArmStatus, Station, StationStatus, Totals};
pub use station_config::{
    ControlConfig, ControlMode, HUMAN_EMBODIMENT, InputConfig, KeypointFormat, OutputConfig,
    StationConfig,
};
pub use station_error::StationError;
pub use station_input::{ControlInput, Notice, StationInput, StationOutputs};
pub use watchdog::{DriveState, WatchdogConfig};
