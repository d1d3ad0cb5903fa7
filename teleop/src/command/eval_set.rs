//! `pomdar eval-set`: an evaluation set of transformed copies of real recordings (the work
//! is in [`crate::eval::eval_set`]).

use std::path::PathBuf;

use clap::Args;

use super::shared_args::readable_mcap_files;
use crate::atomic_file::write_atomically;
use crate::eval::eval_set::build_set;
use crate::station_driver::setup::load_station_config;

/// Build an evaluation set: transformed copies of real recordings for `pomdar eval`.
///
/// Each recording's distinct keypoint frames are written again as they would come from
/// other users and gloves: a smaller hand (0.85×) with the glove turned 15°, a larger hand
/// (1.2×) turned −12°, a noisy glove (2 mm per coordinate) dropping 10 % of its frames,
/// 30 Hz and 120 Hz (re-sampled linearly), and, for the lab's 22 points, its 21-point
/// layout. Besides, --synthetic-users (4 by default) users of the project's simulated
/// glove, each hand with its own proportions (thumb ±15 %, index and middle ±10 %, palm
/// breadth ±10 %, the thumb's base moved, the glove's tip markers ±5 mm off the tips),
/// whose pinches are real contacts of the simulated hand and on whom nothing was tuned
/// (a seed no one looked at gives users no one tuned on). One MCAP per recording in --out
/// and set.json listing them; the sources are not copied (evaluate them beside the set).
///
/// Example:
///   pomdar eval-set recordings/ --out eval_set/
///   pomdar eval recordings/ eval_set/
///   pomdar eval-set --synthetic-users 8 --seed 2027 --out held_out/   (users only)
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct EvalSetArgs {
    /// The real recordings (MCAP) the set is made from, or directories searched for them
    /// (none: only the synthetic users).
    #[arg(value_name = "RECORDING")]
    pub sources: Vec<PathBuf>,
    /// The set's directory (created if needed; an existing recording in it is not replaced).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Seed of the noise, the dropped frames and the synthetic users.
    #[arg(long, value_name = "N", default_value_t = 1)]
    pub seed: u64,
    /// Synthetic users besides the copies: the simulated glove on hands of 0.85-1.15x with
    /// their own proportions (thumb +-15 %, index and middle +-10 %, palm breadth +-10 %, the
    /// thumb's base moved, tip markers +-5 mm off the tips), turned up to 10 deg, 1 mm jitter,
    /// 21 points at 25 Hz, 30 s of a task-like sequence (odd users) or the four pinches (even
    /// users); their pinches are real contacts of the simulated hand.
    #[arg(long, value_name = "N", default_value_t = 4)]
    pub synthetic_users: u64,
    /// Station configuration: the keypoint topic and format read and written (default: the
    /// built-in ETH lab preset).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
}

/// `pomdar eval-set`.
pub fn eval_set(args: EvalSetArgs) -> anyhow::Result<()> {
    let config = load_station_config(args.config.as_deref(), None)?;
    if args.sources.is_empty() && args.synthetic_users == 0 {
        anyhow::bail!(
            "nothing to build: give the real recordings (RECORDING) or --synthetic-users N (1 or more)"
        );
    }
    let sources = if args.sources.is_empty() {
        Vec::new()
    } else {
        readable_mcap_files(&args.sources)?
    };
    std::fs::create_dir_all(&args.out)
        .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", args.out.display()))?;
    let set = build_set(
        &sources,
        &config,
        &args.out,
        args.seed,
        args.synthetic_users,
    )?;
    for r in &set {
        println!(
            "{}  {} frames, {}  ({} ← {})",
            r.path.display(),
            r.frames,
            r.layout,
            r.variants.join(" + "),
            r.source.display()
        );
    }
    let manifest = args.out.join("set.json");
    write_atomically(&manifest, serde_json::to_string_pretty(&set)?)?;
    eprintln!(
        "wrote {} recordings from {} sources and {} synthetic users, and {}; evaluate with: pomdar eval {}",
        set.len(),
        sources.len(),
        args.synthetic_users,
        manifest.display(),
        args.sources
            .iter()
            .chain([&args.out])
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(" ")
    );
    Ok(())
}
