//! `pomdar probe`: the command line of the discovery probe.

use std::process::ExitCode;
use std::time::Duration;

use clap::Args;

use crate::command::shared_args::{NodeArgs, ctrl_c_shutdown};
use crate::ros::NetworkConfig;
use crate::ros::discovery_probe::{ProbeOptions, probe};

/// Check DDS discovery from this host: which publishers it sees, and at what rate.
///
/// Joins the domain on the given interfaces, waits for a publisher of each topic, counts
/// its samples for --duration seconds and prints every discovered publisher with the
/// addresses it announced (its host) and each topic's rate; for stamped messages also
/// how old they were on arrival (receive time − header stamp) and how many were older
/// than --age-limit-ms, and the topic's silences (pauses of 250 ms or more). With
/// --reliable it subscribes as a robot driver does. Exit status 0 when every topic was
/// heard, 2 when one was not discovered or not heard (docs/DEPLOYMENT.md says what to
/// check).
///
/// Example:
///   pomdar probe --topics /pomdar/hand/joint_targets,/franka/end_effector_pose_cmd --interface 10.251.0.3
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct ProbeArgs {
    /// Topics to listen to, comma-separated (e.g. /pomdar/hand/joint_targets).
    #[arg(long, value_delimiter = ',', required = true)]
    pub topics: Vec<String>,
    /// Seconds to count each topic's samples once its publisher is discovered.
    #[arg(long, default_value_t = 5.0)]
    pub duration: f64,
    /// Seconds to wait for a publisher of each topic.
    #[arg(long, default_value_t = 15.0)]
    pub discovery_timeout: f64,
    /// Subscribe reliably, as a robot driver does (a reliable publisher then resends what it
    /// lost, e.g. after a cut link); default best effort, which hears any publisher.
    #[arg(long)]
    pub reliable: bool,
    /// Count stamped samples older than this on arrival (receive time − header stamp; the
    /// hosts' clocks must be in step), milliseconds.
    #[arg(long, default_value_t = 100, value_name = "MS")]
    pub age_limit_ms: u64,
    /// Print the report as JSON on stdout.
    #[arg(long)]
    pub json: bool,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
}

fn seconds(flag: &str, value: f64) -> anyhow::Result<Duration> {
    if !(value > 0.0 && value <= 3600.0) {
        anyhow::bail!("{flag} {value} must be in (0, 3600] seconds");
    }
    Ok(Duration::from_secs_f64(value))
}

/// `pomdar probe`: exit status 0 when every topic was discovered and heard, 2 otherwise.
pub async fn run(args: ProbeArgs) -> anyhow::Result<ExitCode> {
    let options = ProbeOptions {
        topics: args.topics,
        duration: seconds("--duration", args.duration)?,
        discovery_timeout: seconds("--discovery-timeout", args.discovery_timeout)?,
        reliable: args.reliable,
        age_limit_ms: args.age_limit_ms,
    };
    let network = args.node.network(&NetworkConfig::default());
    let report = probe(&network, &options, ctrl_c_shutdown()).await?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{report}");
    }
    Ok(if report.all_heard() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    })
}
