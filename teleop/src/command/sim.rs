//! `pomdar sim`: the simulated robot — the hand and the arm's mount in a MuJoCo task scene,
//! on the real robot's topics — for a station (or `pomdar trial`) running elsewhere. Built
//! with the `physics` feature only; without it the command says how to get it.

use std::path::PathBuf;

use clap::Args;

use super::common::NodeArgs;

/// `pomdar sim` options.
#[derive(Debug, Args)]
pub struct SimArgs {
    /// The task (catalog id, e.g. G4): its scene, its arm constraint and how its progress counts.
    #[arg(long, default_value = "G4")]
    pub task: String,
    /// A lab's own task MJCF instead of the project's scaffold: its hand's joints and
    /// actuators named as the URDF's degrees of freedom, the hand under a mocap body named
    /// `pomdar_arm_mount`; the progress joint is the catalog entry's `physics.joint`.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// Task catalog (default: the built-in POMDAR catalog).
    #[arg(long, value_name = "FILE")]
    pub catalog: Option<PathBuf>,
    /// Station configuration whose topics, arm start pose and network the simulated robot uses,
    /// with its `simulated_hand_mjcf` and `[simulated_physics]` (contact, servo and mount
    /// settings of the project's scenes) (default: the built-in station defaults).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Write the project's scene for --task as MJCF to FILE and exit (open it in MuJoCo's
    /// viewer: `python -m mujoco.viewer --mjcf FILE`).
    #[arg(long, value_name = "FILE")]
    pub write_scene: Option<PathBuf>,
    /// Play this glove task script (launch_configs/sim/*.toml) through the station core into
    /// the scene in simulated time, without DDS, print the progress events and the
    /// correctness, and exit (deterministic: try a script or a scene change in seconds).
    #[arg(long, value_name = "FILE")]
    pub lockstep: Option<PathBuf>,
    /// Stop after this many seconds (default: run until Ctrl-C; with --lockstep the script's
    /// length plus 2 s).
    #[arg(long, value_name = "SECONDS")]
    pub duration: Option<f64>,
    /// With --lockstep: the glove's keypoint noise, standard deviation in mm, 0–50 (default
    /// 0.5: the noise of a hand at rest, as a simulated trial's glove has, so the script's still
    /// phases are not taken for a stalled glove).
    #[arg(long, requires = "lockstep", value_name = "MM")]
    pub glove_jitter_mm: Option<f64>,
    /// With --lockstep: the seed of the glove's noise (of the first run with --runs).
    #[arg(long, requires = "lockstep", default_value_t = 1)]
    pub seed: u64,
    /// With --lockstep: play the script this many times, 1–1000, with the seeds --seed,
    /// --seed + 1, …, and print one line per run, the success rate (correctness 1) and the
    /// spread of the successful runs' completion times.
    #[arg(long, requires = "lockstep", default_value_t = 1)]
    pub runs: u64,
    /// The lab's own MuJoCo model of the hand (the manufacturer's MJCF of ORCA v1, with its
    /// meshes beside it) instead of the hand the project writes from the URDF: its joints
    /// named as the URDF's degrees of freedom, MuJoCo's qpos = URDF angle + the joint's `ref`
    /// (README, "The simulated benchmark"). The project's scenes only. Default: the station
    /// configuration's `simulated_hand_mjcf`.
    #[arg(long, value_name = "FILE")]
    pub hand_mjcf: Option<PathBuf>,
    /// With --lockstep: move the task's start by each run's seed: the free object of a grasp
    /// task (the whole mechanism of the others) shifted by up to 5 mm along x and y and turned
    /// by up to 3° about the vertical; the project's scenes only.
    #[arg(long, requires = "lockstep")]
    pub perturb_start: bool,
    /// DDS settings.
    #[command(flatten)]
    pub node: NodeArgs,
    /// The RTPS datagram guard.
    #[command(flatten)]
    pub guard: super::common::GuardArgs,
}

/// `pomdar sim`.
#[cfg(not(feature = "physics"))]
pub async fn sim(_args: SimArgs) -> anyhow::Result<()> {
    anyhow::bail!(
        "this pomdar was built without the simulator: run `bash sim/setup_mujoco.sh` once, then \
         build with `cargo build --release --features physics` (README, \"The simulated benchmark\")"
    )
}

