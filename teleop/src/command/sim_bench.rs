//! `pomdar sim-bench`: the simulated benchmark with no one at the glove — its flags, their
//! checks, and one call (the work is in `teleop::sim_bench`). Built with the `physics`
//! feature only; without it the command says how to get it.

use std::path::PathBuf;

use clap::Args;

use crate::score::score_inputs::ScoringFileArgs;

/// The benchmark without a teleoperator: every embodiment scored in simulation (needs the
/// `physics` build).
///
/// Per embodiment and task, programmed practice: a seeded cross-entropy search over the
/// task's family of glove strategies (its script with the start placement, the approach,
/// the reach, which digits close and how far, and the timing varied), each practice trial
/// a lock-step run through the station core (retargeting to the embodiment, its other
/// joints locked) into the physics, scored the POMDAR way. Then recorded runs of the best
/// strategy at the glove's noise with moved starts, timed by the physics' completion
/// event. Writes the report `pomdar score` writes, the strategies chosen and the paper's
/// findings checked; shows a line per task and embodiment; same seed, same report.
///
/// Examples:
///   pomdar sim-bench --embodiment all --out reports/sim_bench/
///   pomdar sim-bench --embodiment orca_2,orca_full --tasks G4,H5,C1 --budget 12 --out quick/
///   pomdar sim-bench --shard 2/4 --out shard2/   (then: pomdar sim-bench --merge shard*/ --out all/)
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct SimBenchArgs {
    /// Embodiments: orca_2, orca_3, orca_5, orca_full (the built-in catalog), a
    /// comma-separated list of them, or all.
    #[arg(
        long,
        default_value = "all",
        value_delimiter = ',',
        value_name = "NAMES"
    )]
    pub embodiment: Vec<String>,
    /// Tasks: catalog IDs, comma-separated (G4,H5,C1), or all.
    #[arg(long, default_value = "all", value_delimiter = ',', value_name = "IDS")]
    pub tasks: Vec<String>,
    /// The simulated hand: a lab's MuJoCo model of it (the manufacturer's MJCF of ORCA v1,
    /// meshes beside it; joints named as the URDF's degrees of freedom). Default: the station
    /// configuration's simulated_hand_mjcf, else the hand the project writes from the hand
    /// model (the built-in ORCA v1, or the --urdf hand).
    #[arg(long, value_name = "FILE")]
    pub hand: Option<PathBuf>,
    /// A URDF hand the station imports, instead of the built-in ORCA v1 (needs --import): the
    /// station retargets to it and the project writes its simulated hand from it.
    #[arg(long, value_name = "FILE", requires = "import")]
    pub urdf: Option<PathBuf>,
    /// The import file naming the URDF's frames (launch_configs/hands/*.toml).
    #[arg(long, value_name = "FILE", requires = "urdf")]
    pub import: Option<PathBuf>,
    /// Practice trials per task and embodiment, 1–1000: the search's budget.
    #[arg(long, default_value_t = 16, value_name = "N")]
    pub budget: usize,
    /// Recorded runs of the chosen strategy per task and embodiment, 1–1000.
    #[arg(long, default_value_t = 20, value_name = "N")]
    pub runs: u64,
    /// The seed: recorded run k plays with seed + k (its glove noise and moved start); the
    /// searches and practice trials are drawn from it too. Same seed, same report.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// The glove's keypoint noise, standard deviation in mm, 0–50.
    #[arg(long, default_value_t = 1.0, value_name = "MM")]
    pub glove_jitter_mm: f64,
    /// Output directory: the POMDAR report (as `pomdar score --out` writes it), strategies.md
    /// and .json, findings.md and .json, items/ (one file per task and embodiment) and, with
    /// --trial-logs, trials/.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Do only shard K of N of the work (1 ≤ K ≤ N), e.g. one task of a batch scheduler's
    /// array job per shard; join the shards' directories with --merge.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<practice::Shard>,
    /// Join the output directories of a benchmark's shards into --out: the whole report,
    /// strategies and findings (nothing is simulated).
    #[arg(long, num_args = 1.., value_name = "DIR", conflicts_with = "shard")]
    pub merge: Vec<PathBuf>,
    /// Worker threads (default: the machine's cores).
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,
    /// Write a trial log per recorded run (trials/EMBODIMENT/TASK/run_NN.mcap), as a live
    /// station writes it: `pomdar score` scores them, `pomdar replay` replays them.
    #[arg(long)]
    pub trial_logs: bool,
    /// A lab's practice file (default: the built-in launch_configs/sim/practice.toml).
    #[arg(long, value_name = "FILE")]
    pub practice: Option<PathBuf>,
    /// Station configuration the runs start from (topics, retargeting, arm start pose,
    /// simulated_hand_mjcf, [simulated_physics]); each task's station file and embodiment are
    /// laid over it.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Without a lab's --baseline: score against an EXAMPLE baseline, each task's glove script
    /// as written taking its length in seconds (not a human baseline; every report says so),
    /// written to OUT/example_baseline.toml so `pomdar score --baseline` reads the same.
    #[arg(long, conflicts_with = "baseline")]
    pub example_baseline: bool,
    /// The baseline, catalog and rules the runs are scored with.
    #[command(flatten)]
    pub files: ScoringFileArgs,
}

/// `pomdar sim-bench`.
#[cfg(not(feature = "physics"))]
pub fn sim_bench(_args: SimBenchArgs) -> anyhow::Result<std::process::ExitCode> {
    anyhow::bail!(
        "this pomdar was built without the simulator: run `bash sim/setup_mujoco.sh` once, then \
         build with `cargo build --release --features physics` (README, \"The benchmark without a teleoperator\")"
    )
}

/// `pomdar sim-bench`.
#[cfg(feature = "physics")]
pub fn sim_bench(args: SimBenchArgs) -> anyhow::Result<std::process::ExitCode> {
    use crate::sim_bench::request::{BenchRequest, run_request};
    check_ranges(&args)?;
    let request = BenchRequest {
        embodiments: args.embodiment,
        tasks: args.tasks,
        hand: args.hand,
        urdf: args.urdf.zip(args.import),
        budget: args.budget,
        runs: args.runs,
        seed: args.seed,
        jitter_m: args.glove_jitter_mm * 1e-3,
        out: args.out,
        shard: args.shard.unwrap_or(practice::Shard::WHOLE),
        merge: args.merge,
        jobs: args.jobs,
        trial_logs: args.trial_logs,
        practice: args.practice,
        config: args.config,
        example_baseline: args.example_baseline,
        scoring: args.files.load()?,
    };
    Ok(run_request(request)?)
}

/// The numbers' ranges.
#[cfg(feature = "physics")]
fn check_ranges(args: &SimBenchArgs) -> anyhow::Result<()> {
    if !(1..=1000).contains(&args.budget) {
        anyhow::bail!("--budget {} must be in [1, 1000]", args.budget);
    }
    if !(1..=1000).contains(&args.runs) {
        anyhow::bail!("--runs {} must be in [1, 1000]", args.runs);
    }
    if !(0.0..=50.0).contains(&args.glove_jitter_mm) {
        anyhow::bail!(
            "--glove-jitter-mm {} must be in [0, 50]",
            args.glove_jitter_mm
        );
    }
    if args.jobs == Some(0) {
        anyhow::bail!("--jobs must be at least 1");
    }
    Ok(())
}
