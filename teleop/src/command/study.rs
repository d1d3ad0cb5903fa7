//! `pomdar study`: the human study's plan. One participant does each task of the plan in
//! order with their own hand, wearing the glove; each task is a `pomdar trial --embodiment
//! human` session (no robot, no retargeting, the glove's keypoints and wrist recorded with the
//! trial timing and events, one MCAP per trial, a manifest per task). A study resumes: tasks
//! already complete are skipped, the interrupted one resumes at its next trial.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;

use super::shared_args::{ConsoleArgs, GuardArgs, MotionArg, NodeArgs};
use crate::console::manifest::{MANIFEST_FILE, Manifest, ManifestFile};
use crate::console::session_dir::check_name;
use crate::console::session_options::HUMAN_PROTOCOL;
use crate::console::view::instruction;
use crate::console::{SessionOptions, SimulationOptions, run_session};
use crate::score::score_inputs::ScoringFileArgs;
use crate::tui::terminal_shell::EXIT_INTERRUPTED;

/// The human study: a participant does each task of a plan with their own hand.
///
/// The baseline a robot's speed is scored against comes from people: in the POMDAR study
/// each participant does every task 3 times with their right hand, wearing the glove.
/// For each task in --tasks, in order, this runs the trial console as `pomdar trial
/// --embodiment human` would: the task's instruction and where the participant is in the
/// plan are shown; no robot, no retargeting; the glove's keypoints and wrist pose are
/// recorded with the trial's timing and events (one MCAP per trial, embodiment "human",
/// the participant as the user) in <out>/<participant>/human/<task>; a trial starts once
/// the glove is fresh and fast enough (space, or `start` in a script). Defaults: no
/// practice, 3 trials per task. Run the same command again to resume: complete tasks are
/// skipped, the interrupted one resumes at its next trial. Then `pomdar baseline` makes
/// the baseline table and `pomdar study-report` checks the participants' strategies.
/// Exit status: 0 study complete, 130 stopped (Ctrl-C, SIGTERM, q) before the end, 1 on
/// an error.
///
/// Examples:
///   pomdar study --participant p01 --operator bob --tasks V1,H2,C1,G2
///   pomdar study --participant sim1 --operator me --tasks V1,C1,G2 --simulate --simulate-motion open-close,pinches,abduction
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
pub struct StudyArgs {
    /// The participant (names the session directories and goes into every log as the user).
    #[arg(long, value_name = "NAME")]
    pub participant: String,
    /// The experimenter running the study.
    #[arg(long, value_name = "NAME")]
    pub operator: String,
    /// The tasks, in the order the participant does them (catalog IDs, comma-separated).
    #[arg(long, value_name = "ID,ID,…", value_delimiter = ',', required = true)]
    pub tasks: Vec<String>,
    /// Recorded trials per task (the POMDAR study: 3).
    #[arg(long, value_name = "N", default_value_t = HUMAN_PROTOCOL.1, value_parser = clap::value_parser!(u32).range(1..=200))]
    pub trials: u32,
    /// Practice trials per task before the recorded ones (the POMDAR study: none).
    #[arg(long, value_name = "N", default_value_t = HUMAN_PROTOCOL.0, value_parser = clap::value_parser!(u32).range(0..=50))]
    pub practice: u32,
    /// Sessions directory; each task's session is <DIR>/<participant>/human/<task>.
    #[arg(long, value_name = "DIR", default_value = "sessions")]
    pub out: PathBuf,
    /// Station configuration (default: the built-in ETH lab preset): its glove input
    /// (topics, layout, network) is used; nothing is retargeted.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// The catalog (the tasks' instructions) and rules; a baseline, if given, shows each
    /// trial's speed against it.
    #[command(flatten)]
    pub scoring: ScoringFileArgs,
    /// The countdown, the start gate, the script (played once for each task) and the display.
    #[command(flatten)]
    pub console: ConsoleArgs,
    /// Run a simulated glove in this process, on loopback: a rehearsal, or the study's test.
    #[arg(long)]
    pub simulate: bool,
    /// With --simulate: the glove's motion for each task, in the order of --tasks (the last
    /// one repeats for the tasks after it).
    #[arg(
        long,
        value_enum,
        value_name = "KIND,…",
        value_delimiter = ',',
        default_value = "task-like"
    )]
    pub simulate_motion: Vec<MotionArg>,
    /// With --simulate: the hand's size (default: one drawn from the participant's name).
    #[arg(long, value_name = "SCALE")]
    pub simulate_hand_scale: Option<f64>,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
    /// The RTPS datagram guard.
    #[command(flatten)]
    pub guard: GuardArgs,
}

