//! `pomdar`: the POMDAR teleoperation and scoring station.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use teleop::hand_source::HandSource;
use teleop::model_report;

/// The POMDAR station: teleoperate a robot hand through the POMDAR dexterity benchmark and
/// score the trials.
///
/// Today it inspects hand models. The ROS 2 station (`demo`, `station`), recording, replay,
/// calibration, scoring and the operator console arrive in later issues.
#[derive(Debug, Parser)]
#[command(name = "pomdar", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Load a hand model, validate it and print its joints, limits, frames and embodiments.
    ///
    /// Without options it shows the built-in ORCA v1 right hand. Use it to check a new hand's
    /// URDF before running the station with it: errors name the file, element and problem.
    ///
    /// Examples:
    ///   pomdar model
    ///   pomdar model --urdf orcahand_v1_right.urdf --import launch_configs/hands/orca_v1_right_urdf.toml
    ///   pomdar model --pose index_mcp=0.8,thumb_mcp=0.3 --json
    #[command(verbatim_doc_comment)]
    Model {
        /// A model file in the project's TOML format (see `retarget::model_spec`).
        #[arg(long, value_name = "FILE", conflicts_with_all = ["urdf", "import"])]
        model: Option<PathBuf>,
        /// A URDF to load instead of the built-in hand (needs --import).
        #[arg(long, value_name = "FILE", requires = "import")]
        urdf: Option<PathBuf>,
        /// The import file naming the URDF's frames (launch_configs/hands/*.toml).
        #[arg(long, value_name = "FILE", requires = "urdf")]
        import: Option<PathBuf>,
        /// Joint values (radians) for the frame positions, as NAME=VALUE[,NAME=VALUE...];
        /// unnamed joints stay at zero.
        #[arg(long, value_name = "JOINTS", value_delimiter = ',')]
        pose: Vec<String>,
        /// Print JSON instead of tables.
        #[arg(long)]
        json: bool,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Model {
            model,
            urdf,
            import,
            pose,
            json,
        } => {
            let source = match (model, urdf, import) {
                (Some(path), _, _) => HandSource::ModelFile(path),
                (None, Some(urdf), Some(import)) => HandSource::Urdf { urdf, import },
                _ => HandSource::BuiltinOrcaV1Right,
            };
            model_report::run(&source, &pose, json)
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}
