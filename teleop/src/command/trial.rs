//! `pomdar trial`: the operator console for timed trials. Runs the station in this process,
//! shows the task, the health and the timer full-screen (or as lines without a terminal),
//! takes the operator's keys (or a `--script`), logs one MCAP per trial, keeps the session
//! manifest, scores each trial as it ends and writes the session's report when the plan is
//! done.
//!
//! Test-only slow-down, off by default: `POMDAR_CONSOLE_TEST_PAUSE_MS=N` makes the console
//! sleep N ms (saying `test pause N ms: STEP` on stderr) inside its saving steps (a `.part`
//! recovered on resume, the resumed manifest, a finished trial's scoring, the manifest after a
//! trial, the report), so a test's random kills land in them; see
//! [`crate::console::test_pause`] and `tests/tests/suite/console_random_kills.rs`. Nothing else
//! changes with it.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use anyhow::Context as _;
use clap::Args;
use retarget::HandModel;
use retarget::human_hand::{GloveScript, MotionKind};
use scoring::TaskSpec;
use tokio::signal::unix::Signal;
use tokio::sync::{mpsc, watch};
use tokio::task::JoinHandle;

use super::trial_physics::{PhysicsLink, PhysicsParts, next_progress, progress_action};
use crate::atomic_file::write_atomically;
use crate::clock::StationClock;
use crate::command::common::{MotionArg, NodeArgs, ViewArgs};
use crate::console::message_log::MessageLog;
use crate::device_thread::spawn_device;
use crate::disk_wait::without_holding_the_runtime;
use crate::ros::NetworkConfig;
use crate::ros::default_domain_id;
use crate::score::report_files::write_report_files;
use crate::score::score_inputs::{ScoringFileArgs, ScoringInputs};
use crate::sim::glove_script_file::load_glove_script;
use crate::sim::mock_robot::spawn_mock_robot;
use crate::sim::sim_glove_node::{GloveOrigin, SimGloveConfig, publish_glove};
use crate::station_node::recorder::{RecordingOptions, config_digest};
use crate::station_node::ros_node::{
    LatestInput, OperatorCommand, StationEvent, StationHooks, StationSummary, run_station_observed,
};
use crate::trial_review::review_trial_file_in_background;
use crate::utc_date::{compact_utc, now_unix_s};
use station::StationConfig;
use station::ros_tools::ServiceAction;

use crate::console::health::{Health, StartLimits};
use crate::console::keys::{Action, key_action, parse_action};
use crate::console::manifest::{MANIFEST_FILE, TrialStatus};
use crate::console::plain_output::PlainOutput;
use crate::console::screen::draw;
use crate::console::session_dir::{SessionPlan, check_name, open_session, session_dir};
use crate::console::test_pause::test_pause;
use crate::console::trial_flow::{Effect, Phase, Slot, TrialFlow};
use crate::console::trial_script::{TrialScriptLine, load_script};
use crate::console::view::{ConsoleView, Screen, SessionInfo};
use crate::tui::script_player::ScriptPlayer;
use crate::tui::terminal::{FullScreen, Input, full_screen_wanted, read_stdin_lines};

/// How often a trial's log is flushed (and synced) at least, ns of log time: a kill or a
/// crash loses at most this much of the running trial, plus the writes in flight, well within
/// the second the console promises (the writer's default, 1 s, left no margin for them).
const TRIAL_LOG_FLUSH_INTERVAL_NS: i64 = 500_000_000;

/// Exit status after Ctrl-C (or SIGTERM).
pub const EXIT_INTERRUPTED: u8 = 130;

/// `pomdar trial` options.
#[derive(Debug, Args)]
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
    pub guard: super::common::GuardArgs,
    /// The live view.
    #[command(flatten)]
    pub view: ViewArgs,
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

fn check_range(flag: &str, value: f64, low: f64, high: f64, unit: &str) -> anyhow::Result<()> {
    if !(value.is_finite() && value >= low && value <= high) {
        anyhow::bail!("{flag} {value} is outside the allowed range [{low}, {high}] {unit}");
    }
    Ok(())
}

/// Where the console's actions come from and where it shows itself.
enum Display {
    Full(FullScreen),
    Plain(PlainOutput),
}

/// A prompt being typed in the full-screen console.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Prompt {
    Progress,
    Note,
}

/// Default protocols: (practice, recorded trials).
const ROBOT_PROTOCOL: (u32, u32) = (5, 20);
/// The POMDAR human study's protocol: no practice, three trials per task.
pub const HUMAN_PROTOCOL: (u32, u32) = (0, 3);

impl TrialArgs {
    /// Whether this is a human-study session (embodiment `human`).
    pub fn human(&self) -> bool {
        self.embodiment == station::HUMAN_EMBODIMENT
    }

    /// Practice and recorded trials: the flags, else the protocol's defaults.
    pub fn plan_counts(&self) -> (u32, u32) {
        let (practice, trials) = if self.human() {
            HUMAN_PROTOCOL
        } else {
            ROBOT_PROTOCOL
        };
        (
            self.practice.unwrap_or(practice),
            self.trials.unwrap_or(trials),
        )
    }
}

/// How a console session ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SessionEnd {
    /// Ctrl-C, SIGTERM, q or stdin closed.
    pub interrupted: bool,
    /// Every planned trial is done.
    pub complete: bool,
}

