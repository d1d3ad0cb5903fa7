//! Benchmark: scoring the paper's 1,140 trials from their MCAP files.
//!
//! `cargo bench -p teleop --bench score_trials` generates, once, a realistic trial set in the
//! system temp dir (`pomdar_score_bench/`, reused while its stamp matches): 4 embodiments ×
//! 18 tasks × 15 recorded trials plus 60 practice trials = 1,140 files, and 54 human trials
//! for the baseline. Each is written as the station records it (`write_synthetic_trial`: zstd
//! chunks closed at every event and once per second, 22-point glove keypoints at 100 Hz and
//! 17 joint targets at 25 Hz for the trial's seeded 10–60 s, the metadata record and the
//! trial events). Generation takes a few minutes and shows its progress.
//!
//! Then it times, three times over, what `pomdar score DIR` does minus the printing: find the
//! files, read each one's metadata and events through the summary, score, aggregate, render
//! the terminal, Markdown, CSV and JSON reports (in memory); and, separately, the figures.
//! Prints one JSON line per pass, the chunks the reader decompressed against the chunks in
//! the files, a whole-file read of one file in 20 for comparison, and a summary line. The
//! files are in the page cache after generation (a first read from a cold disk is slower).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a benchmark fails loudly

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use scoring::{
    BaselineTable, CorrectnessKind, ReportInputs, ScoreReport, TaskCatalog, TrialRecord,
    compute_baseline, render_figures, render_markdown, render_overall_csv, render_scores_csv,
    render_terminal, render_trials_csv, score_trial,
};
use serde_json::{Value, json};
use teleop::mcap_log::{TrialReader, read_trial_events};
use teleop::progress_bar::ProgressStyle;
use teleop::score::load_trial::load_trial_log;
use teleop::score::parallel_files::process_files;
use teleop::score::score_inputs::ScoringInputs;
use teleop::score::synthetic_trial::{SplitMix64, SyntheticTrial, write_synthetic_trial};
use teleop::score::trial_files::collect_trial_files;

const STAMP: &str = "score_trials bench set v1: 4 embodiments x 18 tasks x 15 recorded + 60 practice = 1140 trials, 54 human; seed 7; keypoints 100 Hz, joint targets 25 Hz, 10-60 s";
const EMBODIMENTS: [&str; 4] = ["orca_full", "orca_5", "orca_3", "orca_2"];
const RECORDED: usize = 15;
const PRACTICE_TOTAL: usize = 60;
const T0_NS: i64 = 1_732_100_000_000_000_000;
const PASSES: usize = 3;

struct Planned {
    path: PathBuf,
    trial: SyntheticTrial,
}

fn events_for(kind: CorrectnessKind, duration_s: f64, rng: &mut SplitMix64) -> Vec<(f64, Value)> {
    let (start, end) = (0.5, duration_s - 0.5);
    let mut marks: Vec<Value> = Vec::new();
    match kind {
        CorrectnessKind::Notches { count } | CorrectnessKind::Curves { count } => {
            let reached = if rng.next_f64() < 0.6 {
                count
            } else {
                (rng.next_f64() * f64::from(count + 1)) as u32
            };
            marks.extend((0..reached).map(|_| json!({"event": "progress", "value": 1})));
        }
        CorrectnessKind::Rotation { .. } => {
            for _ in 0..(4 + (rng.next_f64() * 5.0) as usize) {
                marks.push(json!({"event": "progress", "value": (rng.next_f64() * 90.0).round()}));
            }
        }
        CorrectnessKind::Distance { .. } => {
            for _ in 0..3 {
                marks.push(json!({"event": "progress", "value": (rng.next_f64() * 70.0).round()}));
            }
        }
        CorrectnessKind::Grasp {} => {
            let r = rng.next_f64();
            if r < 0.6 {
                marks.push(json!({"event": "progress", "value": 0.5}));
                marks.push(json!({"event": "progress", "value": 1.0}));
            } else if r < 0.85 {
                marks.push(json!({"event": "progress", "value": 0.5}));
                marks.push(json!({"event": "drop"}));
            }
        }
    }
    if rng.next_f64() < 0.1 {
        marks.push(json!({"event": "note", "text": "glove re-seated"}));
    }
    let mut events = vec![(start, json!({"event": "start"}))];
    let step = (end - start) / (marks.len() + 1) as f64;
    for (i, m) in marks.into_iter().enumerate() {
        events.push((start + step * (i + 1) as f64, m));
    }
    if rng.next_f64() < 0.03 {
        events.push((
            end - 0.2,
            json!({"event": "abort", "reason": "object fell off"}),
        ));
    }
    events.push((
        end,
        json!({"event": "stop", "summary": {"frames": (duration_s * 100.0) as u64}}),
    ));
    events
}

