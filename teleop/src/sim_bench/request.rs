//! A `pomdar sim-bench` request, checked and run: the hand, the embodiments and tasks, this
//! shard's items (those already in the output directory from an interrupted run with the same
//! settings are kept, not run again), the report; or the merge of shards' directories.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use practice::{Shard, WorkItem, plan};
use retarget::{EmbodimentCatalog, HandModel};
use serde::{Deserialize, Serialize};

use super::bench_run::{BenchRun, run_bench};
use super::error::BenchError;
use super::families::{Families, PracticeSource};
use super::item::ItemSettings;
use super::outputs::{BenchReport, read_items, read_json, write, write_bench_report};
use super::{embodiments_with_abduction, merge_shards};
use crate::hand_source::HandSource;
use crate::score::score_inputs::ScoringInputs;

/// The example baseline's file in an output directory.
pub const EXAMPLE_BASELINE_FILE: &str = "example_baseline.toml";

/// The settings file of an output directory.
pub const SETTINGS_FILE: &str = "sim_bench.json";

/// What the command asks for.
pub struct BenchRequest {
    /// Embodiment names, or `all`.
    pub embodiments: Vec<String>,
    /// Task IDs, or `all`.
    pub tasks: Vec<String>,
    /// The lab's MJCF of the hand.
    pub hand: Option<PathBuf>,
    /// A URDF hand and its import file.
    pub urdf: Option<(PathBuf, PathBuf)>,
    /// Practice trials per item.
    pub budget: usize,
    /// Recorded runs per item.
    pub runs: u64,
    /// The seed.
    pub seed: u64,
    /// Glove noise, metres.
    pub jitter_m: f64,
    /// Output directory.
    pub out: PathBuf,
    /// This shard.
    pub shard: Shard,
    /// Shards' directories to merge instead of running.
    pub merge: Vec<PathBuf>,
    /// Worker threads.
    pub jobs: Option<usize>,
    /// Write trial logs.
    pub trial_logs: bool,
    /// A lab's practice file.
    pub practice: Option<PathBuf>,
    /// The station configuration.
    pub config: Option<PathBuf>,
    /// Score against the scripts' lengths as an example baseline.
    pub example_baseline: bool,
    /// Catalog, baseline, rules.
    pub scoring: ScoringInputs,
}

/// What a benchmark's results depend on; shards of one benchmark share it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BenchSettings {
    /// Embodiments, in run order.
    pub embodiments: Vec<String>,
    /// Tasks, in catalog order.
    pub tasks: Vec<String>,
    /// The hand, described.
    pub hand: String,
    /// Practice trials per item.
    pub budget: usize,
    /// Recorded runs per item.
    pub runs: u64,
    /// The seed.
    pub seed: u64,
    /// Glove noise, mm.
    pub glove_jitter_mm: f64,
    /// The practice file.
    pub practice: String,
    /// The station configuration.
    pub station: String,
    /// The baseline table's source line, if any (shards on other machines read it from
    /// other paths).
    pub baseline: Option<String>,
    /// The station's version.
    pub station_version: String,
}

impl BenchSettings {
    /// The line every report file starts with.
    pub fn header(&self) -> String {
        let scored = match &self.baseline {
            Some(b) => format!("scored against the baseline {b}"),
            None => "no baseline: correctness only (practice took each task's script length as a stand-in baseline for its speed term)".into(),
        };
        format!(
            "Seed {} · practice: {} trials per task and embodiment ({}) · {} recorded runs each, glove noise {:.1} mm, starts moved up to 5 mm and 3° · hand: {} · station: {} · {scored} · pomdar {}",
            self.seed,
            self.budget,
            self.practice,
            self.runs,
            self.glove_jitter_mm,
            self.hand,
            self.station,
            self.station_version
        )
    }
}

