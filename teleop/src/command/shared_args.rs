//! What the commands share: the flag structs (DDS settings, the datagram guard, the glove's
//! motions, the live view, the hand model, the trial console's settings) and the few wiring
//! helpers over them (the async runtime, Ctrl-C, the recordings named on a command line). Not
//! a command: every command may use it, it uses none.

use std::path::PathBuf;

use anyhow::Context as _;
use clap::Args;
use retarget::human_hand::MotionKind;

use crate::console::session_options::ConsoleSettings;
use crate::ros::{NetworkConfig, NetworkOverride};
use crate::view::live_view::{LiveView, start_live_view};

/// The glove's scripted motions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MotionArg {
    /// Open hand to fist and back.
    OpenClose,
    /// The four thumb–finger pinches in turn.
    Pinches,
    /// Fingers spread and closed.
    Abduction,
    /// Grasp, release, pinches.
    TaskLike,
}

impl From<MotionArg> for MotionKind {
    fn from(m: MotionArg) -> MotionKind {
        match m {
            MotionArg::OpenClose => MotionKind::OpenClose,
            MotionArg::Pinches => MotionKind::Pinches,
            MotionArg::Abduction => MotionKind::Abduction,
            MotionArg::TaskLike => MotionKind::TaskLike,
        }
    }
}

/// Options shared by the node commands.
#[derive(Debug, Clone, Args)]
pub struct NodeArgs {
    /// ROS domain id, 0–232 (default: the config's, else ROS_DOMAIN_ID, else 0).
    #[arg(long)]
    pub domain_id: Option<u16>,
    /// Use this address of this host for DDS (repeatable): discovery multicast is joined and
    /// sent on its interface and only it is announced to other hosts, e.g. 127.0.0.1 or the
    /// lab-network address (docs/DEPLOYMENT.md). An address this host lacks is refused.
    #[arg(long = "interface", value_name = "ADDRESS")]
    pub interfaces: Vec<std::net::IpAddr>,
}

impl NodeArgs {
    /// `--domain-id` and `--interface`, to lay over a configuration's network.
    pub(crate) fn overrides(&self) -> NetworkOverride {
        NetworkOverride {
            domain_id: self.domain_id,
            interfaces: self.interfaces.clone(),
        }
    }

    pub(crate) fn network(&self, base: &NetworkConfig) -> NetworkConfig {
        self.overrides().apply(base)
    }
}

/// The datagram guard of the commands that run the station or talk to the robot.
#[derive(Debug, Clone, Default, Args)]
pub struct GuardArgs {
    /// Run without the RTPS datagram guard: by default every DDS socket of this process gets a
    /// kernel filter that drops crafted DATA_FRAG datagrams (one can take gigabytes of memory,
    /// docs/SECURITY.md), and start-up fails, naming the socket, if one cannot be guarded.
    /// With this flag the process says once that it runs unguarded.
    #[arg(long)]
    pub no_datagram_guard: bool,
}

impl GuardArgs {
    /// Require the guard for every participant this process builds, or decline it.
    pub(crate) fn apply(&self) {
        match self.no_datagram_guard {
            true => crate::ros::participant_guard::decline(),
            false => crate::ros::participant_guard::require(),
        }
    }
}

/// Run an async command on a two-worker runtime.
pub fn run_async<T>(future: impl Future<Output = anyhow::Result<T>>) -> anyhow::Result<T> {
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .context("cannot start the async runtime")?
        .block_on(future)
}

pub(crate) use crate::tui::terminal_shell::ctrl_c_shutdown;

