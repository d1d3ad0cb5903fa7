//! `pomdar hand-check`: the hand's command conventions checked on the hand, joint by joint.

use std::path::PathBuf;

use anyhow::Context as _;
use clap::Args;
use retarget::HandModel;

use super::shared_args::NodeArgs;
use crate::atomic_file::write_atomically;
use crate::hand_check::check_node::{Answers, CheckOutput, run_check};
use crate::hand_check::hand_check_script::{ANSWER_WORDS, CheckScriptPlayer, load_check_script};
use crate::hand_check::session::{HandCheck, Motion};
use crate::hand_check::table_file::table_text;
use crate::station_driver::setup::read_station_config;
use crate::tui::terminal_shell::Wakeups;
use crate::utc_date::{iso8601_utc, now_unix_s};

/// Check a hand's command conventions on the hand, joint by joint, and write the table
/// verified.
///
/// The table is the station configuration's [[policy_output.joints]]: for each slot of
/// the array the consumer of the policy output topic reads (the ETH lab's hand-control
/// node in launch_configs/station/eth_lab.toml, orca_core in orca_core.toml), the
/// station joint, sign, offset, clamp range and units, where each number comes from and
/// whether it was checked. Stop the station first: both would drive the hand.
///
/// The hand goes to a neutral pose (each joint at the value nearest the URDF zero inside
/// its URDF limits and the consumer's range), then each joint in the table's order moves
/// a small step (--step-rad, at most 0.15 rad) slowly (--move-s each way, at least 1 s),
/// holds, and comes back, sent at --rate-hz through the table on the consumer's topic,
/// while the others hold still. The terminal shows the progress ("joint 6 of 17:
/// index_abd") and what the operator should see ("the index finger moves towards the
/// middle finger"), then asks. Answers, typed on stdin (one a line) or from --script:
///   yes (y)     it moved as named: the next joint
///   no (n)      it moved the other way; then
///     flip (f)  flip its sign in the table and move it again (confirm it with yes)
///     keep (k)  keep the sign and move it again
///   repeat (r)  move it again
///   quit (q)    stop
/// The check settles directions (signs) only: a wrong offset or zero (orca_core's
/// ref_zero) shows in the neutral pose, which the operator should look at first; a
/// flipped joint keeps its offset and range.
///
/// When every joint is confirmed, --out is written atomically: the configuration file
/// with its [policy_output] replaced by the table with every row verified = true (and
/// any flipped sign, noted), verified_by = --user and verified_at (UTC); other tables
/// and comments are kept. If any joint is not confirmed (quit, Ctrl-C or SIGTERM,
/// stdin or the script ended) nothing is written and the exit status is 1, naming
/// the joints left.
///
/// --script FILE: answers one a line, optionally after a time (seconds since the start,
/// or +S after the previous line), and `wait PHASE [TIMEOUT_S]` with PHASE one of
/// settling, moving, asking, offer_flip, complete, quit (default timeout 30 s):
///   wait asking 30
///   yes
///   wait asking 30
///   no
///   flip
///
/// Try it without a hand: `pomdar mock-hand --policy-config FILE` follows the same
/// topic through the inverse of the table.
///
/// Examples:
///   pomdar hand-check --config launch_configs/station/eth_lab.toml --user ana --out lab/eth_lab_verified.toml
///   pomdar hand-check --config launch_configs/station/orca_core.toml --user ana --out /tmp/orca.toml --script check.script
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
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
    pub guard: super::shared_args::GuardArgs,
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
    run_check(&mut check, &output, answers, Wakeups::with_signals()?).await?;
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