fn plan(root: &Path) -> Vec<Planned> {
    let catalog = TaskCatalog::builtin();
    let mut rng = SplitMix64::new(7);
    let mut planned = Vec::new();
    let mut practice_left = PRACTICE_TOTAL;
    let mut add = |path: PathBuf,
                   e: &str,
                   task: &scoring::TaskSpec,
                   practice: bool,
                   user: &str,
                   index: usize,
                   duration_s: f64,
                   rng: &mut SplitMix64| {
        let metadata = BTreeMap::from([
            ("task".to_string(), task.id.clone()),
            ("embodiment".to_string(), e.to_string()),
            ("practice".to_string(), practice.to_string()),
            ("user".to_string(), user.to_string()),
            ("operator".to_string(), "bench".to_string()),
            ("trial_index".to_string(), index.to_string()),
            ("layout".to_string(), "lab22".to_string()),
        ]);
        let events = events_for(task.correctness, duration_s, rng);
        let seed = rng.next_u64();
        planned.push(Planned {
            path,
            trial: SyntheticTrial {
                metadata,
                t0_ns: T0_NS + planned.len() as i64 * 100_000_000_000,
                duration_s,
                events,
                keypoint_rate_hz: 100.0,
                joint_rate_hz: 25.0,
                seed,
            },
        });
    };
    for e in EMBODIMENTS {
        for task in &catalog.tasks {
            let practice = usize::from(practice_left > 0);
            practice_left -= practice;
            for i in 0..practice + RECORDED {
                let duration = 10.0 + 50.0 * rng.next_f64();
                let path = root.join(format!(
                    "trials/{e}/{}/{e}_{}_{i:02}.mcap",
                    task.id, task.id
                ));
                add(path, e, task, i < practice, "op1", i, duration, &mut rng);
            }
        }
    }
    for task in &catalog.tasks {
        for user in ["h1", "h2", "h3"] {
            let duration = 5.0 + 20.0 * rng.next_f64();
            let path = root.join(format!("human/{}/human_{}_{user}.mcap", task.id, task.id));
            add(path, "human", task, false, user, 0, duration, &mut rng);
        }
    }
    planned
}

fn ensure_set(root: &Path) {
    let stamp = root.join("STAMP");
    if std::fs::read_to_string(&stamp).is_ok_and(|s| s == STAMP) {
        eprintln!("reusing the trial set in {}", root.display());
        return;
    }
    let _ = std::fs::remove_dir_all(root);
    let planned = plan(root);
    for p in &planned {
        std::fs::create_dir_all(p.path.parent().unwrap()).unwrap();
    }
    eprintln!(
        "generating {} trial files in {} (once)",
        planned.len(),
        root.display()
    );
    let started = Instant::now();
    let paths: Vec<PathBuf> = planned.iter().map(|p| p.path.clone()).collect();
    let by_path: BTreeMap<&Path, &SyntheticTrial> = planned
        .iter()
        .map(|p| (p.path.as_path(), &p.trial))
        .collect();
    let results = process_files(
        &paths,
        |path| write_synthetic_trial(path, by_path[path]).map(|_| ()),
        ProgressStyle::redraw_on_terminal(ProgressStyle::Lines { every: 100 }),
        "files generated",
    );
    for r in results {
        r.unwrap();
    }
    std::fs::write(&stamp, STAMP).unwrap();
    eprintln!("generated in {:.0} s", started.elapsed().as_secs_f64());
}

fn dir_bytes(dir: &Path) -> u64 {
    let mut total = 0;
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let m = entry.metadata().unwrap();
        total += if m.is_dir() {
            dir_bytes(&entry.path())
        } else {
            m.len()
        };
    }
    total
}

/// The baseline from the human trials under `root/human`.
fn human_baseline(root: &Path, inputs: &ScoringInputs) -> BaselineTable {
    let human = collect_trial_files(&[root.join("human")]);
    let records: Vec<TrialRecord> = process_files(
        &human.files,
        |p| TrialRecord::from_log(&load_trial_log(p).unwrap(), &inputs.catalog).unwrap(),
        ProgressStyle::Silent,
        "",
    );
    compute_baseline(&records, &inputs.catalog, &inputs.rules, "bench").table
}