/// Runs the request; the exit code says whether every figure was drawn.
pub fn run_request(mut request: BenchRequest) -> Result<ExitCode, BenchError> {
    if !request.merge.is_empty() {
        return merge(&request);
    }
    let station =
        crate::station_driver::setup::load_station_config(request.config.as_deref(), None)
            .map_err(|e| BenchError::Setup(e.to_string()))?;
    let (model, hand_description) = hand_model(&request)?;
    let hand_file = request
        .hand
        .clone()
        .or_else(|| station.simulated_hand_mjcf.clone());
    let embodiments = embodiment_names(&request.embodiments, &model)?;
    let tasks = task_ids(&request.tasks, &request.scoring)?;
    let known: Vec<&str> = request
        .scoring
        .catalog
        .tasks
        .iter()
        .map(|t| t.id.as_str())
        .collect();
    let source = match &request.practice {
        Some(path) => PracticeSource::File(path.clone()),
        None => PracticeSource::Builtin,
    };
    let families = Families::load(&source, &known)?;
    if request.example_baseline {
        let table = example_baseline(&families, &tasks, &request.out, &request.scoring)?;
        request.scoring.baseline = Some(table);
    }
    let settings = bench_settings(
        &request,
        (&embodiments, &tasks),
        &families,
        (hand_file.as_deref(), &hand_description),
    );
    let done = resume(&request.out, &settings)?;
    write_settings(&request.out, &settings)?;
    let mine: Vec<WorkItem> = plan(&embodiments, &tasks)
        .into_iter()
        .filter(|i| request.shard.takes(i))
        .collect();
    let todo: Vec<WorkItem> = mine
        .iter()
        .filter(|i| {
            !done
                .iter()
                .any(|d| d.embodiment == i.embodiment && d.task == i.task)
        })
        .cloned()
        .collect();
    let jobs = request
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from));
    eprintln!(
        "pomdar sim-bench: {} of {} items (shard {}; {} done before), {} practice trials and {} recorded runs each, {jobs} workers; {}",
        todo.len(),
        mine.len(),
        request.shard,
        mine.len() - todo.len(),
        request.budget,
        request.runs,
        settings.hand
    );
    let run = BenchRun {
        items: todo,
        model: &model,
        hand_file: hand_file.as_deref(),
        station: &station,
        families: &families,
        scoring: &request.scoring,
        settings: item_settings(&request, &settings),
        jitter_m: request.jitter_m,
        jobs,
        out: request.out.clone(),
    };
    run_bench(&run)?;
    let items: Vec<_> = read_items(std::slice::from_ref(&request.out))?
        .into_iter()
        .filter(|o| {
            mine.iter()
                .any(|i| i.embodiment == o.item.embodiment && i.task == o.item.task)
        })
        .collect();
    let report = write_bench_report(
        &request.out,
        &items,
        &request.scoring,
        &embodiments_with_abduction(),
        &settings.header(),
    )?;
    Ok(summarise(&report, &request.out))
}

/// The settings record of this run.
fn bench_settings(
    request: &BenchRequest,
    (embodiments, tasks): (&[String], &[String]),
    families: &Families,
    (hand_file, hand_description): (Option<&Path>, &str),
) -> BenchSettings {
    BenchSettings {
        embodiments: embodiments.to_vec(),
        tasks: tasks.to_vec(),
        hand: match hand_file {
            Some(file) => format!("{} (MJCF) for {hand_description}", file.display()),
            None => format!("{hand_description}, written by the project"),
        },
        budget: request.budget,
        runs: request.runs,
        seed: request.seed,
        glove_jitter_mm: request.jitter_m * 1e3,
        practice: families.origin.clone(),
        station: request
            .config
            .as_ref()
            .map_or("built-in defaults".into(), |p| p.display().to_string()),
        baseline: request
            .scoring
            .baseline
            .as_ref()
            .map(|b| b.header.source.clone()),
        station_version: env!("CARGO_PKG_VERSION").into(),
    }
}