/// `pomdar sim`.
#[cfg(feature = "physics")]
pub async fn sim(args: SimArgs) -> anyhow::Result<()> {
    use std::sync::{Arc, Mutex};

    use anyhow::Context as _;

    use super::common::ctrl_c_shutdown;
    use crate::clock::StationClock;
    use crate::physics::robot_node::{
        PhysicsRobotConfig, PhysicsRobotReport, PhysicsRobotRun, run_physics_robot,
    };
    use crate::physics::setup::{ProjectScene, SceneSource, load_task, project_scene_xml};
    use crate::score::score_inputs::ScoringInputs;
    use crate::station_driver::setup::load_station_config;

    // The simulated robot is driven like the real one: guarded the same way.
    args.guard.apply();
    let inputs = ScoringInputs::load(args.catalog.as_deref(), None, None)?;
    let task = inputs.catalog.get(&args.task).cloned().with_context(|| {
        format!(
            "no task {} in the catalog (known: {})",
            args.task,
            inputs.catalog.ids()
        )
    })?;
    let station = load_station_config(args.config.as_deref(), None)?;
    let hand_file = args
        .hand_mjcf
        .as_deref()
        .or(station.simulated_hand_mjcf.as_deref());
    let arm_start = station.arm.start_pose_isometry()?;
    let model = retarget::HandModel::orca_v1_right();
    if let Some(path) = &args.write_scene {
        let scene = ProjectScene {
            hand_file,
            ..ProjectScene::for_station(&station)
        };
        let (xml, _) = project_scene_xml(&task, &model, arm_start, scene)?;
        crate::atomic_file::write_atomically(path, xml.as_bytes())
            .with_context(|| format!("cannot write {}", path.display()))?;
        println!("wrote the {} scene to {}", task.id, path.display());
        return Ok(());
    }
    if (args.perturb_start || hand_file.is_some()) && args.scene.is_some() {
        anyhow::bail!(
            "--perturb-start and --hand-mjcf change the project's scenes only: a lab's own --scene is loaded as written"
        );
    }
    let source = |seed: u64| match &args.scene {
        Some(path) => SceneSource::LabFile(path),
        None => SceneSource::Project(ProjectScene {
            start: start_move(args.perturb_start, seed),
            hand_file,
            physics: &station.simulated_physics,
        }),
    };
    if let Some(script) = &args.lockstep {
        let load = |seed: u64| load_task(&task, &model, source(seed), arm_start);
        return lockstep(&station, &model, &load, script, &args);
    }
    let loaded = load_task(&task, &model, source(args.seed), arm_start)?;
    let config = PhysicsRobotConfig::for_station(&station, &loaded, arm_start);
    let report = Arc::new(Mutex::new(PhysicsRobotReport::default()));
    let (_control, control_rx) = tokio::sync::mpsc::channel(4);
    let shutdown = match args.duration {
        Some(s) => timed_shutdown(s),
        None => ctrl_c_shutdown(),
    };
    eprintln!(
        "pomdar sim: task {} ({}), {} scene; hand targets on {}, arm targets on {}, progress on {}",
        task.id,
        task.name,
        args.scene
            .as_ref()
            .map_or("the project's".to_string(), |p| p.display().to_string()),
        config.hand_targets_topic,
        config.arm_target_topic,
        config.progress_topic
    );
    let run = PhysicsRobotRun {
        model,
        engine: loaded.engine,
        network: args.node.network(&station.network),
        clock: StationClock::new(),
        report: report.clone(),
        control: control_rx,
        events: None,
        shutdown,
        options: Default::default(),
    };
    run_physics_robot(config, run).await?;
    if let Ok(r) = report.lock() {
        eprintln!("{}", summary_line(&r));
    }
    Ok(())
}

/// The run in one line: time simulated, real-time factor, targets, progress.
#[cfg(feature = "physics")]
fn summary_line(r: &crate::physics::robot_node::PhysicsRobotReport) -> String {
    let factor = if r.step_wall_s > 0.0 {
        r.sim_time_s / r.step_wall_s
    } else {
        0.0
    };
    format!(
        "simulated {:.1} s ({factor:.1}× real time while stepping, {:.2} s behind); {} hand and {} arm targets; progress {} ({} events)",
        r.sim_time_s,
        r.behind_s,
        r.hand_targets,
        r.arm_targets,
        r.progress_total,
        r.events.len()
    )
}

/// A shutdown signal that turns true after `seconds` or on Ctrl-C.
#[cfg(feature = "physics")]
fn timed_shutdown(seconds: f64) -> tokio::sync::watch::Receiver<bool> {
    let (tx, rx) = tokio::sync::watch::channel(false);
    let mut ctrl_c = super::common::ctrl_c_shutdown();
    tokio::spawn(async move {
        let wait = std::time::Duration::from_secs_f64(seconds.max(0.0));
        tokio::select! {
            _ = tokio::time::sleep(wait) => {}
            _ = ctrl_c.changed() => {}
        }
        tx.send(true).ok();
    });
    rx
}

/// One lock-step run: the task, what happened, and its correctness.
#[cfg(feature = "physics")]
struct LockstepRun {
    task: scoring::TaskSpec,
    outcome: crate::physics::lockstep::LockstepOutcome,
    correctness: f64,
}

