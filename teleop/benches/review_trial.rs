//! Benchmark: `pomdar review` on a 60 s trial log.
//!
//! `cargo bench -p teleop --bench review_trial` records, once, a 60 s run of the whole pipeline
//! as `pomdar demo --duration 60 --out DIR` does (the simulated glove at 100 Hz, the station,
//! the mock hand's measured state, the arm, the status at 5 Hz) into the system temp dir
//! (`pomdar_review_bench/`, reused while it is there; recording takes the minute), then times
//! five reviews of it as the command and the operator console run them
//! (`teleop::trial_review::review_trial_file`: read the log, review, draw the figure, write the
//! PNG, SVG and JSON). Prints one JSON line per pass and a summary; the budget is 1 s.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a benchmark fails loudly

use std::path::PathBuf;
use std::time::Instant;

use review::FeedbackSettings;
use station::StationConfig;
use teleop::demo::{DemoOptions, run_demo};
use teleop::stand_ins::sim_glove_node::SimGloveConfig;
use teleop::trial_review::review_trial_file;

const SECONDS: f64 = 60.0;
const PASSES: usize = 5;

/// The recorded 60 s run, made on the first use.
fn recorded_run(dir: &std::path::Path) -> PathBuf {
    let existing = std::fs::read_dir(dir)
        .ok()
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .find(|p| p.extension().is_some_and(|e| e == "mcap"));
    if let Some(path) = existing {
        return path;
    }
    eprintln!(
        "recording a {SECONDS} s demo run into {} (once)",
        dir.display()
    );
    std::fs::create_dir_all(dir).unwrap();
    let runtime = tokio::runtime::Runtime::new().unwrap();
    let outcome = runtime
        .block_on(run_demo(DemoOptions {
            duration_s: SECONDS,
            domain_id: teleop::ros::default_domain_id(),
            station: StationConfig::default(),
            glove: SimGloveConfig::default(),
            live: false,
            out: Some(dir.to_path_buf()),
            tap: None,
            physics: None,
        }))
        .unwrap();
    outcome.recorded.expect("the demo recorded its run")
}

fn main() {
    let dir = std::env::temp_dir().join("pomdar_review_bench");
    let log = recorded_run(&dir);
    let out = dir.join("review");
    std::fs::create_dir_all(&out).unwrap();
    let config = StationConfig::default();
    let settings = FeedbackSettings::default();
    let mut seconds = Vec::new();
    for pass in 0..PASSES {
        let start = Instant::now();
        let files = review_trial_file(&log, &config, &settings, Some(&out)).unwrap();
        let took = start.elapsed().as_secs_f64();
        seconds.push(took);
        println!(
            "{{\"pass\":{pass},\"seconds\":{took:.3},\"trial_s\":{:.1},\"glove_frames\":{},\"feedback\":{},\"png_bytes\":{},\"svg_bytes\":{}}}",
            files.review.duration_s,
            files.review.glove.frames,
            files.review.feedback.len(),
            std::fs::metadata(&files.png).unwrap().len(),
            std::fs::metadata(&files.svg).unwrap().len(),
        );
    }
    seconds.sort_by(f64::total_cmp);
    println!(
        "review of a {SECONDS} s trial: median {:.3} s, max {:.3} s over {PASSES} passes (budget 1 s)",
        seconds[PASSES / 2],
        seconds[PASSES - 1]
    );
}