/// One timed pass of `pomdar score` minus the printing: find, read and score every trial,
/// build the report and render it (terminal, Markdown, CSV, JSON) in memory; then, timed
/// apart, the figures. Prints the pass's JSON line; returns the report and both durations.
fn score_pass(
    root: &Path,
    inputs: &ScoringInputs,
    baseline: &BaselineTable,
    pass: usize,
    workers: usize,
) -> (ScoreReport, f64, f64) {
    let started = Instant::now();
    let found = collect_trial_files(&[root.join("trials")]);
    let results = process_files(
        &found.files,
        |p| {
            let log = load_trial_log(p).map_err(|e| e.to_string())?;
            score_trial(&log, &inputs.catalog, Some(baseline), &inputs.rules)
                .map_err(|e| e.to_string())
        },
        ProgressStyle::Silent,
        "",
    );
    let scores: Vec<_> = results.into_iter().map(Result::unwrap).collect();
    let files = scores.len();
    let report = ScoreReport::build(ReportInputs {
        catalog: &inputs.catalog,
        baseline: Some(baseline),
        rules: &inputs.rules,
        rules_origin: &inputs.rules_origin,
        dof: &inputs.dof,
        scores,
        rejected: Vec::new(),
        skipped: Vec::new(),
    });
    let rendered = render_terminal(&report).len()
        + render_markdown(&report).len()
        + render_scores_csv(&report).len()
        + render_overall_csv(&report).len()
        + render_trials_csv(&report).len()
        + report.to_json().len();
    let scoring_s = started.elapsed().as_secs_f64();

    let started = Instant::now();
    let (figures, _, errors) = render_figures(&report);
    let figures_s = started.elapsed().as_secs_f64();
    assert!(errors.is_empty() && figures.len() == 4);
    println!(
        "{{\"bench\":\"score_trials\",\"pass\":{pass},\"files\":{files},\"workers\":{workers},\
         \"scoring_s\":{scoring_s:.3},\"per_file_ms\":{:.3},\"report_bytes\":{rendered},\
         \"figures\":{},\"figures_s\":{figures_s:.3}}}",
        scoring_s * 1000.0 / files as f64,
        figures.len()
    );
    (report, scoring_s, figures_s)
}

/// What the summary-indexed reader saves: chunks it decompressed, and a whole-file read
/// (`TrialReader`, every message decoded into memory) of one file in 20 for comparison.
/// Prints its JSON line.
fn print_reader_savings(root: &Path) {
    let found = collect_trial_files(&[root.join("trials")]);
    let (mut read, mut total) = (0, 0);
    for path in &found.files {
        let events = read_trial_events(path).unwrap();
        read += events.chunks_read;
        total += events.chunks_total;
    }
    let sample: Vec<&PathBuf> = found.files.iter().step_by(20).collect();
    let started = Instant::now();
    for path in &sample {
        std::hint::black_box(TrialReader::open(path).unwrap().message_count());
    }
    let whole_ms = started.elapsed().as_secs_f64() * 1000.0 / sample.len() as f64;
    println!(
        "{{\"bench\":\"score_trials\",\"chunks_decompressed\":{read},\"chunks_total\":{total},\
         \"whole_file_read_ms_per_file\":{whole_ms:.2},\"whole_file_sample\":{}}}",
        sample.len()
    );
}

/// The summary line: set size, baseline time, the median pass's scoring time and each
/// embodiment's overall score from the last report.
fn print_summary(root: &Path, report: &ScoreReport, baseline_s: f64, median_s: f64) {
    let overall: Vec<String> = report
        .embodiments
        .iter()
        .map(|e| {
            format!(
                "{} {:.2}",
                e.embodiment,
                e.overall_attempted.unwrap_or(f64::NAN)
            )
        })
        .collect();
    println!(
        "{{\"bench\":\"score_trials\",\"summary\":true,\"files\":{},\"set_bytes\":{},\"baseline_s\":{baseline_s:.3},\
         \"scoring_median_s\":{median_s:.3},\"per_file_ms\":{:.3},\"overall\":\"{}\"}}",
        report.trials.len(),
        dir_bytes(&root.join("trials")),
        median_s * 1000.0 / report.trials.len() as f64,
        overall.join(", ")
    );
}

fn main() {
    let root = std::env::temp_dir().join("pomdar_score_bench");
    ensure_set(&root);
    let workers = std::thread::available_parallelism().map_or(1, |n| n.get());

    // The baseline's time includes loading the catalog and rules.
    let started = Instant::now();
    let inputs = ScoringInputs::load(None, None, None).unwrap();
    let baseline = human_baseline(&root, &inputs);
    let baseline_s = started.elapsed().as_secs_f64();
    assert_eq!(baseline.tasks.len(), 18);

    let mut passes = Vec::new();
    let mut last_report = None;
    for pass in 1..=PASSES {
        let (report, scoring_s, figures_s) = score_pass(&root, &inputs, &baseline, pass, workers);
        passes.push((scoring_s, figures_s));
        last_report = Some(report);
    }
    let report = last_report.unwrap();

    print_reader_savings(&root);
    passes.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (median_s, _) = passes[PASSES / 2];
    print_summary(&root, &report, baseline_s, median_s);
}
