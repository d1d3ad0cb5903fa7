//! `pomdar relay`: the station's commands onto the robot's topics, on the robot's computer.

use std::path::PathBuf;
use std::sync::Mutex;

use anyhow::Context as _;
use clap::Args;

use super::shared_args::{NodeArgs, ctrl_c_shutdown};
use crate::clock::WallClock;
use crate::relay_node::{RelayReport, RelaySettings, run_relay};
use crate::station_driver::setup::read_station_config;

/// On the robot's computer: the station's commands onto the robot's own topics.
///
/// With `[robot_link] relay_prefix` set, the station sends its robot commands best effort
/// on relay topics (the prefix + the robot's topic): a cut cable loses what was sent into
/// it and nothing old is resent when it returns. The relay republishes each command on the
/// robot's topic with the configuration's output.qos (reliable for the lab's drivers), on
/// this computer, and drops any command older than `[robot_link] max_age_ms` (100 ms) on
/// arrival, by the older of its send time and its header stamp (a hand command's glove
/// frame): the lab's clocks must be kept in step (chrony). It
/// estimates the offset between the two clocks from the smallest command ages and warns,
/// naming it, once it takes a quarter of that limit. Drops and refused publishes are
/// reported every 5 s at most; a summary on Ctrl-C. Twice a second it publishes its status
/// on `<relay_prefix>/relay_status` (the robot's drivers listening, the offset), which the
/// station reads. docs/DEPLOYMENT.md, "When a link fails".
///
/// Example:
///   pomdar relay --config launch_configs/station/deploy_station.toml --interface 10.251.0.3
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct RelayArgs {
    /// The station's configuration (the same file the station runs with): its
    /// [robot_link] relay_prefix and max_age_ms, the robot's topics and output.qos.
    #[arg(long, value_name = "FILE")]
    pub config: PathBuf,
    /// DDS settings (default: the configuration's [network]).
    #[command(flatten)]
    pub node: NodeArgs,
    /// The RTPS datagram guard.
    #[command(flatten)]
    pub guard: super::shared_args::GuardArgs,
}

/// `pomdar relay`.
pub async fn relay(args: RelayArgs) -> anyhow::Result<()> {
    let path = args.config.display().to_string();
    let config = read_station_config(&args.config)?;
    let settings = RelaySettings::of(&config).with_context(|| {
        format!(
            "{path}: robot_link.relay_prefix is empty (the station publishes straight to the robot's topics): nothing to relay"
        )
    })?;
    for route in settings.routes.all() {
        eprintln!(
            "relay: {} → {} ({:?} in, {:?} out, depth {}), dropping commands older than {} ms",
            route.from,
            route.to,
            settings.link_qos.reliability,
            settings.robot_qos.reliability,
            settings.robot_qos.depth,
            settings.max_age_ms
        );
    }
    // The relay is the robot's only source of commands: crafted DATA_FRAG datagrams must not
    // exhaust its memory (docs/SECURITY.md).
    args.guard.apply();
    let report = Mutex::new(RelayReport::default());
    let network = args.node.network(&config.network);
    run_relay(
        &settings,
        &network,
        WallClock::from_env(),
        &report,
        ctrl_c_shutdown(),
    )
    .await?;
    if let Ok(report) = report.lock() {
        for (topic, counts) in &report.topics {
            let ages = &counts.ages;
            eprintln!(
                "relay: {topic}: forwarded {}, dropped {} ({} older than {} ms of which {} by their stamp only (late input, not the link), {} ahead of this clock, {} without a send time or stamp), {} lost in DDS, {} not published",
                ages.forwarded,
                ages.dropped(),
                ages.too_old,
                settings.max_age_ms,
                ages.too_old_by_stamp,
                ages.from_the_future,
                ages.unstamped,
                counts.input_errors,
                counts.publish_failed
            );
        }
        if let Some(offset) = report.clock_offset_ms {
            eprintln!(
                "relay: clock offset estimate at exit {offset:.1} ms (this computer's clock minus the station's)"
            );
        }
    }
    Ok(())
}