/// The `.mcap` files under `paths` (files, or directories searched recursively) for the
/// commands that read many recordings (`pomdar baseline`, `study-report`, `eval`, `eval-set`):
/// `.part` files skipped with a note; an error when there is nothing to read.
pub(crate) fn mcap_files_under(
    paths: &[PathBuf],
) -> anyhow::Result<crate::score::trial_files::TrialFiles> {
    let found = crate::score::trial_files::collect_trial_files(paths);
    for s in &found.skipped {
        eprintln!("note: skipped {}: {}", s.file, s.reason);
    }
    if found.files.is_empty() && found.problems.is_empty() {
        anyhow::bail!(
            "no .mcap trial files in {}",
            paths
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(found)
}

/// The `.mcap` files in `paths` (files, or directories searched), for a command that reads
/// every one: a path that cannot be read stops it, named with the reason, rather than being
/// left out of its figures.
pub(crate) fn readable_mcap_files(paths: &[PathBuf]) -> anyhow::Result<Vec<PathBuf>> {
    let found = mcap_files_under(paths)?;
    if !found.problems.is_empty() {
        let problems: Vec<String> = found
            .problems
            .iter()
            .map(|p| format!("{}: {}", p.file, p.reason))
            .collect();
        anyhow::bail!("cannot read {}", problems.join("; "));
    }
    Ok(found.files)
}

/// `--view [ADDR:]PORT`, shared by the commands that run a station.
#[derive(Debug, Clone, Args)]
pub struct ViewArgs {
    /// Serve a live 3D view of the station (hand links on /tf, glove keypoints beside the
    /// robot's fingertips, the hand's drawing, diagnostics) on this port for the Foxglove app
    /// (Open connection → Foxglove WebSocket, ws://ADDR:PORT); no ROS needed on the viewing
    /// machine. PORT alone listens on 127.0.0.1 only; give 0.0.0.0:PORT to let other hosts
    /// connect; port 0 picks a free one (printed). A slow viewer loses old messages and never
    /// slows the station.
    #[arg(long, value_name = "[ADDR:]PORT")]
    pub view: Option<crate::view::ViewAddress>,
}

impl ViewArgs {
    /// Start the live view if `--view` was given.
    pub(crate) async fn start(&self) -> anyhow::Result<Option<LiveView>> {
        Ok(start_live_view(self.view).await?)
    }
}

/// Where the hand model comes from (`--model`, or `--urdf` with `--import`; default the
/// built-in ORCA v1 right hand).
#[derive(Debug, Clone, clap::Args)]
pub struct HandSourceArgs {
    /// A model file in the project's TOML format (see `retarget::model_spec`).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["urdf", "import"])]
    pub model: Option<PathBuf>,
    /// The robot's URDF, instead of the built-in hand (needs --import); a station also
    /// publishes it on /robot_description.
    #[arg(long, value_name = "FILE", requires = "import")]
    pub urdf: Option<PathBuf>,
    /// The import file naming the URDF's frames (launch_configs/hands/*.toml).
    #[arg(long, value_name = "FILE", requires = "urdf")]
    pub import: Option<PathBuf>,
}

impl HandSourceArgs {
    /// The hand these flags name.
    pub fn source(&self) -> crate::hand_source::HandSource {
        use crate::hand_source::HandSource;
        match (&self.model, &self.urdf, &self.import) {
            (Some(path), _, _) => HandSource::ModelFile(path.clone()),
            (None, Some(urdf), Some(import)) => HandSource::Urdf {
                urdf: urdf.clone(),
                import: import.clone(),
            },
            _ => HandSource::BuiltinOrcaV1Right,
        }
    }
}

/// How the trial console runs: shared by `pomdar trial` and `pomdar study`.
#[derive(Debug, Clone, Args)]
pub struct ConsoleArgs {
    /// Countdown before a trial starts, seconds (0–30).
    #[arg(long, value_name = "S", default_value_t = 3.0)]
    pub countdown: f64,
    /// Refuse to start a trial while new glove frames arrive slower than this, Hz.
    #[arg(long, value_name = "HZ", default_value_t = 20.0)]
    pub min_glove_rate: f64,
    /// Refuse to start a trial while the last glove frame is older than this, ms.
    #[arg(long, value_name = "MS", default_value_t = 200.0)]
    pub max_input_age: f64,
    /// Timed operator actions from a file instead of (or besides) the keyboard; see
    /// `pomdar trial --help` for the format (a study plays it once for each task).
    #[arg(long, value_name = "FILE")]
    pub script: Option<PathBuf>,
    /// Print lines instead of the full-screen console (the default without a terminal);
    /// without --script, commands are read from stdin, one per line.
    #[arg(long)]
    pub plain: bool,
}

impl ConsoleArgs {
    /// The console's settings.
    pub(crate) fn settings(&self) -> ConsoleSettings {
        ConsoleSettings {
            countdown: self.countdown,
            min_glove_rate: self.min_glove_rate,
            max_input_age: self.max_input_age,
            script: self.script.clone(),
            plain: self.plain,
        }
    }
}
