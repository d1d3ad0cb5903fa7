//! `pomdar sim-bench`: the benchmark without a teleoperator. Per embodiment and task,
//! programmed practice (the `practice` crate's seeded search over the task's strategy family,
//! each trial a lock-step run through the station core into the physics), then recorded runs
//! of the best strategy at the glove's noise with moved starts; the POMDAR report of the
//! recorded runs, the strategies chosen, and the paper's findings checked. Items spread over
//! the cores; `--shard K/N` splits them over machines and `--merge` joins the shards.

pub mod bench_run;
pub mod error;
pub mod families;
pub mod item;
pub mod outputs;
pub mod play;
pub mod request;
pub mod trial_events;
pub mod trial_log;

use std::collections::BTreeSet;
use std::path::PathBuf;

pub use error::BenchError;
use outputs::{BenchReport, write_bench_report};

use crate::score::score_inputs::ScoringInputs;

/// The embodiments of the built-in catalog that unlock an abduction joint (a joint whose name
/// ends in `_abd`).
pub fn embodiments_with_abduction() -> BTreeSet<String> {
    retarget::EmbodimentCatalog::builtin()
        .embodiments
        .iter()
        .filter(|e| e.unlocked.iter().any(|j| j.ends_with("_abd")))
        .map(|e| e.name.clone())
        .collect()
}

/// Joins the item files of `dirs` (shards of one benchmark) and writes the whole report into
/// `out`.
pub fn merge_shards(
    dirs: &[PathBuf],
    out: &std::path::Path,
    scoring: &ScoringInputs,
    header: &str,
) -> Result<BenchReport, BenchError> {
    let items = outputs::read_items(dirs)?;
    if items.is_empty() {
        return Err(BenchError::Setup(format!(
            "no item files in {}",
            dirs.iter()
                .map(|d| d.join(outputs::ITEMS_DIR).display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    write_bench_report(out, &items, scoring, &embodiments_with_abduction(), header)
}
