//! `pomdar ingress rokoko|avp`: the command lines of the hand-tracking ingresses.

use std::net::IpAddr;
use std::path::PathBuf;

use clap::{Args, Subcommand};

use crate::clock::StationClock;
use crate::command::shared_args::{NodeArgs, ctrl_c_shutdown};
use crate::ingress::avp_config::AvpConfig;
use crate::ingress::avp_node::{avp_source, run_avp_ingress};
use crate::ingress::ingress_config::{Hand, IngressConfig};
use crate::ingress::rokoko_node::{rokoko_source, run_rokoko_ingress, status_line};

/// Hand-tracking ingress: a glove (Rokoko) or headset (Apple Vision Pro) stream in, the lab's ROS 2 keypoint topics out.
#[derive(Debug, Subcommand)]
pub enum IngressCommand {
    /// Rokoko Studio Live "custom streaming" (JSON v3 over UDP) to the lab's topics.
    ///
    /// Listens for Studio's packets on UDP 127.0.0.1:14043 (this computer only) unless --bind
    /// names the address of the interface Studio streams to; with --allow-sender (or the
    /// file's allowed_senders) datagrams from any other sender are dropped and counted
    /// (refused.sender). Publishes, for each new packet, the hand's keypoints
    /// on /ingress/mano (std_msgs/Float32MultiArray, 22 × 3 or 21 × 3, metres) and the hand
    /// bone's pose on /ingress/wrist (geometry_msgs/PoseStamped, stamped at receipt), both in
    /// a right-handed ROS frame (x forward, y left, z up; Studio's is y-up, z-forward,
    /// left-handed). Nothing is republished on a timer. Every packet is ordered by its
    /// scene.timestamp: one without is refused (no_timestamp); duplicated and out-of-order
    /// packets are dropped; a jump back is taken for a Studio restart only after 5 packets
    /// in a row confirm it (restart_confirm_packets), so one stray old packet never resets
    /// the order. Malformed, truncated, oversized and bone-missing packets are dropped and
    /// counted by kind (each kind logged at most once per 10 s, with the count held back);
    /// the counts and the rate go out as JSON on /ingress/status every second and as a
    /// line on stderr every 5 s. In Studio: Livestream → Custom → JSON v3, the address
    /// given to --bind, port 14043. docs/SECURITY.md says what this trusts.
    ///
    /// Examples:
    ///   pomdar ingress rokoko
    ///   pomdar ingress rokoko --bind 10.251.0.1 --allow-sender 10.251.0.9 --actor Actor1 --hand right
    ///   pomdar ingress rokoko --config launch_configs/ingress/rokoko.toml --domain-id 7
    #[command(verbatim_doc_comment)]
    Rokoko(RokokoArgs),
    /// Apple Vision Pro hand tracking (the VisionProTeleop app's gRPC stream) to the lab's topics.
    ///
    /// Connects to the headset's app (gRPC, port 12345, no TLS) and publishes, for each new
    /// hand update, the hand's keypoints on /ingress/mano (std_msgs/Float32MultiArray, 22 × 3
    /// or 21 × 3, metres; the four metacarpals dropped; the forearm point from the app's
    /// forearm joint, else the wrist) and the wrist's pose on /ingress/wrist
    /// (geometry_msgs/PoseStamped, stamped at receipt), both in ROS axes (x forward, y left,
    /// z up; ARKit's world is y-up). When the headset goes away it reconnects with backoff
    /// (0.25 s doubling to 4 s). Undecodable, untracked, non-finite and repeated updates are
    /// dropped and counted (each kind logged once); the counts, the rate and the connection
    /// state go out as JSON on /ingress/status every second and as a line on stderr every 5 s.
    /// On the headset: start the app; it shows its address.
    ///
    /// Examples:
    ///   pomdar ingress avp --address 192.168.1.42
    ///   pomdar ingress avp --address vision-pro.local:12345 --hand left
    ///   pomdar ingress avp --config launch_configs/ingress/avp.toml --address 10.0.0.7 --domain-id 7
    #[command(verbatim_doc_comment)]
    Avp(AvpArgs),
}

