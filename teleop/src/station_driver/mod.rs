//! The one driver around `station::Station::step` that every loop uses (the live node, the
//! re-simulation of a log and `pomdar eval`'s live path, the lock step with the physics): the
//! task → configuration step (`task_config.rs`: the arm constraint, who engages), the station
//! built from its files with its calibration profile (`setup.rs`), when the timer ticks
//! (`ticks.rs`) and where the outputs go (`sinks.rs`).

pub mod setup;
pub mod sinks;
pub mod task_config;
pub mod ticks;

pub use setup::{SetupError, build_station};
pub use sinks::{Delivery, McapSink, OutputSink, deliveries, route};
pub use task_config::{Engage, constrain_for_task, set_engage};
pub use ticks::{TickSchedule, steps_per_tick, tick_period, tick_period_ns};
