//! `pomdar trial`: the operator console for timed trials. Its flags and their checks; the
//! console itself (the station in this process, the screen, the session's files) is
//! [`crate::console::run_session`].

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use super::shared_args::{ConsoleArgs, GuardArgs, MotionArg, NodeArgs, ViewArgs};
use crate::console::{SessionOptions, SimulationOptions, run_session};
use crate::score::score_inputs::ScoringFileArgs;
use crate::tui::terminal_shell::EXIT_INTERRUPTED;

/// The operator console for timed trials: practice, then a recorded series, per task.
///
/// Runs the station in this process and shows, full-screen: the task and what to mark,
/// the embodiment, the calibration profile, live health (glove rate, input age, latency,
/// engaged/held, watchdog, rejected frames, arm), the countdown and the running timer, and
/// after each trial its time, correctness, score (with a baseline), the series' mean ±
/// std and the trial's feedback (`pomdar review`: holds, pinches the robot did not close,
/// the wrist at its limit, …; nothing for a clean trial). Each trial is its own MCAP log
/// in the session directory (<out>/<user>/<embodiment>/<task>), its review figure and
/// JSON in review/, with session.json (the manifest) written after every change and
/// report/ (as `pomdar score --out`, ending with the trials worst first and their
/// feedback) when the plan is done. Run the same
/// command again to resume an interrupted session: a trial cut short by quit, Ctrl-C or a
/// crash is kept aside (*.interrupted) and run again.
///
/// --embodiment human is a human-study session (see `pomdar study`): no robot, no
/// retargeting, the glove's keypoints and wrist recorded; the start checks only the glove;
/// no practice and 3 trials unless --practice / --trials say otherwise.
///
/// Keys: e engage / clutch out · space start (after the countdown) / stop · + one notch or
/// curve · - take one back · p type a value (degrees, mm, grasp level 0 / 0.5 / 1) · d drop
/// · a abort (scored as aborted) · r redo (abort and run again, or set the last trial
/// aside) · n note · q quit (twice during a trial) · Ctrl-C quit now. A trial does not
/// start while the station is not engaged, the glove input is stale or slower than
/// --min-glove-rate.
///
/// Without a terminal (or with --plain) it prints a line per change and reads commands
/// from stdin, one per line: engage, disengage, start, stop, progress [V], unmark, drop,
/// abort, redo, note TEXT, quit. --script FILE plays timed commands instead:
///   # seconds since the start, or +S after the previous line
///   1.0  engage
///   wait ready 10        # wait (at most 10 s) for a state: waiting_engage, ready,
///   +0.5 start           #   countdown, running, finishing, summary, complete
///   wait running 10
///   +2   progress
///   +1   stop
///   wait summary 10
/// Exit status: 0 when the console ends normally, 130 after Ctrl-C or SIGTERM, 1 on an
/// error (a script's wait timing out, a bad file).
///
/// Examples:
///   pomdar trial --task V1 --embodiment orca_full --user alice --operator bob --profile profiles/alice.toml --baseline baselines/eth_2026.toml
///   pomdar trial --task G2 --user sim --operator me --simulate --practice 1 --trials 3
///   pomdar trial --task V1 --embodiment human --user p01 --operator bob
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct TrialArgs {
    /// The task ID (V1–V3, H1–H5, C1–C4, G1–G6; the catalog's IDs).
    #[arg(long, value_name = "ID")]
    pub task: String,
    /// The embodiment being benchmarked (the station's embodiment catalog), or `human`: a
    /// human-study session (no robot, no retargeting: the glove is recorded, the start
    /// checks only its health; see `pomdar study` for a plan over several tasks).
    #[arg(long, value_name = "NAME", default_value = "orca_full")]
    pub embodiment: String,
    /// The user wearing the glove, or the study's participant (names the session directory
    /// and goes into every log).
    #[arg(long, value_name = "NAME")]
    pub user: String,
    /// The operator running the session.
    #[arg(long, value_name = "NAME")]
    pub operator: String,
    /// Recorded trials in the series (default: the POMDAR protocol's 20 for a robot, the
    /// human study's 3 for `--embodiment human`).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=200))]
    pub trials: Option<u32>,
    /// Practice trials first, not in the series' mean (default: the POMDAR protocol's 5 for a
    /// robot, none for `--embodiment human`).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(0..=50))]
    pub practice: Option<u32>,
    /// Sessions directory; this session's is <DIR>/<user>/<embodiment>/<task>, holding one
    /// MCAP per trial, session.json (the manifest) and report/ when the plan is done. A
    /// session found there resumes where it stopped.
    #[arg(long, value_name = "DIR", default_value = "sessions")]
    pub out: PathBuf,
    /// Station configuration (default: the built-in ETH lab preset). The task sets the arm
    /// constraint.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// The user's calibration profile (from `pomdar calibrate`); overrides the configuration's.
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// The baseline (with it each trial shows its score, without it correctness only),
    /// catalog and rules.
    #[command(flatten)]
    pub scoring: ScoringFileArgs,
    /// The countdown, the start gate, the script and the display.
    #[command(flatten)]
    pub console: ConsoleArgs,
    /// Run a simulated glove, a mock hand and a mock Franka (only the glove for
    /// `--embodiment human`) in this process, on loopback (a domain of 150–229 that no other run
    /// on this machine holds, unless --domain-id): a demo or a rehearsal.
    #[arg(long)]
    pub simulate: bool,
    /// With --simulate: the simulated glove's motion (periodic, the wrist in place).
    #[arg(long, value_enum, value_name = "KIND", default_value = "task-like")]
    pub simulate_motion: MotionArg,
    /// With --simulate, instead of --simulate-motion: the simulated glove plays this task
    /// script (TOML keyframes of the wrist's offset from its start, glove frame, and the
    /// hand's pose, e.g. launch_configs/sim/grasp_place.toml) once from its first frame, then
    /// holds the last keyframe. The arm follows the wrist's path from the operator's engage:
    /// engage (a --script line, or the key) during the script's opening hold.
    #[arg(
        long,
        value_name = "FILE",
        requires = "simulate",
        conflicts_with = "simulate_motion"
    )]
    pub simulate_glove_script: Option<PathBuf>,
    /// With --simulate: the robot is the simulated one in the task's MuJoCo scene (needs the
    /// `physics` build: `bash sim/setup_mujoco.sh`, then `--features physics`). Its physics
    /// marks the progress as the operator's keys would (the operator can still correct a
    /// mark); every trial starts from the scene's initial state, and a
    /// --simulate-glove-script plays from each trial's start.
    #[arg(long, requires = "simulate")]
    pub physics: bool,
    /// With --physics: a lab's own task MJCF instead of the project's scaffold (see
    /// `pomdar sim --help`).
    #[arg(long, value_name = "FILE", requires = "physics")]
    pub scene: Option<PathBuf>,
    /// With --simulate: the simulated glove's keypoint noise, standard deviation per axis, mm
    /// (0–50; default 1, or 0.5 with --simulate-glove-script: the noise of a hand at rest, so
    /// the script's still phases are not taken for a stalled glove).
    #[arg(long, value_name = "MM", requires = "simulate")]
    pub simulate_glove_jitter_mm: Option<f64>,
    /// With --simulate: the simulated hand's size relative to an average adult hand
    /// (0.8–1.25; default: 1, or a size drawn from the user's name for `--embodiment human`,
    /// so each simulated participant has their own hand).
    #[arg(long, value_name = "SCALE")]
    pub simulate_hand_scale: Option<f64>,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
    /// The RTPS datagram guard.
    #[command(flatten)]
    pub guard: GuardArgs,
    /// The live view.
    #[command(flatten)]
    pub view: ViewArgs,
}