/// `pomdar ingress avp` options (each overrides the configuration file's key).
#[derive(Debug, Args)]
pub struct AvpArgs {
    /// The headset: HOST or HOST:PORT [port default: 12345]; required unless the file names it.
    #[arg(long, value_name = "HOST[:PORT]")]
    pub address: Option<String>,
    /// Settings file (launch_configs/ingress/avp.toml shows every key and its default).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Which hand to publish [default: right].
    #[arg(long, value_enum)]
    pub hand: Option<Hand>,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
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
    /// Local address to listen on: this computer's address on the network Studio streams
    /// to [default: 127.0.0.1, this computer only; 0.0.0.0: every interface].
    #[arg(long, value_name = "ADDRESS")]
    pub bind: Option<IpAddr>,
    /// Take datagrams only from this sender (repeatable; replaces the file's
    /// allowed_senders) [default: any sender that can reach --bind].
    #[arg(long = "allow-sender", value_name = "ADDRESS[:PORT]")]
    pub allow_sender: Vec<String>,
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
    match command {
        IngressCommand::Rokoko(args) => run_rokoko(args).await,
        IngressCommand::Avp(args) => run_avp(args).await,
    }
}

async fn run_avp(args: AvpArgs) -> anyhow::Result<()> {
    let mut config = match &args.config {
        Some(path) => AvpConfig::from_file(path)?,
        None => AvpConfig::default(),
    };
    if let Some(address) = &args.address {
        config.set_address(address)?;
    }
    config.hand = args.hand.unwrap_or(config.hand);
    config.network = args.node.network(&config.network);
    config.validate()?;
    eprintln!(
        "pomdar ingress avp: {} ({} hand) -> {} and {} on domain {}; Ctrl-C stops",
        config.device(),
        config.hand.bone_prefix(),
        config.keypoints_topic,
        config.wrist_topic,
        crate::ros::domain_id(config.network.domain_id)?,
    );
    let source = avp_source(&config);
    let clock = StationClock::new();
    let mut counters = run_avp_ingress(config, clock, ctrl_c_shutdown(), true).await?;
    eprintln!("{}", status_line(&counters.status(clock.now_ns(), &source)));
    Ok(())
}

async fn run_rokoko(args: RokokoArgs) -> anyhow::Result<()> {
    let mut config = match &args.config {
        Some(path) => IngressConfig::from_file(path)?,
        None => IngressConfig::default(),
    };
    config.port = args.port.unwrap_or(config.port);
    config.bind_address = args.bind.unwrap_or(config.bind_address);
    if !args.allow_sender.is_empty() {
        config.allowed_senders = args.allow_sender;
    }
    config.actor = args.actor.or(config.actor);
    config.hand = args.hand.unwrap_or(config.hand);
    config.network = args.node.network(&config.network);
    config.validate()?;
    eprintln!(
        "pomdar ingress rokoko: UDP {}:{} from {} ({} hand, actor {}) -> {} and {} on domain {}; Ctrl-C stops",
        config.bind_address,
        config.port,
        if config.allowed_senders.is_empty() {
            "any sender".to_string()
        } else {
            config.allowed_senders.join(", ")
        },
        config.hand.bone_prefix(),
        config.actor.as_deref().unwrap_or("(first)"),
        config.keypoints_topic,
        config.wrist_topic,
        crate::ros::domain_id(config.network.domain_id)?,
    );
    let source = rokoko_source(&config, (config.bind_address, config.port).into());
    let clock = StationClock::new();
    let mut counters = run_rokoko_ingress(config, clock, ctrl_c_shutdown(), None, true).await?;
    eprintln!("{}", status_line(&counters.status(clock.now_ns(), &source)));
    Ok(())
}
