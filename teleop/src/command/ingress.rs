//! `pomdar ingress rokoko`: the command line of the Rokoko ingress.

use std::net::IpAddr;
use std::path::PathBuf;

use clap::{Args, Subcommand};

use crate::clock::StationClock;
use crate::command::common::{NodeArgs, ctrl_c_shutdown};
use crate::ingress::ingress_config::{Hand, IngressConfig};
use crate::ingress::rokoko_node::{run_rokoko_ingress, status_line};

/// The glove streams `pomdar ingress` reads.
#[derive(Debug, Subcommand)]
pub enum IngressCommand {
    /// Rokoko Studio Live "custom streaming" (JSON v3 over UDP) to the lab's topics.
    ///
    /// Listens for Studio's packets and publishes, for each new packet, the hand's keypoints
    /// on /ingress/mano (std_msgs/Float32MultiArray, 22 × 3 or 21 × 3, metres) and the hand
    /// bone's pose on /ingress/wrist (geometry_msgs/PoseStamped, stamped at receipt), both in
    /// a right-handed ROS frame (x forward, y left, z up; Studio's is y-up, z-forward,
    /// left-handed). Nothing is republished on a timer. Malformed, truncated, oversized,
    /// duplicated and out-of-order packets are dropped and counted (each kind logged once);
    /// the counts and the rate go out as JSON on /ingress/status every second and as a
    /// line on stderr every 5 s. In Studio: Livestream → Custom → JSON v3, this computer's
    /// address, port 14043.
    ///
    /// Examples:
    ///   pomdar ingress rokoko
    ///   pomdar ingress rokoko --port 14043 --actor Actor1 --hand right
    ///   pomdar ingress rokoko --config launch_configs/ingress/rokoko.toml --domain-id 7
    #[command(verbatim_doc_comment)]
    Rokoko(RokokoArgs),
}

/// `pomdar ingress rokoko` options (each overrides the configuration file's key).
#[derive(Debug, Args)]
pub struct RokokoArgs {
    /// Settings file (launch_configs/ingress/rokoko.toml shows every key and its default).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// UDP port to listen on [default: 14043].
    #[arg(long)]
    pub port: Option<u16>,
    /// Local address to listen on [default: 0.0.0.0, every interface].
    #[arg(long, value_name = "ADDRESS")]
    pub bind: Option<IpAddr>,
    /// Follow this actor by name [default: the first actor in each packet].
    #[arg(long, value_name = "NAME")]
    pub actor: Option<String>,
    /// Which hand's bones to publish [default: right].
    #[arg(long, value_enum)]
    pub hand: Option<Hand>,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
}

/// Run an ingress command until Ctrl-C.
pub async fn run(command: IngressCommand) -> anyhow::Result<()> {
    let IngressCommand::Rokoko(args) = command;
    let mut config = match &args.config {
        Some(path) => IngressConfig::from_file(path)?,
        None => IngressConfig::default(),
    };
    config.port = args.port.unwrap_or(config.port);
    config.bind_address = args.bind.unwrap_or(config.bind_address);
    config.actor = args.actor.or(config.actor);
    config.hand = args.hand.unwrap_or(config.hand);
    config.network = args.node.network(&config.network);
    config.validate()?;
    eprintln!(
        "pomdar ingress rokoko: UDP {}:{} ({} hand, actor {}) -> {} and {} on domain {}; Ctrl-C stops",
        config.bind_address,
        config.port,
        config.hand.bone_prefix(),
        config.actor.as_deref().unwrap_or("(first)"),
        config.keypoints_topic,
        config.wrist_topic,
        crate::ros::domain_id(config.network.domain_id)?,
    );
    let port = config.port;
    let clock = StationClock::new();
    let mut counters = run_rokoko_ingress(config, clock, ctrl_c_shutdown(), None, true).await?;
    eprintln!("{}", status_line(&counters.status(clock.now_ns(), port)));
    Ok(())
}
