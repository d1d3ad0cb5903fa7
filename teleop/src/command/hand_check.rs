//! `pomdar hand-check`: the hand's command conventions checked on the hand, joint by joint.

use std::path::PathBuf;

use anyhow::Context as _;
use clap::Args;
use retarget::HandModel;

use super::common::{NodeArgs, ctrl_c_shutdown};
use crate::atomic_file::write_atomically;
use crate::hand_check::check_node::{Answers, CheckOutput, run_check};
use crate::hand_check::hand_check_script::{ANSWER_WORDS, CheckScriptPlayer, load_check_script};
use crate::hand_check::session::{HandCheck, Motion};
use crate::hand_check::table_file::table_text;
use crate::station_driver::setup::read_station_config;
use crate::utc_date::{iso8601_utc, now_unix_s};

/// `pomdar hand-check` options.
#[derive(Debug, Args)]
pub struct HandCheckArgs {
    /// The station configuration whose [[policy_output.joints]] table is checked
    /// (launch_configs/station/eth_lab.toml, orca_core.toml).
    #[arg(long, value_name = "FILE")]
    pub config: PathBuf,
    /// Where the verified configuration is written (written only when every joint is
    /// confirmed).
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Who checks the hand (written into the table).
    #[arg(long, value_name = "NAME")]
    pub user: String,
    /// Timed answers instead of typed ones (see above).
    #[arg(long, value_name = "FILE")]
    pub script: Option<PathBuf>,
    /// The step each joint moves, radians of the URDF joint, at most 0.15.
    #[arg(long, default_value_t = Motion::default().step_rad)]
    pub step_rad: f64,
    /// Seconds the step takes each way, at least 1.
    #[arg(long, default_value_t = Motion::default().move_s)]
    pub move_s: f64,
    /// Seconds held at the end of the step.
    #[arg(long, default_value_t = Motion::default().hold_s)]
    pub hold_s: f64,
    /// Seconds to go to and hold the neutral pose first (at least --move-s).
    #[arg(long, default_value_t = Motion::default().settle_s)]
    pub settle_s: f64,
    /// Commands a second on the consumer's topic.
    #[arg(long, default_value_t = 25.0)]
    pub rate_hz: f64,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
    /// The RTPS datagram guard.
    #[command(flatten)]
    pub guard: super::common::GuardArgs,
}

/// `pomdar hand-check`.
pub async fn hand_check(args: HandCheckArgs) -> anyhow::Result<()> {
    // It drives the robot hand: crafted DATA_FRAG datagrams must not exhaust its memory.
    args.guard.apply();
    let config = read_station_config(&args.config)?;
    let text = std::fs::read_to_string(&args.config)
        .with_context(|| format!("cannot read {}", args.config.display()))?;
    if !(args.rate_hz >= 5.0 && args.rate_hz <= 200.0) {
        anyhow::bail!("--rate-hz = {} must be in [5, 200]", args.rate_hz);
    }
    let motion = Motion {
        step_rad: args.step_rad,
        move_s: args.move_s,
        hold_s: args.hold_s,
        settle_s: args.settle_s,
    };
    let table = config.policy_output.clone();
    let mut check = HandCheck::new(HandModel::orca_v1_right(), table.clone(), motion, 0.0)
        .with_context(|| format!("{}: policy_output", args.config.display()))?;
    // Through `pomdar relay` when the station's commands go through one, as the station's own.
    let (topic, qos) = config
        .robot_link
        .command_wire(&table.topic, config.output.qos);
    let output = CheckOutput {
        topic,
        qos,
        network: args.node.network(&config.network),
        rate_hz: args.rate_hz,
    };
    println!(
        "pomdar hand-check: {} on {} ({}, domain {}); {}",
        table.consumer,
        output.topic,
        match table.units {
            station::hand_convention::Units::Rad => "radians",
            station::hand_convention::Units::Deg => "degrees",
        },
        crate::ros::domain_id(output.network.domain_id)?,
        table.verification().line()
    );
    let answers = match &args.script {
        Some(path) => Answers::Script(CheckScriptPlayer::new(
            load_check_script(path)?,
            std::time::Instant::now(),
        )),
        None => {
            let words: Vec<String> = ANSWER_WORDS
                .iter()
                .map(|(long, short, _, _)| format!("{long} ({short})"))
                .collect();
            println!("answer on stdin: {}", words.join(", "));
            let (tx, rx) = tokio::sync::mpsc::unbounded_channel();
            crate::tui::terminal::read_stdin_lines(tx)?;
            Answers::Stdin(rx)
        }
    };
    run_check(&mut check, &output, answers, ctrl_c_shutdown()).await?;
    let at = iso8601_utc(now_unix_s());
    let verified = check.verified_table(&args.user, &at)?;
    let header = format!(
        "Written by pomdar hand-check from {}: every joint of the [policy_output] table\nchecked on the hand by {} on {at}.",
        args.config.display(),
        args.user
    );
    let written = table_text(&args.config, &text, &verified, &header)?;
    write_atomically(&args.out, written)?;
    println!(
        "wrote {}: {}",
        args.out.display(),
        verified.verification().line()
    );
    Ok(())
}
