//! `pomdar model`: load a hand model, validate it and print it.

use std::path::PathBuf;

use clap::Args;

use crate::hand_source::HandSource;
use crate::model_report;

/// `pomdar model` options.
#[derive(Debug, Args)]
pub struct ModelArgs {
    /// A model file in the project's TOML format (see `retarget::model_spec`).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["urdf", "import"])]
    pub model: Option<PathBuf>,
    /// A URDF to load instead of the built-in hand (needs --import).
    #[arg(long, value_name = "FILE", requires = "import")]
    pub urdf: Option<PathBuf>,
    /// The import file naming the URDF's frames (launch_configs/hands/*.toml).
    #[arg(long, value_name = "FILE", requires = "urdf")]
    pub import: Option<PathBuf>,
    /// Joint values (radians) for the frame positions, as NAME=VALUE[,NAME=VALUE...];
    /// unnamed joints stay at zero.
    #[arg(long, value_name = "JOINTS", value_delimiter = ',')]
    pub pose: Vec<String>,
    /// Print JSON instead of tables.
    #[arg(long)]
    pub json: bool,
}

/// `pomdar model`.
pub fn model(args: ModelArgs) -> anyhow::Result<()> {
    let source = match (args.model, args.urdf, args.import) {
        (Some(path), _, _) => HandSource::ModelFile(path),
        (None, Some(urdf), Some(import)) => HandSource::Urdf { urdf, import },
        _ => HandSource::BuiltinOrcaV1Right,
    };
    Ok(model_report::run(&source, &args.pose, args.json)?)
}