/// `pomdar trial`.
pub async fn trial(args: TrialArgs) -> anyhow::Result<ExitCode> {
    // The console runs the station: crafted DATA_FRAG datagrams must not exhaust its memory
    // (docs/SECURITY.md).
    args.guard.apply();
    let end = run_session(&args, Vec::new()).await?;
    Ok(if end.interrupted {
        ExitCode::from(EXIT_INTERRUPTED)
    } else {
        ExitCode::SUCCESS
    })
}

/// One task's console session; `study` lines are added to the setting shown (the study's
/// plan and where the participant is in it).
pub async fn run_session(
    args: &TrialArgs,
    study: Vec<(String, String)>,
) -> anyhow::Result<SessionEnd> {
    check_args(args)?;
    let inputs = args.scoring.load()?;
    let task = task_of(args, &inputs)?;
    let config = station_config_for(args, &task)?;
    let model = HandModel::orca_v1_right();
    // The profile and the embodiment are checked before any log or node exists.
    crate::station_driver::setup::build_station(&config, model.clone())?;
    let script = args
        .console
        .script
        .as_deref()
        .map(load_script)
        .transpose()?;
    let glove_script = args
        .simulate_glove_script
        .as_deref()
        .map(load_glove_script)
        .transpose()?;

    let plan = session_plan(args, &task, &config);
    let dir = session_dir(&args.out, &plan);
    let score = |path: &Path| inputs.score_file(path).map_err(|e| e.to_string());
    let (manifest, opened) = open_session(&dir, &plan, &score)?;
    let limits = StartLimits {
        min_glove_rate_hz: args.console.min_glove_rate,
        max_input_age_ms: args.console.max_input_age,
        max_status_age_ms: StartLimits::default().max_status_age_ms,
        drives_robot: !args.human(),
    };
    let mut flow = TrialFlow::new(manifest, task.correctness, args.console.countdown, limits);
    for line in opened {
        flow.say(line);
    }
    let mut info = session_info(args, &plan, &config, &dir, &inputs, task.clone(), limits)?;
    info.setup.splice(0..0, study);

    // The live view, then the station (and, with --simulate, the glove and the robot).
    let view = args.view.start().await?;
    if let Some(view) = &view {
        flow.say(view.announcement());
    }
    let clock = StationClock::new();
    let tap = view.as_ref().map(|v| v.tap.clone());
    let station = spawn_station(args, (&config, &task), &model, clock, tap, glove_script)?;
    let operator = OperatorSide::open(args.console.plain, script)?;
    let mut console = TrialConsole {
        operator,
        wakeups: Wakeups::start()?,
        session: Session {
            flow,
            health: Health::default(),
            info,
            inputs,
            manifest_path: dir.join(MANIFEST_FILE),
            message_log: MessageLog::new(&dir),
            dir,
            report_written: false,
            config: config.clone(),
        },
        station,
        clock,
        end: ConsoleEnd::default(),
    };
    console.run().await?;
    let end = console.finish().await;
    if let Some(view) = view {
        view.stop().await;
    }
    end
}

/// The names and ranges of the flags.
fn check_args(args: &TrialArgs) -> anyhow::Result<()> {
    check_name("--user", &args.user)?;
    check_name("--operator", &args.operator)?;
    check_name("--embodiment", &args.embodiment)?;
    if args.human() && args.profile.is_some() {
        anyhow::bail!(
            "--profile: a human-study session (--embodiment human) drives no robot and uses no calibration profile"
        );
    }
    if let Some(scale) = args.simulate_hand_scale {
        check_range(
            "--simulate-hand-scale",
            scale,
            0.5,
            2.0,
            "(relative hand size)",
        )?;
    }
    check_range("--countdown", args.console.countdown, 0.0, 30.0, "s")?;
    check_range(
        "--min-glove-rate",
        args.console.min_glove_rate,
        0.0,
        1000.0,
        "Hz",
    )?;
    check_range(
        "--max-input-age",
        args.console.max_input_age,
        10.0,
        10_000.0,
        "ms",
    )?;
    Ok(())
}

/// The `--task` in the catalog.
fn task_of(args: &TrialArgs, inputs: &ScoringInputs) -> anyhow::Result<TaskSpec> {
    inputs.catalog.get(&args.task).cloned().ok_or_else(|| {
        anyhow::anyhow!(
            "--task {:?} is not in the {} ({})",
            args.task,
            inputs.catalog.origin,
            inputs.catalog.ids()
        )
    })
}

/// The station's configuration for this session: the file (or the preset) with the profile,
/// the network (loopback with `--simulate`), the embodiment and the task's arm constraint;
/// engaged by the operator only.
fn station_config_for(args: &TrialArgs, task: &TaskSpec) -> anyhow::Result<StationConfig> {
    let mut config = crate::station_driver::setup::load_station_config(
        args.config.as_deref(),
        args.profile.as_deref(),
    )?;
    config.network = args.node.network(&config.network);
    if args.simulate {
        config.network = NetworkConfig {
            domain_id: Some(args.node.domain_id.unwrap_or_else(default_domain_id)),
            interfaces: vec![std::net::IpAddr::from([127, 0, 0, 1])],
        };
    }
    config.retarget.embodiment.clone_from(&args.embodiment);
    if args.human() {
        // No robot: nothing is retargeted, so no user's calibration applies.
        config.calibration_profile = None;
    }
    config.arm.constraint = task.arm;
    config.control.auto_engage = false;
    config.validate()?;
    Ok(config)
}