impl StudyArgs {
    /// The `pomdar trial` session of the plan's task number `index`.
    fn task_session(&self, index: usize) -> SessionOptions {
        let motion = self
            .simulate_motion
            .get(index)
            .or(self.simulate_motion.last())
            .copied()
            .unwrap_or(MotionArg::TaskLike);
        SessionOptions {
            task: self.tasks[index].clone(),
            embodiment: station::HUMAN_EMBODIMENT.to_string(),
            user: self.participant.clone(),
            operator: self.operator.clone(),
            trials: Some(self.trials),
            practice: Some(self.practice),
            out: self.out.clone(),
            config: self.config.clone(),
            profile: None,
            scoring: self.scoring.clone(),
            console: self.console.settings(),
            network: self.node.overrides(),
            simulation: self.simulate.then(|| SimulationOptions {
                motion: motion.into(),
                // A study's glove is a participant's: it plays motions, not task scripts.
                glove_script: None,
                physics: false,
                scene: None,
                glove_jitter_mm: None,
            }),
            simulated_hand_scale: self.simulate_hand_scale,
            // The human study drives no robot: nothing to view.
            view: None,
        }
    }

    /// A task's session directory.
    fn task_dir(&self, task: &str) -> PathBuf {
        self.out
            .join(&self.participant)
            .join(station::HUMAN_EMBODIMENT)
            .join(task)
    }
}

/// Whether the session in `dir` has done every trial of this plan.
fn task_complete(dir: &Path, practice: u32, trials: u32) -> anyhow::Result<bool> {
    let path = dir.join(MANIFEST_FILE);
    if !path.exists() {
        return Ok(false);
    }
    let manifest = Manifest::load(&path)?;
    Ok(manifest.done(true) >= practice && manifest.done(false) >= trials)
}

/// Checks the plan before anything runs: the names, every task in the catalog, none twice.
fn check_plan(args: &StudyArgs) -> anyhow::Result<()> {
    check_name("--participant", &args.participant)?;
    check_name("--operator", &args.operator)?;
    let inputs = args.scoring.load()?;
    for (i, task) in args.tasks.iter().enumerate() {
        if inputs.catalog.get(task).is_none() {
            anyhow::bail!(
                "--tasks: {task:?} is not in the {} ({})",
                inputs.catalog.origin,
                inputs.catalog.ids()
            );
        }
        if args.tasks[..i].contains(task) {
            anyhow::bail!("--tasks: {task} is listed twice (each task is one session)");
        }
    }
    Ok(())
}

/// `pomdar study`.
pub async fn study(args: StudyArgs) -> anyhow::Result<ExitCode> {
    check_plan(&args)?;
    // Its consoles run the station: crafted DATA_FRAG datagrams must not exhaust their memory.
    args.guard.apply();
    let catalog = args.scoring.load()?.catalog;
    let count = args.tasks.len();
    for (index, task) in args.tasks.iter().enumerate() {
        let spec = catalog.get(task).cloned();
        let what = spec
            .as_ref()
            .map(|t| instruction(t, false))
            .unwrap_or_default();
        let step = format!("task {} of {count}: {task}", index + 1);
        if task_complete(&args.task_dir(task), args.practice, args.trials)? {
            eprintln!("study {}: {step} is complete: skipped", args.participant);
            continue;
        }
        eprintln!("study {}: {step} — {what}", args.participant);
        let plan = (
            "study".to_string(),
            format!("{step} (plan: {})", args.tasks.join(", ")),
        );
        let end = run_session(&args.task_session(index), vec![plan]).await?;
        if end.interrupted || !end.complete {
            eprintln!(
                "study {}: stopped at {step}; run the same command again to resume",
                args.participant
            );
            return Ok(ExitCode::from(EXIT_INTERRUPTED));
        }
    }
    println!(
        "study {}: all {count} tasks complete in {}; next: pomdar baseline {} --out FILE, pomdar study-report {} --out DIR",
        args.participant,
        args.out.join(&args.participant).display(),
        args.out.display(),
        args.out.display()
    );
    Ok(ExitCode::SUCCESS)
}
