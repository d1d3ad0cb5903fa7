//! What the node commands share: DDS settings, the glove's motions, the async runtime and
//! Ctrl-C.

use anyhow::Context as _;
use clap::Args;
use retarget::human_hand::MotionKind;
use tokio::sync::watch;

use crate::ros::NetworkConfig;

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
    pub(crate) fn network(&self, base: &NetworkConfig) -> NetworkConfig {
        NetworkConfig {
            domain_id: self.domain_id.or(base.domain_id),
            interfaces: if self.interfaces.is_empty() {
                base.interfaces.clone()
            } else {
                self.interfaces.clone()
            },
        }
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

/// A shutdown signal that turns true on Ctrl-C.
pub(crate) fn ctrl_c_shutdown() -> watch::Receiver<bool> {
    let (tx, rx) = watch::channel(false);
    tokio::spawn(async move {
        if tokio::signal::ctrl_c().await.is_ok() {
            tx.send(true).ok();
        }
    });
    rx
}

/// The `.mcap` files under `paths` (files, or directories searched recursively) for the
/// commands that read many recordings (`pomdar baseline`, `study-report`, `eval`, `eval-set`):
/// `.part` files skipped with a note; an error when there is nothing to read.
pub(crate) fn mcap_files_under(
    paths: &[std::path::PathBuf],
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
pub(crate) fn readable_mcap_files(
    paths: &[std::path::PathBuf],
) -> anyhow::Result<Vec<std::path::PathBuf>> {
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

/// A running live view and the tap the station feeds it through.
#[derive(Debug)]
#[cfg_attr(not(feature = "view"), allow(dead_code))] // never started without the feature
pub(crate) struct LiveView {
    /// Give this to the station's hooks.
    pub(crate) tap: crate::station_node::tap::Tap,
    #[cfg(feature = "view")]
    server: crate::view::ViewServer,
}

#[cfg(feature = "view")]
/// Messages the tap holds for a live view that falls behind, before the oldest are dropped
/// (several seconds of every topic at the station's rates).
const TAP_CAPACITY: usize = 4096;

impl ViewArgs {
    /// Start the live view if `--view` was given.
    pub(crate) async fn start(&self) -> anyhow::Result<Option<LiveView>> {
        let Some(address) = self.view else {
            return Ok(None);
        };
        start_view(address).await.map(Some)
    }
}

#[cfg(feature = "view")]
async fn start_view(address: crate::view::ViewAddress) -> anyhow::Result<LiveView> {
    let tap = crate::station_node::tap::Tap::new(TAP_CAPACITY);
    let server = crate::view::ViewServer::start(address, tap.subscribe()).await?;
    Ok(LiveView { tap, server })
}

#[cfg(not(feature = "view"))]
async fn start_view(address: crate::view::ViewAddress) -> anyhow::Result<LiveView> {
    anyhow::bail!(
        "--view {address}: this pomdar was built without the live view; rebuild with `cargo build --release -p teleop --features view`"
    )
}

#[cfg_attr(not(feature = "view"), allow(dead_code))]
impl LiveView {
    /// The line to show on start: where to point the Foxglove app.
    pub(crate) fn announcement(&self) -> String {
        #[cfg(feature = "view")]
        return self.server.announcement();
        #[cfg(not(feature = "view"))]
        String::new()
    }

    /// Stop the view after the station (a no-op without the `view` feature, which never
    /// starts one).
    pub(crate) async fn stop(self) {
        #[cfg(feature = "view")]
        {
            let report = self.server.stop().await;
            if report.counts.lagged > 0 {
                eprintln!(
                    "live view: fell behind and dropped {} of {} messages",
                    report.counts.lagged,
                    report.counts.lagged + report.counts.forwarded
                );
            }
        }
    }
}

/// Where the hand model comes from (`--model`, or `--urdf` with `--import`; default the
/// built-in ORCA v1 right hand).
#[derive(Debug, Clone, clap::Args)]
pub struct HandSourceArgs {
    /// A model file in the project's TOML format (see `retarget::model_spec`).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["urdf", "import"])]
    pub model: Option<std::path::PathBuf>,
    /// The robot's URDF, instead of the built-in hand (needs --import); a station also
    /// publishes it on /robot_description.
    #[arg(long, value_name = "FILE", requires = "import")]
    pub urdf: Option<std::path::PathBuf>,
    /// The import file naming the URDF's frames (launch_configs/hands/*.toml).
    #[arg(long, value_name = "FILE", requires = "urdf")]
    pub import: Option<std::path::PathBuf>,
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