/// What the session is: its task, embodiment, people, plan and the files it depends on.
fn session_plan(args: &TrialArgs, task: &TaskSpec, config: &StationConfig) -> SessionPlan {
    let (practice, trials) = args.plan_counts();
    SessionPlan {
        task: task.id.clone(),
        embodiment: args.embodiment.clone(),
        user: args.user.clone(),
        operator: args.operator.clone(),
        practice,
        trials,
        calibration_profile: config
            .calibration_profile
            .as_ref()
            .map(|p| p.display().to_string()),
        config_digest: config_digest(config),
        baseline: args
            .scoring
            .baseline
            .as_ref()
            .map(|p| p.display().to_string()),
    }
}

/// The setting the console shows all session long: the task, the setup, the baseline and
/// the start limits.
fn session_info(
    args: &TrialArgs,
    plan: &SessionPlan,
    config: &StationConfig,
    dir: &Path,
    inputs: &ScoringInputs,
    task: TaskSpec,
    limits: StartLimits,
) -> anyhow::Result<SessionInfo> {
    let baseline_s = inputs
        .baseline
        .as_ref()
        .and_then(|b| b.get(&task.id))
        .map(|b| b.mean_s);
    let (who, embodiment, profile) = if args.human() {
        (
            "participant",
            "human (study: no robot, the glove is recorded)".to_string(),
            "none (no retargeting)".to_string(),
        )
    } else {
        (
            "user",
            args.embodiment.clone(),
            plan.calibration_profile
                .clone()
                .unwrap_or_else(|| "none (scale 1, no rotation)".into()),
        )
    };
    let simulated = match (args.simulate, args.human()) {
        (false, _) => "",
        (true, true) => " (simulated glove)",
        (true, false) => " (simulated glove and robot)",
    };
    Ok(SessionInfo {
        setup: vec![
            (who.into(), args.user.clone()),
            ("operator".into(), args.operator.clone()),
            ("embodiment".into(), embodiment),
            ("profile".into(), profile),
            (
                "baseline".into(),
                match baseline_s {
                    Some(b) => format!("{b:.1} s ({})", plan.baseline.clone().unwrap_or_default()),
                    None => "none for this task: correctness only".into(),
                },
            ),
            (
                "plan".into(),
                format!("{} practice + {} recorded", plan.practice, plan.trials),
            ),
            ("session".into(), dir.display().to_string()),
            (
                "domain".into(),
                format!(
                    "{}{simulated}",
                    crate::ros::domain_id(config.network.domain_id)?
                ),
            ),
        ],
        task,
        baseline_s,
        limits,
        hand_convention: (!config.policy_output.topic.is_empty())
            .then(|| config.policy_output.verification()),
    })
}

/// The station running in this process (and, with `--simulate`, the glove and the robot):
/// what the console holds of it.
struct StationHandles {
    /// The station's task; its summary when it stops.
    task: JoinHandle<Result<StationSummary, crate::station_node::NodeError>>,
    /// Commands to the station.
    operator_tx: mpsc::UnboundedSender<OperatorCommand>,
    /// The station's status, as published.
    status_rx: watch::Receiver<Option<serde_json::Value>>,
    /// Trial log starts and ends, and messages for the operator.
    events_rx: mpsc::UnboundedReceiver<StationEvent>,
    /// The newest glove frame's receive time, kept by the station at every frame.
    latest_input: LatestInput,
    /// Stops the station and the simulation.
    shutdown_tx: watch::Sender<bool>,
    _shutdown_rx: watch::Receiver<bool>,
    /// `--simulate`: the hand's, the arm's and the glove's tasks.
    simulated: Vec<JoinHandle<Result<(), crate::sim::SimError>>>,
    /// `--physics`: the simulated robot's progress events and resets.
    physics: Option<PhysicsLink>,
}

/// Starts the station (status and trial-log events back to the console) and, with
/// `--simulate`, the glove (playing `glove_script` if given) and the robot.
fn spawn_station(
    args: &TrialArgs,
    (config, task): (&StationConfig, &TaskSpec),
    model: &HandModel,
    clock: StationClock,
    tap: Option<crate::station_node::tap::Tap>,
    glove_script: Option<GloveScript>,
) -> anyhow::Result<StationHandles> {
    let (shutdown_tx, shutdown_rx) = watch::channel(false);
    let (operator_tx, operator_rx) = mpsc::unbounded_channel();
    let (status_tx, status_rx) = watch::channel(None);
    let (events_tx, events_rx) = mpsc::unbounded_channel();
    let latest_input = LatestInput::default();
    let station = tokio::spawn(run_station_observed(
        config.clone(),
        model.clone(),
        clock,
        shutdown_rx.clone(),
        operator_rx,
        None,
        StationHooks {
            status: Some(status_tx),
            events: Some(events_tx),
            latest_input: Some(latest_input.clone()),
            tap,
            trial_log_flush_interval_ns: Some(TRIAL_LOG_FLUSH_INTERVAL_NS),
            ..StationHooks::default()
        },
    ));
    let mut simulated = Vec::new();
    let mut physics = None;
    if args.simulate {
        let robot = SimulatedRobot {
            config,
            model,
            task,
        };
        (simulated, physics) = spawn_simulation(args, &robot, clock, &shutdown_rx, glove_script)?;
    }
    Ok(StationHandles {
        task: station,
        operator_tx,
        status_rx,
        events_rx,
        latest_input,
        shutdown_tx,
        _shutdown_rx: shutdown_rx,
        simulated,
        physics,
    })
}

