//! Both simulated hands against the URDF: the hand the project writes from its model and the
//! manufacturer's MJCF (with `qpos` = URDF angle + `ref`), loaded in the G4 scene through the
//! engine the twin uses, set to 50 random configurations within the URDF's limits (in URDF
//! angles), every body named as a URDF link posed as an independent implementation, the `k`
//! crate reading `../shared/reference/orcahand_v1_right.urdf`, poses it. Skipped with a message
//! where `../shared/reference/` is absent (`.ci/run` requires it).

use std::collections::HashMap;
use std::path::PathBuf;

use k::Chain;
use nalgebra::Isometry3;
use retarget::HandModel;
use retarget::human_hand::SplitMix64;
use teleop::physics::setup::{ProjectScene, SceneSource, load_task};
use teleop::score::score_inputs::ScoringInputs;

const TOLERANCE_M: f64 = 1e-9;
const CONFIGURATIONS: usize = 50;

fn reference_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/reference"
    ));
    if dir.is_dir() {
        Some(dir)
    } else {
        println!(
            "SKIPPED: reference data directory {} is absent",
            dir.display()
        );
        None
    }
}

fn random_configuration(model: &HandModel, rng: &mut SplitMix64) -> Vec<f64> {
    model
        .limits()
        .map(|l| l.lower_rad + rng.next_f64() * (l.upper_rad - l.lower_rad))
        .collect()
}

/// The largest distance (m) and angle (rad) between MuJoCo's body frames and `k`'s link
/// frames, both relative to the hand's root, over the configurations; with the worst body.
fn worst_frame_error(
    hand_file: Option<&std::path::Path>,
    chain: &Chain<f64>,
) -> (f64, f64, String) {
    let model = HandModel::orca_v1_right();
    let inputs = ScoringInputs::load(None, None, None).unwrap();
    let task = inputs.catalog.get("G4").unwrap().clone();
    let scene = ProjectScene {
        hand_file,
        ..ProjectScene::default()
    };
    let mut loaded = load_task(
        &task,
        &model,
        SceneSource::Project(scene),
        Isometry3::identity(),
    )
    .unwrap();
    let root = if hand_file.is_some() {
        simulation::lab_hand::LAB_HAND_ROOT.to_string()
    } else {
        simulation::hand_mjcf::hand_mjcf(&model, &Default::default()).root_body
    };
    let links: Vec<String> = model
        .ros_link_names()
        .iter()
        // MuJoCo's own world body is not the URDF's root link `world`.
        .filter(|name| *name != "world" && loaded.engine.body_pose(name).is_some())
        .cloned()
        .collect();
    assert!(links.len() >= 17, "{links:?}");
    let mut rng = SplitMix64::new(20261129);
    let mut worst = (0.0_f64, 0.0_f64, String::new());
    for _ in 0..CONFIGURATIONS {
        let q = random_configuration(&model, &mut rng);
        loaded.engine.set_hand_positions(&q).unwrap();
        let by_name: HashMap<&str, f64> = model
            .ros_dof_names()
            .iter()
            .map(String::as_str)
            .zip(q.iter().copied())
            .collect();
        let positions: Vec<f64> = chain
            .iter_joints()
            .map(|j| by_name[j.name.as_str()])
            .collect();
        chain.set_joint_positions(&positions).unwrap();
        chain.update_transforms();
        let root_pose = loaded.engine.body_pose(&root).unwrap();
        for link in &links {
            let ours = root_pose.inverse() * loaded.engine.body_pose(link).unwrap();
            let node = chain
                .find_link(link)
                .unwrap_or_else(|| panic!("{link} not in the URDF"));
            let k_pose = node.world_transform().unwrap();
            let t = k_pose.translation.vector;
            let r = k_pose.rotation;
            let theirs = Isometry3::from_parts(
                nalgebra::Translation3::new(t.x, t.y, t.z),
                nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                    r.w, r.i, r.j, r.k,
                )),
            );
            let distance = (ours.translation.vector - theirs.translation.vector).norm();
            let angle = ours.rotation.angle_to(&theirs.rotation);
            if distance > worst.0 {
                worst = (distance, worst.1, link.clone());
            }
            worst.1 = worst.1.max(angle);
        }
    }
    worst
}

#[test]
fn both_simulated_hands_pose_every_link_as_the_urdf_at_random_configurations() {
    let Some(dir) = reference_dir() else {
        return;
    };
    let chain = Chain::<f64>::from_urdf_file(dir.join("orcahand_v1_right.urdf")).unwrap();
    let manufacturer = dir.join("orcahand_v1_mjcf/orcahand_right.mjcf");
    for (name, file) in [
        ("project's hand", None),
        ("manufacturer's MJCF", Some(manufacturer.as_path())),
    ] {
        let (distance, angle, link) = worst_frame_error(file, &chain);
        println!(
            "{name}: {CONFIGURATIONS} configurations, worst {distance:.2e} m (at {link}), {angle:.2e} rad"
        );
        assert!(distance <= TOLERANCE_M, "{name}: {distance} m at {link}");
        assert!(angle <= 1e-8, "{name}: {angle} rad");
    }
}
