//! One embodiment on one task: programmed practice (a seeded cross-entropy search over the
//! task's strategy family, each practice trial one run scored the POMDAR way), then the
//! recorded runs of the best strategy, each kept as a trial (and, if asked, written as a
//! trial log).

use std::collections::BTreeMap;
use std::path::PathBuf;

use practice::{CrossEntropySearch, StrategyFamily, StrategyParams, WorkItem, practice_score};
use retarget::human_hand::SplitMix64;
use serde::{Deserialize, Serialize};

use super::error::BenchError;
use super::play::{ItemSetup, PlayedRun, play};
use super::trial_events::{RunTrial, run_trial};
use super::trial_log::TrialLogWriter;
use crate::score::score_inputs::ScoringInputs;
use crate::station_node::recorder::config_digest;

/// Seeds of practice trials start here above the benchmark's seed, far from the recorded
/// runs' (the seed and the next ones): practice never sees a recorded run's noise or start.
pub const PRACTICE_SEED_OFFSET: u64 = 1_000_000;

/// How an item is run.
#[derive(Debug, Clone)]
pub struct ItemSettings {
    /// Practice trials.
    pub budget: usize,
    /// Recorded runs of the chosen strategy.
    pub runs: u64,
    /// The benchmark's seed.
    pub seed: u64,
    /// Where to write a trial log per recorded run (`DIR/EMBODIMENT/TASK/run_NN.mcap`).
    pub trial_logs: Option<PathBuf>,
    /// Metadata every trial carries (the hand, the station's version).
    pub metadata: BTreeMap<String, String>,
}

/// A practice trial.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PracticeTrial {
    /// The strategy tried.
    pub params: StrategyParams,
    /// Its seed.
    pub seed: u64,
    /// Its correctness.
    pub correctness: f64,
    /// When it completed, simulated seconds.
    pub completed_at_s: Option<f64>,
    /// The practice score.
    pub score: f64,
}

/// A recorded run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RecordedRun {
    /// Its seed.
    pub seed: u64,
    /// The trial.
    pub trial: RunTrial,
    /// The trial log written, if any.
    pub log: Option<PathBuf>,
}

/// What an item produced.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ItemOutcome {
    /// The item.
    pub item: WorkItem,
    /// The strategy practice chose.
    pub strategy: StrategyParams,
    /// Its mean practice score.
    pub practice_score: f64,
    /// Every practice trial, in order.
    pub practice: Vec<PracticeTrial>,
    /// The recorded runs.
    pub recorded: Vec<RecordedRun>,
}

/// The seed of an item's search: the benchmark's seed keyed by the embodiment and the task
/// (so a shard, or a run of fewer tasks, searches alike).
pub fn search_seed(seed: u64, item: &WorkItem) -> u64 {
    let name = format!("{}/{}", item.embodiment, item.task);
    name.bytes()
        .fold(SplitMix64::new(seed), |rng, b| {
            let mut rng = rng;
            SplitMix64::keyed(rng.next_u64(), u64::from(b))
        })
        .next_u64()
}

/// Runs `item`: practice over `family`, then the recorded runs.
pub fn run_item(
    setup: &ItemSetup<'_>,
    family: &StrategyFamily,
    scoring: &ScoringInputs,
    settings: &ItemSettings,
    item: &WorkItem,
) -> Result<ItemOutcome, BenchError> {
    let stand_in_s = family.script.duration_s();
    let mut search = CrossEntropySearch::new(
        family.space(),
        settings.budget,
        search_seed(settings.seed, item),
    );
    let mut practice = Vec::new();
    while let Some(candidate) = search.ask() {
        let params = family.params(&candidate);
        let seed = settings
            .seed
            .wrapping_add(PRACTICE_SEED_OFFSET + practice.len() as u64);
        let run = play(setup, &family.strategy(&params), seed, None)?;
        let trial = run_trial(
            metadata(settings, setup, item, true, practice.len()),
            &run.events,
            run.completed_at_s,
            run.end_s,
        );
        let scored = score(scoring, &trial, item, "practice")?;
        let score = practice_score(&scored, &scoring.rules, stand_in_s);
        search.tell(score);
        practice.push(PracticeTrial {
            params,
            seed,
            correctness: run.correctness,
            completed_at_s: run.completed_at_s,
            score,
        });
    }
    let (strategy, practice_mean) = search
        .best()
        .map_or((StrategyParams::AS_WRITTEN, 0.0), |best| {
            (family.params(&best.candidate), best.mean())
        });
    let chosen = family.strategy(&strategy);
    let mut recorded = Vec::new();
    for k in 0..settings.runs {
        let seed = settings.seed.wrapping_add(k);
        let metadata = metadata(settings, setup, item, false, k as usize);
        let log = settings.trial_logs.as_ref().map(|dir| {
            dir.join(&item.embodiment)
                .join(&item.task)
                .join(format!("run_{:02}.mcap", k + 1))
        });
        let run = match &log {
            Some(path) => play_logged(setup, &chosen, seed, path, &metadata)?,
            None => play(setup, &chosen, seed, None)?,
        };
        let trial = run_trial(metadata, &run.events, run.completed_at_s, run.end_s);
        recorded.push(RecordedRun { seed, trial, log });
    }
    Ok(ItemOutcome {
        item: item.clone(),
        strategy,
        practice_score: practice_mean,
        practice,
        recorded,
    })
}

/// A run played with its trial log written beside.
fn play_logged(
    setup: &ItemSetup<'_>,
    strategy: &practice::Strategy,
    seed: u64,
    path: &std::path::Path,
    metadata: &BTreeMap<String, String>,
) -> Result<PlayedRun, BenchError> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| BenchError::Write {
            path: dir.to_path_buf(),
            reason: e.to_string(),
        })?;
    }
    let mut writer = TrialLogWriter::start(path, &setup.station, metadata.clone())?;
    let run = play(setup, strategy, seed, Some(&mut writer))?;
    writer.finish(run.completed_at_s, run.end_s)?;
    Ok(run)
}

/// A trial's metadata: the task, the embodiment, practice or not, its index, and the
/// benchmark's entries (the recorder adds the station's own when it writes a log; the same
/// values are added here).
fn metadata(
    settings: &ItemSettings,
    setup: &ItemSetup<'_>,
    item: &WorkItem,
    practice: bool,
    index: usize,
) -> BTreeMap<String, String> {
    let mut m = settings.metadata.clone();
    m.insert("station_version".into(), env!("CARGO_PKG_VERSION").into());
    m.insert("config_digest".into(), config_digest(&setup.station));
    m.insert("layout".into(), setup.station.retarget.layout.name().into());
    m.insert("task".into(), item.task.clone());
    m.insert("embodiment".into(), item.embodiment.clone());
    m.insert("practice".into(), practice.to_string());
    m.insert("trial_index".into(), (index + 1).to_string());
    m
}

/// A trial scored against the run's baseline and rules.
pub fn score(
    scoring: &ScoringInputs,
    trial: &RunTrial,
    item: &WorkItem,
    what: &str,
) -> Result<scoring::TrialScore, BenchError> {
    let source = format!("{}/{}/{what}", item.embodiment, item.task);
    scoring::score_trial(
        &trial.log(&source),
        &scoring.catalog,
        scoring.baseline.as_ref(),
        &scoring.rules,
    )
    .map_err(|e| BenchError::Scoring {
        embodiment: item.embodiment.clone(),
        task: item.task.clone(),
        reason: e.to_string(),
    })
}