/// The operator's side: where the console shows itself and where its actions come from.
struct OperatorSide {
    display: Display,
    /// Whether the console is full-screen (a keyboard says q).
    full_screen: bool,
    /// Keys, or lines of stdin.
    input_rx: mpsc::UnboundedReceiver<Input>,
    _keep_open: mpsc::UnboundedSender<Input>,
    /// `--script`.
    player: Option<ScriptPlayer<Action, Screen>>,
    scripted: bool,
    /// A prompt being typed (full-screen).
    prompt: Option<(Prompt, String)>,
    /// When the console started (the line console's time).
    started: Instant,
}

impl OperatorSide {
    /// Full-screen when wanted (not `plain`, on a terminal), else lines; the line console
    /// without a script reads commands from stdin.
    fn open(plain: bool, script: Option<Vec<TrialScriptLine>>) -> anyhow::Result<OperatorSide> {
        let (input_tx, input_rx) = mpsc::unbounded_channel();
        let full_screen = full_screen_wanted(plain);
        let display = if full_screen {
            Display::Full(FullScreen::enter(input_tx.clone())?)
        } else {
            if script.is_none() {
                read_stdin_lines(input_tx.clone())?;
                eprintln!(
                    "pomdar trial: line console; type commands, one per line: {}",
                    crate::console::keys::ACTION_WORDS
                        .iter()
                        .map(|(w, _)| *w)
                        .collect::<Vec<_>>()
                        .join(", ")
                );
            }
            Display::Plain(PlainOutput::default())
        };
        let player = script.map(|s| ScriptPlayer::new(s, Instant::now()));
        let scripted = player.is_some();
        Ok(OperatorSide {
            display,
            full_screen,
            input_rx,
            _keep_open: input_tx,
            player,
            scripted,
            prompt: None,
            started: Instant::now(),
        })
    }

    /// Draws the session full-screen (with the prompt being typed) or prints what changed.
    fn show(&mut self, session: &Session, now: i64) -> anyhow::Result<()> {
        let flow = &session.flow;
        let view = ConsoleView::build(flow, &session.health, &session.info, now);
        match &mut self.display {
            Display::Full(screen) => {
                let typed_text = self.prompt.as_ref().map(|(kind, text)| match kind {
                    Prompt::Progress => {
                        format!("progress ({}): {text}", flow.kind().progress_unit())
                    }
                    Prompt::Note => format!("note: {text}"),
                });
                screen.draw(|frame| draw(frame, &view, typed_text.as_deref()))?;
            }
            Display::Plain(out) => {
                out.update(&view, flow.said(), self.started.elapsed().as_secs_f64());
            }
        }
        Ok(())
    }
}

/// What wakes the console besides the station and the operator: its tick and the signals.
struct Wakeups {
    tick: tokio::time::Interval,
    interrupt: Signal,
    terminate: Signal,
}

impl Wakeups {
    fn start() -> anyhow::Result<Wakeups> {
        // Listening from the start, so a signal between two turns of the loop is not missed.
        let terminate = tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate())
            .context("cannot watch SIGTERM")?;
        let interrupt = tokio::signal::unix::signal(tokio::signal::unix::SignalKind::interrupt())
            .context("cannot watch SIGINT")?;
        Ok(Wakeups {
            tick: tokio::time::interval(Duration::from_millis(50)),
            interrupt,
            terminate,
        })
    }
}

/// The session: its state machine, the station's last health, what is shown all along and
/// the files.
struct Session {
    flow: TrialFlow,
    health: Health,
    info: SessionInfo,
    /// The baseline, catalog and rules each trial is scored with.
    inputs: ScoringInputs,
    /// The session directory and its manifest.
    dir: PathBuf,
    manifest_path: PathBuf,
    /// Whether the complete session's report is written.
    report_written: bool,
    /// The console's messages, kept in the session directory.
    message_log: MessageLog,
    /// The station's configuration (the topics and limits each trial is reviewed with).
    config: StationConfig,
}

impl Session {
    /// The trial log's metadata.
    fn trial_metadata(&self, slot: &Slot) -> BTreeMap<String, String> {
        let flow = &self.flow;
        BTreeMap::from([
            ("task".to_string(), flow.manifest.task.clone()),
            ("user".to_string(), flow.manifest.user.clone()),
            ("operator".to_string(), flow.manifest.operator.clone()),
            (
                "calibration_profile".to_string(),
                flow.manifest
                    .calibration_profile
                    .clone()
                    .unwrap_or_else(|| "none".into()),
            ),
            ("trial_index".to_string(), slot.index.to_string()),
            ("practice".to_string(), slot.practice.to_string()),
            ("session".to_string(), self.dir.display().to_string()),
            ("source".to_string(), "pomdar trial".to_string()),
        ])
    }

