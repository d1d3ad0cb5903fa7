//! The simulated robot's progress events as they travel (`/pomdar/sim/progress`,
//! `std_msgs/String` holding one JSON object each), and what an operator console makes of
//! them: the same marks its keys make.

use serde::{Deserialize, Serialize};

/// One progress event as published.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ProgressMessage {
    /// The task.
    pub task: String,
    /// `progress` (a value in the task's unit) or `drop`.
    pub event: String,
    /// The value (progress only): ±1 notch or curve, degrees, millimetres, or a grasp level.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub value: Option<f64>,
    /// The unit of values and totals.
    pub unit: String,
    /// The progress since the last reset.
    pub total: f64,
    /// Simulated time since the last reset, seconds.
    pub sim_time_s: f64,
}
