//! `pomdar sim`: the simulated robot — the hand and the arm's mount in a MuJoCo task scene,
//! on the real robot's topics — for a station (or `pomdar trial`) running elsewhere. Built
//! with the `physics` feature only; without it the command says how to get it.

use std::path::PathBuf;

use clap::Args;

use super::shared_args::{GuardArgs, NodeArgs};

/// The simulated robot in a MuJoCo task scene (needs the `physics` build).
///
/// The ORCA hand and the arm's mount in the task's scene, stepped in real time, on the real
/// robot's topics: follows hand and arm targets, publishes the hand's measured joint states,
/// the arm's pose, the task object's pose and the task's progress as the physics measures
/// it (/pomdar/sim/progress, JSON). The scene is the project's scaffold for --task or a
/// lab's own MJCF (--scene). Set-up: `bash sim/setup_mujoco.sh`, then build with
/// `--features physics` (README, "The simulated benchmark").
///
/// Example:
///   pomdar sim --task G4 --config launch_configs/station/eth_lab.toml
///   pomdar sim --task G4 --write-scene g4.xml
#[derive(Debug, Args)]
#[command(verbatim_doc_comment)]
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
    pub guard: GuardArgs,
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
    // The simulated robot is driven like the real one: guarded the same way.
    args.guard.apply();
    let request = crate::sim_runs::SimRequest {
        task: args.task,
        scene: args.scene,
        catalog: args.catalog,
        config: args.config,
        write_scene: args.write_scene,
        lockstep: args.lockstep,
        duration: args.duration,
        glove_jitter_mm: args.glove_jitter_mm,
        seed: args.seed,
        runs: args.runs,
        hand_mjcf: args.hand_mjcf,
        perturb_start: args.perturb_start,
        network: args.node.overrides(),
    };
    Ok(crate::sim_runs::run_sim(request).await?)
}
