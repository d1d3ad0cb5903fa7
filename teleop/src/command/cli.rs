//! `pomdar`'s command line: its subcommands (their help sits on each one's `Args`), and the process's exit status.
//! It lives in the library, and `main.rs` only calls [`main`]: the binary then compiles in a
//! second, where it took about 20 s of a cold release build's serial tail (the generic code
//! it instantiated).

use std::process::ExitCode;

use crate::command;
use clap::{Parser, Subcommand};

/// The POMDAR station: teleoperate a robot hand through the POMDAR dexterity benchmark and
/// score the trials.
///
/// Today: the ROS 2 station (glove keypoints in, ORCA joint targets and a constrained Franka
/// pose out), trial recording to MCAP, re-simulation, recovery and replay, a simulated
/// glove, mock robot nodes, the all-in-one demo, hand model inspection, the per-user glove
/// calibration, scoring trial logs against a human baseline, the Rokoko Studio and Apple
/// Vision Pro ingresses, a DDS discovery probe and the robot PC's command relay for
/// multi-host set-ups (docs/DEPLOYMENT.md), a
/// retargeting quality report for a recording, commanded vs measured joint angles of a trial,
/// and the operator console for timed trials.
#[derive(Debug, Parser)]
#[command(name = "pomdar", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The subcommands; each one's help (`about`, `long_about`) is the doc comment on its `Args`
/// in its own file under `command/`.
#[derive(Debug, Subcommand)]
enum Command {
    Demo(command::demo::DemoArgs),
    Station(command::station::StationArgs),
    SimGlove(command::sim_glove::SimGloveArgs),
    MockHand(command::mock_hand::MockHandArgs),
    MockFranka(command::mock_franka::MockFrankaArgs),
    Sim(command::sim::SimArgs),
    SimBench(command::sim_bench::SimBenchArgs),
    Resim(command::resim::ResimArgs),
    Eval(command::eval::EvalArgs),
    Tracking(command::tracking::TrackingArgs),
    Review(command::review::ReviewArgs),
    EvalSet(command::eval_set::EvalSetArgs),
    Recover(command::recover::RecoverArgs),
    Replay(command::replay::ReplayArgs),
    Probe(command::probe::ProbeArgs),
    Relay(command::relay::RelayArgs),
    Calibrate(command::calibrate::CalibrateArgs),
    HandCheck(command::hand_check::HandCheckArgs),
    Trial(command::trial::TrialArgs),
    Study(command::study::StudyArgs),
    StudyReport(command::study_report::StudyReportArgs),
    Score(command::score::ScoreArgs),
    Baseline(command::baseline::BaselineArgs),
    #[command(subcommand)]
    Ingress(command::ingress::IngressCommand),
    Model(command::model::ModelArgs),
}

/// The `pomdar` process: parse the command line, run the command, return its exit status.
pub fn main() -> ExitCode {
    crate::library_log::install();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Model(args) => command::model::model(args),
        Command::Score(args) => return exit_code(command::score::score(args)),
        Command::Baseline(args) => {
            return exit_code(command::baseline::baseline(args));
        }
        Command::Trial(args) => {
            return exit_code(command::shared_args::run_async(command::trial::trial(args)));
        }
        Command::Study(args) => {
            return exit_code(command::shared_args::run_async(command::study::study(args)));
        }
        Command::StudyReport(args) => {
            return exit_code(command::study_report::study_report(args));
        }
        Command::Demo(args) => command::shared_args::run_async(command::demo::demo(args)),
        Command::Calibrate(args) => return exit_code(command::calibrate::calibrate(args)),
        Command::Resim(args) => command::resim::resim(args),
        Command::Eval(args) => command::eval::eval(args),
        Command::Tracking(args) => command::tracking::tracking(args),
        Command::Review(args) => command::review::review(args),
        Command::EvalSet(args) => command::eval_set::eval_set(args),
        Command::Recover(args) => command::recover::recover(args),
        Command::Replay(args) => command::shared_args::run_async(command::replay::replay(args)),
        Command::Probe(args) => {
            return exit_code(command::shared_args::run_async(command::probe::run(args)));
        }
        Command::Relay(args) => command::shared_args::run_async(command::relay::relay(args)),
        Command::Ingress(command) => {
            command::shared_args::run_async(command::ingress::run(command))
        }
        Command::Station(args) => command::shared_args::run_async(command::station::station(args)),
        Command::SimGlove(args) => {
            command::shared_args::run_async(command::sim_glove::sim_glove(args))
        }
        Command::HandCheck(args) => {
            command::shared_args::run_async(command::hand_check::hand_check(args))
        }
        Command::MockHand(args) => {
            command::shared_args::run_async(command::mock_hand::mock_hand(args))
        }
        Command::Sim(args) => command::shared_args::run_async(command::sim::sim(args)),
        Command::SimBench(args) => return exit_code(command::sim_bench::sim_bench(args)),
        Command::MockFranka(args) => {
            command::shared_args::run_async(command::mock_franka::mock_franka(args))
        }
    };
    exit_code(result.map(|()| ExitCode::SUCCESS))
}

/// The process's exit status: the command's, or 1 after printing the error.
fn exit_code(result: anyhow::Result<ExitCode>) -> ExitCode {
    match result {
        Ok(code) => code,
        Err(error) => {
            eprintln!("error: {}", error_message(&error));
            ExitCode::FAILURE
        }
    }
}

/// The error and its causes on one line, `outer: inner: …`. A typed error's message already
/// carries its cause's text (the project's rule, ARCHITECTURE.md "Conventions"), so a cause
/// whose text the line holds already is not repeated.
fn error_message(error: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in error.chain() {
        let text = cause.to_string();
        if line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&text);
    }
    line
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, thiserror::Error)]
    #[error("profile /p.toml: {source}")]
    struct Outer {
        #[source]
        source: std::io::Error,
    }

    #[test]
    fn the_whole_command_line_is_consistent() {
        use clap::CommandFactory as _;
        Cli::command().debug_assert();
        let cli = Cli::try_parse_from([
            "pomdar",
            "score",
            "trials/",
            "--compare",
            "keypoint_source",
            "--compare-reference",
            "rokoko",
        ])
        .unwrap();
        let Command::Score(args) = cli.command else {
            panic!("not score");
        };
        assert_eq!(args.compare.as_deref(), Some("keypoint_source"));
    }

    #[test]
    fn a_cause_already_in_the_message_is_not_repeated_and_a_context_is_kept() {
        let io = std::io::Error::new(std::io::ErrorKind::NotFound, "no such file");
        let error = anyhow::Error::new(Outer { source: io }).context("pomdar resim");
        assert_eq!(
            error_message(&error),
            "pomdar resim: profile /p.toml: no such file"
        );
        let plain = anyhow::anyhow!("inner").context("outer");
        assert_eq!(error_message(&plain), "outer: inner");
    }
}