    fn save_manifest(&mut self) {
        self.flow.manifest.updated_utc = compact_utc(now_unix_s());
        if let Err(e) = self.flow.manifest.save(&self.manifest_path) {
            self.flow
                .say(format!("error: cannot save the manifest: {e:#}"));
        }
        test_pause("the manifest saved");
    }

    /// A trial set aside: its file renamed.
    fn set_aside(&mut self, from: &str, to: &str) {
        if let Err(e) = std::fs::rename(self.dir.join(from), self.dir.join(to)) {
            self.flow
                .say(format!("error: cannot rename {from} to {to}: {e}"));
        }
    }

    /// Writes the session's report once the plan is complete (again after a trial redone).
    fn write_report_once_complete(&mut self) {
        if *self.flow.phase() != Phase::Complete {
            // A trial redone after the plan was complete: the report is written again.
            self.report_written = false;
        } else if !self.report_written {
            self.report_written = true;
            test_pause("the session complete: writing its report");
            let written = without_holding_the_runtime(|| {
                write_session_report(&self.dir, &self.flow, &self.inputs)
            });
            match written {
                Ok(path) => self
                    .flow
                    .say(format!("session complete: report in {}", path.display())),
                Err(e) => self
                    .flow
                    .say(format!("error: cannot write the session report: {e:#}")),
            }
        }
    }

    /// The session's state on stdout after the console: trials done, trials not scored,
    /// whether it can be resumed.
    fn print_summary(&self) {
        let m = &self.flow.manifest;
        println!(
            "session {}: {} of {} practice and {} of {} recorded trials done; manifest {}",
            self.dir.display(),
            m.done(true),
            m.practice_planned,
            m.done(false),
            m.trials_planned,
            self.manifest_path.display()
        );
        for trial in m.trials.iter().filter(|t| t.status != TrialStatus::Scored) {
            println!("  {}: {:?}", trial.file, trial.status);
        }
        if m.next_slot().is_some() {
            println!("not complete: run the same command again to resume");
        }
    }
}

/// How the console ends.
#[derive(Default)]
struct ConsoleEnd {
    /// Ctrl-C, SIGTERM, q or stdin closed: exit status [`EXIT_INTERRUPTED`].
    interrupted: bool,
    /// A script that failed (a wait timed out).
    failure: Option<anyhow::Error>,
}

/// What one wake-up brought: the operator's actions and the session's effects so far.
#[derive(Default)]
struct Turn {
    actions: Vec<Action>,
    effects: Vec<Effect>,
}

/// What happens after a turn of the console's loop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Next {
    /// Wait for the next tick, key, status or station event.
    Continue,
    /// Leave the console.
    Quit,
}

/// `pomdar trial` while it runs: the operator's side, the session, the station.
struct TrialConsole {
    operator: OperatorSide,
    wakeups: Wakeups,
    session: Session,
    station: StationHandles,
    clock: StationClock,
    end: ConsoleEnd,
}

impl TrialConsole {
    /// Turns until the console quits: wait for something, then act on it.
    async fn run(&mut self) -> anyhow::Result<()> {
        loop {
            let mut turn = Turn::default();
            self.wait(&mut turn).await?;
            if self.finish_turn(turn)? == Next::Quit {
                return Ok(());
            }
        }
    }

    /// Waits for a tick, the station's status or events, a key or line, or a signal; an
    /// error when the station stops.
    async fn wait(&mut self, turn: &mut Turn) -> anyhow::Result<()> {
        tokio::select! {
            _ = self.wakeups.tick.tick() => {}
            Ok(()) = self.station.status_rx.changed() => self.status_changed(),
            Some(input) = self.operator.input_rx.recv() => self.input(input, &mut turn.actions),
            Some(event) = self.station.events_rx.recv() => self.station_event(event, turn),
            Some(progress) = next_progress(&mut self.station.physics) => {
                // Marks count only in a running trial; between trials the physics is ignored.
                if matches!(self.session.flow.phase(), Phase::Running { .. }) {
                    turn.actions.push(progress_action(&progress));
                }
            }
            result = &mut self.station.task => return Err(station_stopped(result)),
            _ = self.wakeups.interrupt.recv() => turn.actions.push(Action::Interrupt),
            _ = self.wakeups.terminate.recv() => turn.actions.push(Action::Interrupt),
        }
        Ok(())
    }

    fn status_changed(&mut self) {
        if let Some(status) = self.station.status_rx.borrow_and_update().as_ref() {
            self.session.health = Health::from_status(status, self.clock.now_ns());
        }
    }

    /// A key or a line: an action, or a key typed into the prompt.
    fn input(&mut self, input: Input, actions: &mut Vec<Action>) {
        let flow = &mut self.session.flow;
        match input {
            Input::CtrlC => actions.push(Action::Interrupt),
            Input::Line(line) if !line.trim().is_empty() => match parse_action(&line) {
                Ok(action) => actions.push(action),
                Err(e) => flow.say(e.to_string()),
            },
            Input::Line(_) => {}
            Input::Closed => {
                flow.say("stdin closed: quitting (a running trial is set aside)");
                actions.push(Action::Interrupt);
            }
            key => {
                if let Some(action) = typed(&mut self.operator.prompt, key) {
                    actions.push(action);
                }
            }
        }
    }

