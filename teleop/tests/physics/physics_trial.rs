//! The whole simulated benchmark in one command, over loopback DDS: `pomdar trial --simulate
//! --physics` on G4 (small cylinder) with the simulated glove playing a task script. The
//! station retargets it, the simulated hand lifts and relocates the cylinder, the physics marks
//! the progress, and the trial is scored: correctness 1 for the scripted grasp, 0 for the
//! scripted miss. The same scripts in lock step (no DDS, simulated time) give the same.
//! (`physics` feature.)

use std::path::{Path, PathBuf};
use std::process::Command;

use retarget::HandModel;
use scoring::TaskCatalog;
use teleop::physics::lockstep::run_lockstep;
use teleop::physics::setup::{SceneSource, load_task};
use teleop::ros::domain_lease::{TEST_DOMAINS, lease_domain};
use teleop::score::score_inputs::ScoringInputs;
use teleop::sim::glove_script_file::load_glove_script;
use teleop::sim::sim_glove_node::SimGloveConfig;

const BASELINE_G4_S: f64 = 8.0;

fn shipped(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../launch_configs/sim")
        .join(name)
}

/// One recorded G4 trial with the glove playing `script`; its scored log.
fn simulated_trial(root: &Path, script: &str) -> scoring::TrialScore {
    std::fs::create_dir_all(root).unwrap();
    // The console script the README's simulated trial uses.
    let console = shipped("one_trial.script");
    let baseline = root.join("baseline.toml");
    std::fs::write(&baseline, format!("[baseline]\nexample = false\nsource = \"physics_trial test\"\n\n[[task]]\nid = \"G4\"\nmean_s = {BASELINE_G4_S}\nn = 3\n")).unwrap();
    let out = root.join("sessions");
    let output = Command::new(env!("CARGO_BIN_EXE_pomdar"))
        .args([
            "trial",
            "--task",
            "G4",
            "--user",
            "sim",
            "--operator",
            "ci",
            "--practice",
            "0",
            "--trials",
            "1",
        ])
        .args(["--simulate", "--physics", "--simulate-glove-script"])
        .arg(shipped(script))
        .args([
            "--domain-id",
            &lease_domain(TEST_DOMAINS).unwrap().to_string(),
            "--countdown",
            "0.5",
            "--script",
        ])
        .arg(&console)
        .arg("--baseline")
        .arg(&baseline)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    eprintln!("--- pomdar trial ({script}) stderr:\n{stderr}");
    assert!(output.status.success(), "pomdar trial failed");
    let log = out.join("sim/orca_full/G4/G4-t01.mcap");
    let inputs = ScoringInputs::load(None, None, Some(&baseline)).unwrap();
    inputs.score_file(&log).unwrap()
}

#[test]
fn a_scripted_grasp_of_g4_is_scored_one_by_the_physics_and_a_miss_zero() {
    let root = std::env::temp_dir().join(format!("pomdar-physics-trial-{}", std::process::id()));
    std::fs::remove_dir_all(&root).ok();
    let grasp = simulated_trial(&root.join("grasp"), "grasp_place.toml");
    assert_eq!(grasp.correctness, 1.0, "{grasp:?}");
    assert!(grasp.score.is_some_and(|s| s > 0.8), "{grasp:?}");
    let miss = simulated_trial(&root.join("miss"), "grasp_miss.toml");
    assert_eq!(miss.correctness, 0.0, "{miss:?}");
    std::fs::remove_dir_all(&root).ok();
}

/// The shipped scripts in lock step: the grasp relocates the cylinder (0.5 then 1), the miss
/// leaves it (no event).
#[test]
fn the_scripts_in_lock_step_give_the_same_levels() {
    let model = HandModel::orca_v1_right();
    let mut config = station::StationConfig::default();
    config.arm.constraint = station::arm::Constraint::Free;
    let start = config.arm.start_pose_isometry().unwrap();
    let task = TaskCatalog::builtin().get("G4").unwrap().clone();
    for (script, expected) in [
        ("grasp_place.toml", vec![0.5, 1.0]),
        ("grasp_miss.toml", vec![]),
    ] {
        // With the noise of a hand at rest, as `pomdar trial --simulate-glove-script` plays
        // a script: noise-free still phases are identical frames, which the station takes for
        // a stalled glove (and disengages after 500 ms). Seeded and keyed by the lock step's
        // time, so the run is still the same every time.
        let glove = SimGloveConfig {
            script: Some(load_glove_script(&shipped(script)).unwrap()),
            jitter_m: teleop::sim::sim_glove_node::REST_JITTER_M,
            ..SimGloveConfig::default()
        }
        .glove()
        .unwrap();
        let loaded = load_task(&task, &model, SceneSource::Project, start).unwrap();
        let outcome = run_lockstep(&config, &model, &glove, loaded, 100.0, 12.0).unwrap();
        let levels: Vec<f64> = outcome.events.iter().filter_map(|e| e.value).collect();
        assert_eq!(levels, expected, "{script}: {:?}", outcome.events);
        assert!(
            outcome.hand_commands > 500 && outcome.arm_targets > 100,
            "{outcome:?}"
        );
    }
}
