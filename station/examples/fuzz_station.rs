//! The long fuzz run of the whole station (docs/FAULTS.md, "Hostile frames"): one seeded
//! hostile world fed to one station built from the ETH lab's preset, every output checked
//! against the invariants of `station::fuzz`, the counts printed.
//!
//! ```sh
//! cargo run --release -p station --example fuzz_station -- --frames 1000000 --seed 1
//! ```
//!
//! Exit status 1 when an invariant was violated, 2 on a usage error.

use std::process::ExitCode;
use std::time::Instant;

use retarget::HandModel;
use station::StationConfig;
use station::fuzz::{FuzzOptions, config_for_seed, run};

/// The ETH lab's preset, as shipped.
const ETH_LAB: &str = include_str!("../../launch_configs/station/eth_lab.toml");

const USAGE: &str =
    "usage: fuzz_station [--frames N] [--seed S]   (defaults: 1000000 frames, seed 1)";

fn parse_args() -> Result<FuzzOptions, String> {
    let mut options = FuzzOptions {
        seed: 1,
        frames: 1_000_000,
    };
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = |name: &str| {
            args.next()
                .and_then(|v| v.parse::<u64>().ok())
                .ok_or_else(|| format!("{name} needs a whole number\n{USAGE}"))
        };
        match arg.as_str() {
            "--frames" => options.frames = value("--frames")?,
            "--seed" => options.seed = value("--seed")?,
            "-h" | "--help" => return Err(USAGE.to_string()),
            other => return Err(format!("unknown argument {other}\n{USAGE}")),
        }
    }
    Ok(options)
}

fn main() -> ExitCode {
    let options = match parse_args() {
        Ok(options) => options,
        Err(message) => {
            eprintln!("{message}");
            return ExitCode::from(2);
        }
    };
    let base = match StationConfig::from_toml_str(ETH_LAB) {
        Ok(config) => config,
        Err(e) => {
            eprintln!("eth_lab.toml: {e}");
            return ExitCode::from(2);
        }
    };
    let config = config_for_seed(&base, options.seed);
    println!(
        "fuzz_station: {} frames, seed {}, constraint {:?}, control {:?}, auto_engage {}",
        options.frames,
        options.seed,
        config.arm.constraint,
        config.control.mode,
        config.control.auto_engage
    );
    let started = Instant::now();
    let tally = match run(&config, HandModel::orca_v1_right(), options) {
        Ok(tally) => tally,
        Err(e) => {
            eprintln!("station: {e}");
            return ExitCode::from(2);
        }
    };
    let seconds = started.elapsed().as_secs_f64();
    print!("{tally}");
    println!(
        "time: {seconds:.1} s ({:.1} µs per step)",
        seconds * 1e6 / tally.event("steps").max(1) as f64
    );
    if tally.violations() == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