    /// A trial log started, finished or failed, or a message from the station.
    fn station_event(&mut self, event: StationEvent, turn: &mut Turn) {
        let effects = &mut turn.effects;
        let flow = &mut self.session.flow;
        let inputs = &self.session.inputs;
        match event {
            StationEvent::TrialStarted(path) => flow.say(format!("recording {}", path.display())),
            StationEvent::TrialStartFailed { path, error } => {
                effects.extend(flow.trial_start_failed(&format!("{}: {error}", path.display())));
            }
            StationEvent::TrialFinished(path) => {
                test_pause(&format!("{} finished: scoring it", path.display()));
                let (said, scored) = without_holding_the_runtime(|| {
                    let said = review_lines(&path, &self.session.dir, &self.session.config);
                    (said, inputs.score_file(&path).map_err(|e| e.to_string()))
                });
                effects.extend(flow.trial_logged(scored));
                for line in said {
                    flow.say(line);
                }
            }
            StationEvent::TrialFinishFailed { path, error } => {
                effects.extend(flow.trial_logged(Err(format!(
                    "the log {} could not be finished: {error} (its .part is kept for pomdar recover)",
                    path.display()
                ))));
            }
            StationEvent::Message(text) => flow.say(text),
            StationEvent::ServiceRequest(action) => turn.actions.push(match action {
                ServiceAction::Engage => Action::Engage,
                ServiceAction::Disengage => Action::Disengage,
                ServiceAction::TrialStart => Action::Start,
                ServiceAction::TrialStop => Action::Stop,
                ServiceAction::TrialAbort => Action::Abort,
            }),
        }
    }

    /// The rest of a turn: the script's and the operator's actions and the clock go to the
    /// session, its effects are carried out, the report written when the plan is complete,
    /// the console shown.
    fn finish_turn(&mut self, mut turn: Turn) -> anyhow::Result<Next> {
        let now = self.clock.now_ns();
        // The newest status, even when this turn woke for something else: a turn that waited
        // on the disk must not take the station for silent.
        if self.station.status_rx.has_changed().unwrap_or(false) {
            self.status_changed();
        }
        self.session.health.latest_input_ns = self.station.latest_input.get();
        self.play_script(&mut turn.actions);
        self.act(turn.actions, &mut turn.effects, now);
        let session = &mut self.session;
        turn.effects.extend(session.flow.tick(&session.health, now));
        let mut next = self.carry_out(turn.effects);
        self.session.write_report_once_complete();
        if self.done_unattended() {
            next = Next::Quit;
        }
        let session = &mut self.session;
        session.message_log.append_new(&mut session.flow);
        self.operator.show(&self.session, now)?;
        Ok(next)
    }

    /// The script's due action in the current screen; a script that failed interrupts.
    fn play_script(&mut self, actions: &mut Vec<Action>) {
        let screen_now = Screen::of(&self.session.flow, &self.session.health);
        if let Some(p) = self.operator.player.as_mut() {
            match p.next(screen_now, Instant::now()) {
                Ok(Some(action)) => actions.push(action),
                Ok(None) => {}
                Err(e) => {
                    self.session.flow.say(e.to_string());
                    self.end.failure = Some(e.into());
                    actions.push(Action::Interrupt);
                }
            }
        }
    }

    /// The actions: prompts open, the rest go to the session.
    fn act(&mut self, actions: Vec<Action>, effects: &mut Vec<Effect>, now: i64) {
        let session = &mut self.session;
        for action in actions {
            if action == Action::Interrupt {
                self.end.interrupted = true;
            }
            match action {
                Action::PromptProgress => {
                    self.operator.prompt = Some((Prompt::Progress, String::new()));
                }
                Action::PromptNote => self.operator.prompt = Some((Prompt::Note, String::new())),
                other => effects.extend(session.flow.act(other, &session.health, now)),
            }
        }
    }

    /// Carries out the session's effects: commands to the station, the manifest, trials set
    /// aside, quitting.
    fn carry_out(&mut self, effects: Vec<Effect>) -> Next {
        let operator_tx = &self.station.operator_tx;
        let mut next = Next::Continue;
        for effect in effects {
            match effect {
                Effect::Engage => send(operator_tx, OperatorCommand::Engage),
                Effect::Disengage => send(operator_tx, OperatorCommand::Disengage),
                Effect::TrialEvent(event) => send(operator_tx, OperatorCommand::TrialEvent(event)),
                Effect::StopTrial => send(operator_tx, OperatorCommand::StopTrial),
                Effect::StartTrial { file, slot } => {
                    if let Some(physics) = &self.station.physics {
                        physics.trial_started(self.clock.now_ns());
                    }
                    let metadata = self.session.trial_metadata(&slot);
                    let dir = &self.session.dir;
                    send(
                        operator_tx,
                        OperatorCommand::StartTrial(RecordingOptions {
                            path: dir.join(&file),
                            metadata,
                        }),
                    );
                }
                // The disk's waits must not hold up the station this loop has just woken.
                Effect::SaveManifest => {
                    without_holding_the_runtime(|| self.session.save_manifest());
                }
                Effect::SetAside { from, to } => {
                    without_holding_the_runtime(|| self.session.set_aside(&from, &to));
                }
                Effect::Quit => next = Next::Quit,
            }
        }
        next
    }

    /// Without a keyboard to say q, a finished plan (and script) ends the console.
    fn done_unattended(&self) -> bool {
        let operator = &self.operator;
        *self.session.flow.phase() == Phase::Complete
            && !operator.full_screen
            && (!operator.scripted || operator.player.as_ref().is_some_and(ScriptPlayer::finished))
    }

