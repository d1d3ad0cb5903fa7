//! The benchmark's items spread over the cores: each worker takes the next item, practises,
//! records, writes the item's file, and prints a line; the first error stops the others.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Instant;

use practice::{StrategyFamily, WorkItem};
use retarget::HandModel;
use station::StationConfig;

use super::error::BenchError;
use super::families::{Families, overlay_station};
use super::item::{ItemOutcome, ItemSettings, run_item};
use super::outputs::write_item;
use super::play::ItemSetup;
use crate::score::score_inputs::ScoringInputs;

/// Everything the items share.
pub struct BenchRun<'a> {
    /// This shard's items.
    pub items: Vec<WorkItem>,
    /// The hand the station retargets to.
    pub model: &'a HandModel,
    /// The lab's MuJoCo model of the hand, if any.
    pub hand_file: Option<&'a Path>,
    /// The station configuration every item starts from.
    pub station: &'a StationConfig,
    /// The strategy families.
    pub families: &'a Families,
    /// Catalog, baseline and rules.
    pub scoring: &'a ScoringInputs,
    /// Budget, runs, seed, logs, metadata.
    pub settings: ItemSettings,
    /// The glove's keypoint noise, metres.
    pub jitter_m: f64,
    /// Worker threads.
    pub jobs: usize,
    /// The output directory (item files go to `items/`).
    pub out: PathBuf,
}

/// Runs every item; the outcomes in item order.
pub fn run_bench(run: &BenchRun<'_>) -> Result<Vec<ItemOutcome>, BenchError> {
    let next = AtomicUsize::new(0);
    let finished = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    let results: Mutex<Vec<Option<ItemOutcome>>> = Mutex::new(vec![None; run.items.len()]);
    let first_error: Mutex<Option<BenchError>> = Mutex::new(None);
    let started = Instant::now();
    std::thread::scope(|scope| {
        for _ in 0..run.jobs.clamp(1, run.items.len().max(1)) {
            scope.spawn(|| {
                while !stop.load(Ordering::Relaxed) {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(item) = run.items.get(i) else {
                        break;
                    };
                    let item_started = Instant::now();
                    match run_one(run, item) {
                        Ok(outcome) => {
                            let done = finished.fetch_add(1, Ordering::Relaxed) + 1;
                            eprintln!(
                                "[{done:>3}/{}] {} ({:.0} s, {:.0} s in all)",
                                run.items.len(),
                                item_line(&outcome),
                                item_started.elapsed().as_secs_f64(),
                                started.elapsed().as_secs_f64()
                            );
                            if let Ok(mut r) = results.lock() {
                                r[i] = Some(outcome);
                            }
                        }
                        Err(error) => {
                            stop.store(true, Ordering::Relaxed);
                            if let Ok(mut e) = first_error.lock() {
                                e.get_or_insert(error);
                            }
                        }
                    }
                }
            });
        }
    });
    if let Some(error) = first_error.into_inner().ok().flatten() {
        return Err(error);
    }
    let results = results.into_inner().unwrap_or_default();
    Ok(results.into_iter().flatten().collect())
}

/// One item: its setup, practice, records, and its file.
fn run_one(run: &BenchRun<'_>, item: &WorkItem) -> Result<ItemOutcome, BenchError> {
    let (setup, family) = item_setup(run, item)?;
    let outcome = run_item(&setup, family, run.scoring, &run.settings, item)?;
    write_item(&run.out, &outcome)?;
    Ok(outcome)
}

/// The station and scene settings of `item`: the embodiment, the task's station file and
/// its arm constraint.
fn item_setup<'a>(
    run: &'a BenchRun<'a>,
    item: &WorkItem,
) -> Result<(ItemSetup<'a>, &'a StrategyFamily), BenchError> {
    let task = run
        .scoring
        .catalog
        .get(&item.task)
        .ok_or_else(|| BenchError::Setup(format!("no task {} in the catalog", item.task)))?;
    let family = run.families.tasks.get(&item.task).ok_or_else(|| {
        BenchError::Setup(format!(
            "{} has no strategy family for task {}",
            run.families.origin, item.task
        ))
    })?;
    let mut station = match &family.station_overlay {
        Some(text) => overlay_station(run.station, text)?,
        None => run.station.clone(),
    };
    station.retarget.embodiment = item.embodiment.clone();
    crate::station_driver::constrain_for_task(&mut station, task);
    // The keypoints go into the core directly; a trial log records them as the lab's glove
    // sends them.
    station.input.keypoints_format = station::KeypointFormat::Float32MultiArray;
    let setup = ItemSetup {
        model: run.model,
        task,
        station,
        hand_file: run.hand_file,
        jitter_m: run.jitter_m,
    };
    Ok((setup, &family.family))
}

/// `orca_2 · G4: practice 24 (best 0.93), recorded 20/20 complete, mean 9.8 s`.
fn item_line(outcome: &ItemOutcome) -> String {
    let complete: Vec<f64> = outcome
        .recorded
        .iter()
        .filter_map(|r| completion_s(&r.trial))
        .collect();
    let mean = if complete.is_empty() {
        String::new()
    } else {
        format!(
            ", mean {:.1} s",
            complete.iter().sum::<f64>() / complete.len() as f64
        )
    };
    format!(
        "{} · {}: practice {} (best {:.2}), recorded {}/{} complete{mean}",
        outcome.item.embodiment,
        outcome.item.task,
        outcome.practice.len(),
        outcome.practice_score,
        complete.len(),
        outcome.recorded.len()
    )
}

/// A recorded run's completion time, if it completed (stopped without an abort).
fn completion_s(trial: &super::trial_events::RunTrial) -> Option<f64> {
    let aborted = trial.events.iter().any(|(_, e)| e["event"] == "abort");
    let start = trial.events.first()?.0;
    let stop = trial.events.last()?.0;
    (!aborted).then(|| (stop - start) as f64 * 1e-9)
}
