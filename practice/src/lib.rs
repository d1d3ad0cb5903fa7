//! Programmed practice: the simulated benchmark with no one at the glove (pure).
//!
//! The paper's results mix the hand with the operator's skill; it names scoring embodiments by
//! programmed practice as its next step. This crate holds what that needs, without I/O:
//!
//! - [`family`]: a task's family of strategies, its glove script changed by a few named
//!   parameters (start offset, approach direction, reach, which digits close and how far,
//!   timing);
//! - [`search`]: a seeded cross-entropy search over such a family with a bounded budget of
//!   noisy trials;
//! - [`objective`]: the score it maximises (the POMDAR score);
//! - [`practice_file`]: the practice file (per task: script, station settings, grips);
//! - [`mod@plan`]: the benchmark's work items and shards;
//! - [`findings`]: the paper's findings checked against the recorded trials.
//!
//! `teleop` plays the strategies through the station core and the physics in lock step
//! (`pomdar sim-bench`).

pub mod error;
pub mod family;
pub mod findings;
pub mod findings_checks;
pub mod objective;
pub mod plan;
pub mod practice_file;
pub mod search;

pub use error::PracticeError;
pub use family::{Grip, Strategy, StrategyBounds, StrategyFamily, StrategyParams};
pub use findings::{Cell, Evidence, Finding, Verdict};
pub use findings_checks::check_findings;
pub use objective::practice_score;
pub use plan::{Shard, WorkItem, plan};
pub use practice_file::{PracticeFile, TaskPractice};
pub use search::{Candidate, CrossEntropySearch, Dimension, SearchSpace, Tried};