    /// The console has quit: the station disengages and stops, the console is left, the
    /// session's state printed; the exit status says whether it was interrupted.
    async fn finish(self) -> anyhow::Result<SessionEnd> {
        let TrialConsole {
            operator,
            session,
            station,
            end,
            ..
        } = self;
        let StationHandles {
            task: station,
            operator_tx,
            shutdown_tx,
            simulated,
            ..
        } = station;
        // The station stops commanding: the robot holds its last target.
        send(&operator_tx, OperatorCommand::Disengage);
        shutdown_tx.send(true).ok();
        let summary = station.await.context("station task")??;
        for task in simulated {
            task.await.ok();
        }
        drop(operator.display);
        session.print_summary();
        let complete = session.flow.manifest.next_slot().is_none();
        if summary.counters.frames_new == 0 {
            eprintln!("note: the station received no glove frames");
        }
        if let Some(error) = end.failure {
            return Err(error);
        }
        Ok(SessionEnd {
            interrupted: end.interrupted,
            complete,
        })
    }
}

/// Why the station's task ended while the console ran.
fn station_stopped(
    result: Result<Result<StationSummary, crate::station_node::NodeError>, tokio::task::JoinError>,
) -> anyhow::Error {
    match result {
        Ok(Ok(_)) => anyhow::anyhow!("the station stopped unexpectedly"),
        Ok(Err(e)) => anyhow::Error::new(e).context("the station stopped"),
        Err(e) => anyhow::Error::new(e).context("the station task failed"),
    }
}

fn send(tx: &mpsc::UnboundedSender<OperatorCommand>, command: OperatorCommand) {
    tx.send(command).ok();
}

/// A key in the full-screen console: typed into the prompt if one is open.
fn typed(prompt: &mut Option<(Prompt, String)>, key: Input) -> Option<Action> {
    let Some((kind, text)) = prompt.as_mut() else {
        return match key {
            Input::Char(c) => key_action(c),
            _ => None,
        };
    };
    match key {
        Input::Char(c) => {
            text.push(c);
            None
        }
        Input::Backspace => {
            text.pop();
            None
        }
        Input::Escape => {
            *prompt = None;
            None
        }
        Input::Enter => {
            let (kind, text) = (*kind, text.trim().to_string());
            *prompt = None;
            if text.is_empty() {
                return None;
            }
            match kind {
                Prompt::Note => Some(Action::Note(text)),
                // A value that is not a number becomes a progress mark the session refuses
                // with a message, so a typo is seen, not dropped.
                Prompt::Progress => Some(
                    parse_action(&format!("progress {text}"))
                        .unwrap_or(Action::Progress(Some(f64::NAN))),
                ),
            }
        }
        _ => None,
    }
}

/// Where the console writes each trial's review, in the session directory.
const REVIEW_DIR: &str = "review";

/// The session index appended to the report: every scored trial, worst first (lowest score,
/// or correctness without a baseline; then more feedback), with its feedback (count and
/// sentences) and a link to its review figure.
fn review_index(dir: &Path, scores: &[scoring::TrialScore]) -> String {
    let mut rows: Vec<(f64, usize, String)> = scores
        .iter()
        .map(|score| {
            let stem = Path::new(&score.file)
                .file_stem()
                .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
            let json = dir.join(REVIEW_DIR).join(format!("{stem}.review.json"));
            let said: Option<Vec<String>> = std::fs::read_to_string(&json)
                .ok()
                .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
                .and_then(|v| {
                    let list = v["feedback"].as_array()?;
                    Some(list.iter().filter_map(|f| f["text"].as_str()).map(str::to_string).collect())
                });
            let value = score.score.unwrap_or(score.correctness);
            let feedback = match &said {
                None => "no review".to_string(),
                Some(s) if s.is_empty() => "0".to_string(),
                Some(s) => format!("{}: {}", s.len(), s.join("; ")),
            };
            let row = format!(
                "| {stem} | {value:.3} | {feedback} | [figure](../{REVIEW_DIR}/{stem}.review.png) |\n"
            );
            (value, said.map_or(0, |s| s.len()), row)
        })
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
    let mut text = String::from(
        "\n## Trials, worst first\n\n| trial | score | feedback | review |\n|---|---|---|---|\n",
    );
    for (_, _, row) in rows {
        text.push_str(&row);
    }
    text
}

/// Scores the session's counted trials and writes the report into `DIR/report`.
fn write_session_report(
    dir: &Path,
    flow: &TrialFlow,
    inputs: &ScoringInputs,
) -> anyhow::Result<PathBuf> {
    let mut scores = Vec::new();
    let mut rejected = Vec::new();
    for trial in flow
        .manifest
        .trials
        .iter()
        .filter(|t| t.status == TrialStatus::Scored)
    {
        let path = dir.join(&trial.file);
        match inputs.score_file(&path) {
            Ok(score) => scores.push(score),
            Err(reason) => rejected.push(scoring::FileProblem {
                file: path.display().to_string(),
                reason: reason.to_string(),
            }),
        }
    }
    let index = review_index(dir, &scores);
    let mut report = inputs.report(scores, rejected, Vec::new());
    let out = dir.join("report");
    write_report_files(&out, &mut report)?;
    let markdown = out.join("report.md");
    let mut text = std::fs::read_to_string(&markdown)
        .with_context(|| format!("cannot read {}", markdown.display()))?;
    text.push_str(&index);
    write_atomically(&markdown, text.as_bytes())?;
    Ok(markdown)
}

