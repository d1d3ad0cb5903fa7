//! `pomdar recover`: repair an interrupted log.

use std::path::PathBuf;

use clap::Args;

/// Repair an interrupted log (NAME.mcap.part) up to its last flushed chunk.
///
/// Prints what was recovered and what was lost; never modifies the input.
#[derive(Debug, Args)]
pub struct RecoverArgs {
    /// The interrupted log (`NAME.mcap.part`).
    pub part: PathBuf,
    /// Where to write the repaired log (default: the name without `.part`).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

/// `pomdar recover`.
pub fn recover(args: RecoverArgs) -> anyhow::Result<()> {
    let out = match args.out {
        Some(out) => out,
        None => {
            let name = args.part.to_string_lossy();
            let Some(stem) = name.strip_suffix(".part") else {
                anyhow::bail!("{} does not end in .part: give --out", args.part.display());
            };
            PathBuf::from(stem)
        }
    };
    let report = crate::mcap_log::recover(&args.part, &out)?;
    println!("{report}");
    Ok(())
}