/// How each item is run.
fn item_settings(request: &BenchRequest, settings: &BenchSettings) -> ItemSettings {
    ItemSettings {
        budget: request.budget,
        runs: request.runs,
        seed: request.seed,
        trial_logs: request.trial_logs.then(|| request.out.join("trials")),
        metadata: [
            (
                "operator",
                "pomdar sim-bench (programmed practice)".to_string(),
            ),
            ("keypoint_source", "simulated glove".to_string()),
            ("simulated_hand", settings.hand.clone()),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect(),
    }
}

/// An example baseline: each task's script as written, its length as the time; written to
/// `out/example_baseline.toml`.
fn example_baseline(
    families: &Families,
    tasks: &[String],
    out: &Path,
    scoring: &ScoringInputs,
) -> Result<scoring::BaselineTable, BenchError> {
    let mut text = String::from(
        "# EXAMPLE baseline written by pomdar sim-bench --example-baseline: not a human baseline.\n\
         [baseline]\nexample = true\nsource = \"EXAMPLE, not human: each task's glove script as written, its length in seconds\"\n",
    );
    for task in tasks {
        if let Some(family) = families.tasks.get(task) {
            let length = family.family.script.duration_s();
            text.push_str(&format!(
                "\n[[task]]\nid = \"{task}\"\nmean_s = {length:.3}\nn = 1\n"
            ));
        }
    }
    let path = out.join(EXAMPLE_BASELINE_FILE);
    write(&path, text.as_bytes())?;
    baseline_table(&text, &path, scoring)
}

fn baseline_table(
    text: &str,
    path: &Path,
    scoring: &ScoringInputs,
) -> Result<scoring::BaselineTable, BenchError> {
    scoring::BaselineTable::from_toml_str(text, &path.display().to_string(), &scoring.catalog)
        .map_err(|e| BenchError::Setup(e.to_string()))
}

/// `--merge`: the shards' directories joined into `out`.
fn merge(request: &BenchRequest) -> Result<ExitCode, BenchError> {
    let settings = shard_settings(&request.merge)?;
    let mut scoring = request.scoring.clone();
    if request.example_baseline {
        let path = request.merge[0].join(EXAMPLE_BASELINE_FILE);
        let text = std::fs::read_to_string(&path).map_err(|source| BenchError::Read {
            path: path.clone(),
            source,
        })?;
        let copy = request.out.join(EXAMPLE_BASELINE_FILE);
        write(&copy, text.as_bytes())?;
        scoring.baseline = Some(baseline_table(&text, &copy, &scoring)?);
    }
    let scoring = &scoring;
    let report = merge_shards(&request.merge, &request.out, scoring, &settings.header())?;
    write_settings(&request.out, &settings)?;
    Ok(summarise(&report, &request.out))
}

/// The hand model and its description.
fn hand_model(request: &BenchRequest) -> Result<(HandModel, String), BenchError> {
    let source = match &request.urdf {
        Some((urdf, import)) => HandSource::Urdf {
            urdf: urdf.clone(),
            import: import.clone(),
        },
        None => HandSource::BuiltinOrcaV1Right,
    };
    let model = source
        .load()
        .map_err(|e| BenchError::Setup(e.to_string()))?;
    Ok((model, source.describe()))
}

/// `all` → every embodiment of the built-in catalog, fewest DoF first; else the names, each
/// checked against the catalog and the hand.
fn embodiment_names(names: &[String], model: &HandModel) -> Result<Vec<String>, BenchError> {
    let catalog = EmbodimentCatalog::builtin();
    let mut list: Vec<String> = if names.iter().any(|n| n == "all") {
        let mut all: Vec<_> = catalog.embodiments.iter().collect();
        all.sort_by_key(|e| e.dof);
        all.into_iter().map(|e| e.name.clone()).collect()
    } else {
        names.to_vec()
    };
    list.dedup();
    for name in &list {
        let embodiment = catalog.get(name).ok_or_else(|| {
            BenchError::Setup(format!(
                "--embodiment {name}: not an embodiment (known: {}, or all)",
                catalog.names().collect::<Vec<_>>().join(", ")
            ))
        })?;
        embodiment
            .unlocked_mask(model)
            .map_err(|e| BenchError::Setup(format!("--embodiment {name}: {e}")))?;
    }
    Ok(list)
}

/// `all` → every catalog task; else the IDs in catalog order, each checked.
fn task_ids(ids: &[String], scoring: &ScoringInputs) -> Result<Vec<String>, BenchError> {
    let all = ids.iter().any(|t| t == "all");
    for id in ids.iter().filter(|t| *t != "all") {
        if scoring.catalog.get(id).is_none() {
            return Err(BenchError::Setup(format!(
                "--tasks {id}: not a task of the catalog (known: {}, or all)",
                scoring.catalog.ids()
            )));
        }
    }
    Ok(scoring
        .catalog
        .tasks
        .iter()
        .filter(|t| all || ids.contains(&t.id))
        .map(|t| t.id.clone())
        .collect())
}

/// The items an interrupted run with the same settings left in `out`; an error if `out`
/// holds another benchmark's results.
fn resume(out: &Path, settings: &BenchSettings) -> Result<Vec<WorkItem>, BenchError> {
    let path = out.join(SETTINGS_FILE);
    if !path.is_file() {
        return Ok(Vec::new());
    }
    let earlier: BenchSettings = read_json(&path)?;
    if &earlier != settings {
        return Err(BenchError::Setup(format!(
            "{} holds the results of a benchmark with other settings ({}): choose another --out",
            out.display(),
            path.display()
        )));
    }
    if !out.join(super::outputs::ITEMS_DIR).is_dir() {
        return Ok(Vec::new());
    }
    Ok(read_items(&[out.to_path_buf()])?
        .into_iter()
        .map(|o| o.item)
        .collect())
}

/// The settings every shard directory holds; an error if they differ.
fn shard_settings(dirs: &[PathBuf]) -> Result<BenchSettings, BenchError> {
    let mut found: Option<(PathBuf, BenchSettings)> = None;
    for dir in dirs {
        let path = dir.join(SETTINGS_FILE);
        let settings: BenchSettings = read_json(&path)?;
        if let Some((first, earlier)) = &found {
            if earlier != &settings {
                return Err(BenchError::Setup(format!(
                    "{} and {} are shards of different benchmarks (their {SETTINGS_FILE} differ)",
                    first.display(),
                    path.display()
                )));
            }
        } else {
            found = Some((path, settings));
        }
    }
    found
        .map(|(_, s)| s)
        .ok_or_else(|| BenchError::Setup("--merge needs a directory".into()))
}

fn write_settings(out: &Path, settings: &BenchSettings) -> Result<(), BenchError> {
    let text = serde_json::to_string_pretty(settings).unwrap_or_default();
    write(&out.join(SETTINGS_FILE), text.as_bytes())
}

/// The table, the findings, and where the files went.
fn summarise(report: &BenchReport, out: &Path) -> ExitCode {
    print!("{}", scoring::render_terminal(&report.report));
    println!("\nThe paper's findings:");
    for f in &report.findings {
        println!("  {:<28} {:<10} {}", f.id, f.verdict.word(), f.why);
    }
    for e in &report.figure_errors {
        eprintln!("error: {e}");
    }
    eprintln!("wrote {} files to {}", report.files.len(), out.display());
    if report.figure_errors.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
