//! # Scoring trials (`pomdar score`, `pomdar baseline`)
//!
//! The scoring maths, reports and figures are the pure `scoring` crate; this module finds the
//! files, reads what scoring needs from each (fast, through the MCAP summary), runs the files
//! on every core with a progress bar, and writes the reports.
//!
//! | file | what |
//! |---|---|
//! | `trial_files.rs` | the `.mcap` files under the paths given; `.part` skipped with a note |
//! | `load_trial.rs` | a file → `scoring::TrialLog` (metadata record, events as JSON) |
//! | `score_inputs.rs` | catalog, rules, baseline files and the embodiments' DoF |
//! | `parallel_files.rs` | files on every core, in input order, with progress |
//! | `report_files.rs` | `--out DIR`: reports and figures, atomic writes |
//! | `compare_files.rs` | `--compare FIELD --out DIR`: the comparison's files and figures, atomic writes |
//! | `synthetic_trial.rs` | trial logs written as the station writes them, for the benchmark and tests |
//! | `error.rs` | `ScoreFileError` (the run's own files), `TrialFileError` (a trial not scored) |

pub mod baseline_source;
pub mod compare_files;
mod error;
pub mod load_trial;
pub mod parallel_files;
pub mod report_files;
pub mod score_inputs;
pub mod synthetic_trial;
pub mod trial_files;

pub use error::{ScoreFileError, TrialFileError};
