//! The simulated robot's physics against the wall clock, per task scene: the ORCA hand (the
//! built-in model) moving through its whole range (every joint on its own sine between its
//! limits, period 2 s, the mount swaying 5 cm) for 10 simulated seconds in each of the 18
//! project scenes, stepped as the `pomdar sim` node steps it (5 ms advances of 2 ms MuJoCo
//! steps). Prints the real-time factor (simulated seconds per wall second) of each scene and
//! the slowest. `cargo bench -p teleop --features physics --bench physics_realtime`
//! (after `bash sim/setup_mujoco.sh`); `-- --hand-mjcf FILE` runs the lab's MJCF of the hand
//! (the manufacturer's, with its meshes) instead.

#![allow(clippy::expect_used)] // a benchmark stops on a broken set-up

use std::time::Instant;

use nalgebra::{Isometry3, Translation3};
use retarget::HandModel;
use scoring::TaskCatalog;
use teleop::physics::setup::{ProjectScene, SceneSource, load_task};

const SIMULATED_S: f64 = 10.0;
const TICK_S: f64 = 0.005;

fn main() {
    let model = HandModel::orca_v1_right();
    let limits: Vec<_> = model.limits().collect();
    let start = station::StationConfig::default()
        .arm
        .start_pose_isometry()
        .expect("the default start pose");
    let catalog = TaskCatalog::builtin();
    let args: Vec<String> = std::env::args().collect();
    let hand_file = args
        .iter()
        .position(|a| a == "--hand-mjcf")
        .and_then(|i| args.get(i + 1))
        .map(std::path::PathBuf::from);
    let scene = ProjectScene {
        hand_file: hand_file.as_deref(),
        ..ProjectScene::default()
    };
    let mut slowest = f64::INFINITY;
    println!(
        "physics real-time factor, {SIMULATED_S} s per scene, hand in motion ({}):",
        hand_file
            .as_ref()
            .map_or("the project's hand".to_string(), |f| f
                .display()
                .to_string())
    );
    for task in &catalog.tasks {
        let mut loaded = load_task(task, &model, SceneSource::Project(scene), start)
            .expect("the project's scene");
        let steps = (SIMULATED_S / TICK_S) as usize;
        let began = Instant::now();
        for k in 0..steps {
            let t = k as f64 * TICK_S;
            let targets: Vec<f64> = limits
                .iter()
                .enumerate()
                .map(|(i, l)| {
                    let phase = 0.5 + 0.5 * (std::f64::consts::TAU * (t / 2.0) + i as f64).sin();
                    l.lower_rad + phase * (l.upper_rad - l.lower_rad)
                })
                .collect();
            loaded.engine.set_hand_targets(&targets).expect("targets");
            let sway = 0.05 * (std::f64::consts::TAU * t / 4.0).sin();
            let mount = Isometry3::from_parts(
                Translation3::from(
                    start.translation.vector + nalgebra::Vector3::new(0.0, sway, 0.0),
                ),
                start.rotation,
            );
            loaded.engine.set_mount_pose(&mount);
            loaded.engine.advance(TICK_S);
        }
        let factor = SIMULATED_S / began.elapsed().as_secs_f64();
        slowest = slowest.min(factor);
        println!(
            "  {:<3} {:<16} {factor:>6.1}× real time",
            task.id, task.name
        );
    }
    println!("slowest scene: {slowest:.1}× real time (≥ 1 needed)");
}