impl TrialArgs {
    /// The session these flags ask for.
    fn session(&self) -> SessionOptions {
        SessionOptions {
            task: self.task.clone(),
            embodiment: self.embodiment.clone(),
            user: self.user.clone(),
            operator: self.operator.clone(),
            trials: self.trials,
            practice: self.practice,
            out: self.out.clone(),
            config: self.config.clone(),
            profile: self.profile.clone(),
            scoring: self.scoring.clone(),
            console: self.console.settings(),
            network: self.node.overrides(),
            simulation: self.simulate.then(|| SimulationOptions {
                motion: self.simulate_motion.into(),
                glove_script: self.simulate_glove_script.clone(),
                physics: self.physics,
                scene: self.scene.clone(),
                glove_jitter_mm: self.simulate_glove_jitter_mm,
            }),
            simulated_hand_scale: self.simulate_hand_scale,
            view: self.view.view,
        }
    }
}

/// `pomdar trial`.
pub async fn trial(args: TrialArgs) -> anyhow::Result<ExitCode> {
    // The console runs the station: crafted DATA_FRAG datagrams must not exhaust its memory
    // (docs/SECURITY.md).
    args.guard.apply();
    let end = run_session(&args.session(), Vec::new()).await?;
    Ok(if end.interrupted {
        ExitCode::from(EXIT_INTERRUPTED)
    } else {
        ExitCode::SUCCESS
    })
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::*;

    #[derive(Debug, Parser)]
    struct Cli {
        #[command(flatten)]
        args: TrialArgs,
    }

    fn parse(extra: &[&str]) -> Result<TrialArgs, clap::Error> {
        let argv = [
            "pomdar",
            "--task",
            "G4",
            "--user",
            "sim",
            "--operator",
            "me",
        ];
        Cli::try_parse_from(argv.iter().chain(extra)).map(|c| c.args)
    }

    #[test]
    fn a_simulated_glove_script_needs_simulate_and_replaces_the_motion() {
        use clap::CommandFactory as _;
        Cli::command().debug_assert();
        assert_eq!(parse(&[]).unwrap().simulate_glove_script, None);
        let script = ["--simulate", "--simulate-glove-script", "grasp_place.toml"];
        let args = parse(&script).unwrap();
        assert_eq!(
            args.simulate_glove_script,
            Some(PathBuf::from("grasp_place.toml"))
        );
        assert!(parse(&script[1..]).is_err(), "needs --simulate");
        let both = [&script[..], &["--simulate-motion", "pinches"]].concat();
        assert!(parse(&both).is_err(), "one or the other");
    }
}