/// The trial's review written into the session's `review/` directory, and what the console
/// says of it: its feedback sentences (none for a clean trial), or why it has no review.
fn review_lines(path: &Path, dir: &Path, config: &StationConfig) -> Vec<String> {
    let settings = review::FeedbackSettings::default();
    let out = dir.join(REVIEW_DIR);
    if let Err(e) = std::fs::create_dir_all(&out) {
        return vec![format!(
            "warning: no review: cannot create {}: {e}",
            out.display()
        )];
    }
    match review_trial_file_in_background(path, config, &settings, Some(&out)) {
        Ok(files) => files
            .review
            .feedback
            .iter()
            .map(|f| format!("  feedback: {}", f.text))
            .collect(),
        Err(e) => vec![format!("warning: no review: {e}")],
    }
}

/// What the simulated robot is for.
struct SimulatedRobot<'a> {
    config: &'a StationConfig,
    model: &'a HandModel,
    #[cfg_attr(not(feature = "physics"), allow(dead_code))] // read by the simulator only
    task: &'a TaskSpec,
}

/// The simulated robot's tasks and, with `--physics`, the console's link to it.
type SimulatedTasks = (
    Vec<JoinHandle<Result<(), crate::sim::SimError>>>,
    Option<PhysicsLink>,
);

/// `--simulate`: a simulated glove (its motion, or `glove_script`), and for a robot a mock
/// hand and a mock Franka, or with `--physics` the simulated robot in the task's scene, on the
/// station's loopback domain, until `shutdown`.
fn spawn_simulation(
    args: &TrialArgs,
    robot: &SimulatedRobot<'_>,
    clock: StationClock,
    shutdown: &watch::Receiver<bool>,
    glove_script: Option<GloveScript>,
) -> anyhow::Result<SimulatedTasks> {
    let config = robot.config;
    let mut tasks = Vec::new();
    let mut physics = None;
    let mut origin = GloveOrigin::FirstSubscriber;
    if args.physics {
        let (task, link, origin_rx) = spawn_physics(args, robot, clock, shutdown)?;
        tasks.push(task);
        physics = Some(link);
        origin = GloveOrigin::Shared(origin_rx);
    } else if config.drives_robot() {
        let mock = spawn_mock_robot(config, robot.model, clock, shutdown)?;
        tasks.extend([mock.hand, mock.arm]);
    }
    let motion = MotionKind::from(args.simulate_motion);
    let glove_config = SimGloveConfig {
        keypoints_topic: config.input.keypoints_topic.clone(),
        wrist_topic: config.input.wrist_topic.clone(),
        layout: config.retarget.layout,
        motion,
        period_s: motion.default_period_s(),
        hand_scale: simulated_hand_scale(args),
        seed: name_seed(&args.user),
        jitter_m: super::demo::glove_jitter_m(
            args.simulate_glove_jitter_mm,
            glove_script.is_some(),
        )?,
        script: glove_script,
        ..SimGloveConfig::default()
    };
    let glove = glove_config.glove()?;
    let network = config.network.clone();
    // On a thread of its own, as a real glove is a machine of its own (`device_thread`).
    let glove = spawn_device("simulated-glove", {
        let shutdown = shutdown.clone();
        async move {
            publish_glove(glove, &glove_config, network, clock, origin, shutdown).await?;
            Ok(())
        }
    })?;
    tasks.push(glove);
    Ok((tasks, physics))
}

/// `--physics`: the simulated robot in the session task's scene.
#[cfg(feature = "physics")]
fn spawn_physics(
    args: &TrialArgs,
    robot: &SimulatedRobot<'_>,
    clock: StationClock,
    shutdown: &watch::Receiver<bool>,
) -> anyhow::Result<PhysicsParts> {
    super::trial_physics::spawn_physics_robot(
        robot.config,
        robot.model,
        robot.task,
        args.scene.as_deref(),
        clock,
        shutdown,
    )
}

/// `--physics` in a build without the simulator.
#[cfg(not(feature = "physics"))]
fn spawn_physics(
    _args: &TrialArgs,
    _robot: &SimulatedRobot<'_>,
    _clock: StationClock,
    _shutdown: &watch::Receiver<bool>,
) -> anyhow::Result<PhysicsParts> {
    anyhow::bail!(
        "--physics: this pomdar was built without the simulator: run `bash sim/setup_mujoco.sh` once, then build with `--features physics`"
    )
}

/// The simulated hand's size: the flag, else 1 for a robot session, else one drawn from the
/// participant's name in [0.85, 1.15] (each simulated participant keeps their own hand).
fn simulated_hand_scale(args: &TrialArgs) -> f64 {
    match (args.simulate_hand_scale, args.human()) {
        (Some(scale), _) => scale,
        (None, false) => 1.0,
        (None, true) => 0.85 + 0.3 * (name_seed(&args.user) % 1000) as f64 / 999.0,
    }
}

/// A stable seed from a name (FNV-1a), so a simulated participant is the same every run.
fn name_seed(name: &str) -> u64 {
    name.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
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