/// `--lockstep`: the script through the station core into the scene, in simulated time, once
/// or `--runs` times over consecutive seeds.
#[cfg(feature = "physics")]
fn lockstep(
    station: &station::StationConfig,
    model: &retarget::HandModel,
    load: &dyn Fn(
        u64,
    ) -> Result<
        crate::physics::setup::SimulatedTask,
        crate::physics::error::PhysicsError,
    >,
    script: &std::path::Path,
    args: &SimArgs,
) -> anyhow::Result<()> {
    use crate::sim::glove_script_file::load_glove_script;
    if !(1..=1000).contains(&args.runs) {
        anyhow::bail!("--runs {} must be in [1, 1000]", args.runs);
    }
    let script = load_glove_script(script)?;
    let jitter_m = super::demo::glove_jitter_m(args.glove_jitter_mm, true)?;
    if args.runs == 1 {
        let run = lockstep_run(
            station,
            model,
            load(args.seed)?,
            &script,
            (jitter_m, args.seed),
            args,
        )?;
        print_run(&run);
        return Ok(());
    }
    let mut completions = Vec::new();
    for seed in (0..args.runs).map(|k| args.seed.wrapping_add(k)) {
        let run = lockstep_run(station, model, load(seed)?, &script, (jitter_m, seed), args)?;
        let completion = (run.correctness >= 1.0)
            .then(|| run.outcome.events.last().map(|e| e.sim_time_s))
            .flatten();
        println!(
            "seed {seed}: correctness {:.3}, progress {} {}{}{}",
            run.correctness,
            run.outcome.progress,
            run.task.correctness.progress_unit(),
            completion.map_or(String::new(), |t| format!(", done at {t:.2} s")),
            start_note(args.perturb_start, seed)
        );
        completions.push(completion);
    }
    print_spread(&completions, args, jitter_m);
    Ok(())
}

/// The script played once at `seed` with `jitter_m` of glove noise, scored.
#[cfg(feature = "physics")]
fn lockstep_run(
    station: &station::StationConfig,
    model: &retarget::HandModel,
    loaded: crate::physics::setup::SimulatedTask,
    script: &retarget::human_hand::GloveScript,
    (jitter_m, seed): (f64, u64),
    args: &SimArgs,
) -> anyhow::Result<LockstepRun> {
    use crate::physics::lockstep::run_lockstep;
    use crate::sim::sim_glove_node::SimGloveConfig;
    let task = loaded.task.clone();
    let glove_config = SimGloveConfig {
        script: Some(script.clone()),
        jitter_m,
        seed,
        layout: station.retarget.layout,
        ..SimGloveConfig::default()
    };
    let duration_s = args.duration.unwrap_or(script.duration_s() + 2.0);
    let glove = glove_config.glove()?;
    let mut config = station.clone();
    config.arm.constraint = task.arm;
    let outcome = run_lockstep(
        &config,
        model,
        &glove,
        loaded,
        glove_config.rate_hz,
        duration_s,
    )?;
    let correctness = crate::demo::robot::physics_correctness(&task, &outcome.events)
        .map_err(|e| anyhow::anyhow!("the physics' marks do not score: {e}"))?;
    Ok(LockstepRun {
        task,
        outcome,
        correctness,
    })
}

/// A single run: its events and a summary line.
#[cfg(feature = "physics")]
fn print_run(run: &LockstepRun) {
    let (task, outcome) = (&run.task, &run.outcome);
    for event in &outcome.events {
        let value = event.value.map_or(String::new(), |v| format!(" {v}"));
        println!(
            "{:>7.2} s  {}{value} {}",
            event.sim_time_s, event.event, event.unit
        );
    }
    println!(
        "{} ({}): progress {} {}, correctness {:.3} over {:.1} simulated s ({} hand commands, {} arm targets)",
        task.id,
        task.name,
        outcome.progress,
        task.correctness.progress_unit(),
        run.correctness,
        outcome.sim_time_s,
        outcome.hand_commands,
        outcome.arm_targets
    );
}

/// Several runs: how many scored correctness 1, and when the successful ones were done.
#[cfg(feature = "physics")]
fn print_spread(completions: &[Option<f64>], args: &SimArgs, jitter_m: f64) {
    let mut done: Vec<f64> = completions.iter().flatten().copied().collect();
    done.sort_by(f64::total_cmp);
    let spread = match (done.first(), done.last()) {
        (Some(min), Some(max)) => format!(
            "; done at {min:.2} / {:.2} / {max:.2} s (min / median / max)",
            done[done.len() / 2]
        ),
        _ => String::new(),
    };
    let starts = if args.perturb_start {
        ", starts moved up to 5 mm and 3°"
    } else {
        ""
    };
    println!(
        "correctness 1 in {} of {} runs (seeds {}–{}, glove noise {:.1} mm{starts}){spread}",
        done.len(),
        completions.len(),
        args.seed,
        args.seed.wrapping_add(args.runs - 1),
        jitter_m * 1e3
    );
}

/// The move of a run's start: drawn from its seed with `--perturb-start`, else none.
#[cfg(feature = "physics")]
fn start_move(perturb: bool, seed: u64) -> simulation::scene::StartPerturbation {
    use simulation::scene::StartPerturbation;
    if perturb {
        StartPerturbation::from_seed(seed)
    } else {
        StartPerturbation::NONE
    }
}

/// `" (start +1.2, −4.0 mm, +0.8°)"` for a moved start, else nothing.
#[cfg(feature = "physics")]
fn start_note(perturb: bool, seed: u64) -> String {
    if !perturb {
        return String::new();
    }
    let start = start_move(true, seed);
    format!(
        " (start {:+.1}, {:+.1} mm, {:+.1}°)",
        start.offset_m[0] * 1e3,
        start.offset_m[1] * 1e3,
        start.yaw_rad.to_degrees()
    )
}
