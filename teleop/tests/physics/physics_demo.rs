//! The whole chain in simulation over loopback DDS: simulated glove → station → the simulated
//! robot in a MuJoCo task scene. The hand follows the station's commands in free space; a
//! scripted grasp of G4 is measured by the physics as relocated, a scripted miss as not
//! lifted. (`physics` feature.)

use retarget::human_hand::MotionKind;
use scoring::TaskCatalog;
use station::StationConfig;
use teleop::demo::PhysicsTask;
use teleop::demo::{DemoOptions, DemoOutcome, run_demo};
use teleop::ros::domain_lease::{TEST_DOMAINS, lease_domain};
use teleop::stand_ins::sim_glove_node::SimGloveConfig;

async fn physics_demo(task: &str, glove: SimGloveConfig, duration_s: f64) -> DemoOutcome {
    let task = TaskCatalog::builtin().get(task).unwrap().clone();
    run_demo(DemoOptions {
        duration_s,
        domain_id: lease_domain(TEST_DOMAINS).unwrap(),
        station: StationConfig::default(),
        glove,
        live: false,
        out: None,
        tap: None,
        physics: Some(PhysicsTask {
            task,
            scene: None,
            record_states: true,
        }),
    })
    .await
    .unwrap()
}

/// The 95th percentile of `values`.
fn p95(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[((values.len() as f64 * 0.95) as usize).min(values.len() - 1)]
}

/// The demo's default glove motion (grasp, release, pinches) away from every object. (A full
/// fist, `OpenClose`, drives the retargeted digits into one another: the contacts between the
/// digits hold some joints up to 0.1 rad short of their targets, as they would the real hand.)
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_simulated_hand_tracks_the_station_in_free_space() {
    let glove = SimGloveConfig {
        motion: MotionKind::TaskLike,
        period_s: MotionKind::TaskLike.default_period_s(),
        ..SimGloveConfig::default()
    };
    let outcome = physics_demo("G4", glove, 6.0).await;
    let physics = outcome.physics.expect("physics outcome");
    assert!(
        physics.hand_targets > 200,
        "{} hand targets",
        physics.hand_targets
    );
    // Once settled: from 1 s on, every joint's measured angle against the target in force.
    let errors: Vec<f64> = physics.states[100..]
        .iter()
        .flat_map(|(measured, target)| measured.iter().zip(target).map(|(m, t)| (m - t).abs()))
        .collect();
    let p95 = p95(errors.clone());
    let max = errors.iter().copied().fold(0.0, f64::max);
    eprintln!(
        "tracking error over {} samples: p95 {p95:.4} rad, max {max:.4} rad",
        errors.len()
    );
    assert!(p95 <= 0.05, "tracking error p95 {p95} rad");
}
