//! Forward kinematics cross-check of the project's built-in ORCA v1 model (and of its URDF
//! importer) against an independent implementation: the `k` crate (openrr, v0.32) reading
//! `../shared/reference/orcahand_v1_right.urdf` with its own URDF-to-tree conversion and its
//! own transform chain.

use crate::common;

use std::collections::HashMap;

use k::Chain;
use rand::{SeedableRng, rngs::StdRng};
use retarget::{FrameSpec, HandModel, JointMotion, UrdfImport};

const URDF: &str = "orcahand_v1_right.urdf";
const TOLERANCE_M: f64 = 1e-6;
const POSES: usize = 1000;

fn reference_chain(test: &str) -> Option<(Chain<f64>, String)> {
    let path = common::reference_file(test, URDF)?;
    let text = std::fs::read_to_string(&path).unwrap();
    Some((Chain::from_urdf_file(&path).unwrap(), text))
}

/// Seeded random joint vectors within the built-in model's limits, limits included.
fn random_poses(model: &HandModel, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut poses: Vec<Vec<f64>> = (0..POSES - 2)
        .map(|_| common::poses::random_pose(model, &mut rng))
        .collect();
    poses.push(model.limits().map(|l| l.lower_rad).collect());
    poses.push(model.limits().map(|l| l.upper_rad).collect());
    poses
}

/// Set `k`'s joints from our joint vector, by name (`right_` + orca_core name).
fn set_reference(chain: &Chain<f64>, model: &HandModel, q: &[f64]) {
    let by_name: HashMap<String, f64> = model
        .dof_names()
        .zip(q)
        .map(|(n, v)| (format!("right_{n}"), *v))
        .collect();
    let positions: Vec<f64> = chain
        .iter_joints()
        .map(|j| by_name[j.name.as_str()])
        .collect();
    chain.set_joint_positions(&positions).unwrap();
    chain.update_transforms();
}

fn reference_position(chain: &Chain<f64>, joint: &str) -> [f64; 3] {
    let node = chain
        .find(joint)
        .unwrap_or_else(|| panic!("{joint} not in URDF"));
    let t = node.world_transform().unwrap().translation.vector;
    [t.x, t.y, t.z]
}

#[test]
fn builtin_orca_matches_k_on_the_reference_urdf_at_1000_random_poses() {
    let Some((chain, _)) = reference_chain("fk_crosscheck::builtin") else {
        return;
    };
    let model = HandModel::orca_v1_right();
    assert_eq!(chain.dof(), model.dof());

    // Compared frames: every revolute joint frame (child link origin) and every fingertip.
    let mut compared: Vec<(String, retarget::LinkId)> = model
        .joints()
        .iter()
        .filter(|j| matches!(j.motion, JointMotion::Revolute { .. }))
        .map(|j| (format!("right_{}", j.name), j.child))
        .collect();
    for finger in ["thumb", "index", "middle", "ring", "pinky"] {
        let link = model.link(&format!("{finger}_fingertip")).unwrap();
        let joint = chain
            .find_link(&format!("right_{finger}_fingertip"))
            .unwrap()
            .joint()
            .name
            .clone();
        compared.push((joint, link));
    }
    assert_eq!(compared.len(), 17 + 5);

    let mut state = model.fk_state();
    let mut worst = (0.0_f64, String::new());
    for q in random_poses(&model, 20261121) {
        model.forward(&q, &mut state).unwrap();
        set_reference(&chain, &model, &q);
        for (joint, link) in &compared {
            let ours = state.position(*link);
            let theirs = reference_position(&chain, joint);
            let error = ((ours.x - theirs[0]).powi(2)
                + (ours.y - theirs[1]).powi(2)
                + (ours.z - theirs[2]).powi(2))
            .sqrt();
            if error > worst.0 {
                worst = (error, joint.clone());
            }
        }
    }
    println!(
        "compared against k 0.32 on {URDF}: {POSES} poses x {} frames, worst {:.3e} m at {}",
        compared.len(),
        worst.0,
        worst.1
    );
    assert!(
        worst.0 <= TOLERANCE_M,
        "worst error {} m at {}",
        worst.0,
        worst.1
    );
}

#[test]
fn builtin_orca_limits_and_zero_convention_are_the_urdf_ones() {
    let Some((chain, _)) = reference_chain("fk_crosscheck::limits") else {
        return;
    };
    let model = HandModel::orca_v1_right();
    for dof in model.dofs() {
        let node = chain.find(&format!("right_{}", dof.name)).unwrap();
        let range = node.joint().limits.unwrap();
        assert_eq!(
            (dof.limits.lower_rad, dof.limits.upper_rad),
            (range.min, range.max),
            "{}",
            dof.name
        );
    }
}

fn orca_urdf_import() -> UrdfImport {
    UrdfImport {
        strip_prefix: "right_".into(),
        frames: FrameSpec {
            palm: "palm".into(),
            wrist: "wrist_jointbody".into(),
            thumb_base: "thumb_mcp_jointbody".into(),
            index_base: "index_abd_jointbody".into(),
            middle_base: "middle_abd_jointbody".into(),
            ring_base: "ring_abd_jointbody".into(),
            little_base: "pinky_abd_jointbody".into(),
            thumb_tip: "thumb_fingertip".into(),
            index_tip: "index_fingertip".into(),
            middle_tip: "middle_fingertip".into(),
            ring_tip: "ring_fingertip".into(),
            little_tip: "pinky_fingertip".into(),
            thumb_mid: Some("thumb_ip".into()),
            index_mid: Some("index_ip".into()),
            middle_mid: Some("middle_ip".into()),
            ring_mid: Some("ring_ip".into()),
            little_mid: Some("pinky_ip".into()),
        },
    }
}

#[test]
fn urdf_import_matches_k_on_every_joint_frame() {
    let Some((chain, text)) = reference_chain("fk_crosscheck::urdf_import") else {
        return;
    };
    let model = HandModel::from_urdf_str(&text, &orca_urdf_import()).unwrap();
    let builtin = HandModel::orca_v1_right();
    assert_eq!(model.dof(), 17);
    let mut state = model.fk_state();
    let mut builtin_state = builtin.fk_state();
    for q_builtin in random_poses(&builtin, 5).into_iter().take(200) {
        // Same values by name: the importer keeps the URDF's joint order.
        let q: Vec<f64> = model
            .dof_names()
            .map(|n| q_builtin[builtin.dof_index(n).unwrap()])
            .collect();
        model.forward(&q, &mut state).unwrap();
        builtin.forward(&q_builtin, &mut builtin_state).unwrap();
        set_reference(&chain, &model, &q);
        for joint in model.joints() {
            // The importer stripped `right_` where present (`thumb_dp2right_…` has none).
            let prefixed = format!("right_{}", joint.name);
            let original = if chain.find(&prefixed).is_some() {
                prefixed
            } else {
                joint.name.clone()
            };
            let theirs = reference_position(&chain, &original);
            let ours = state.position(joint.child);
            let error = (ours.coords - nalgebra::Vector3::from(theirs)).norm();
            assert!(error <= TOLERANCE_M, "{}: {error} m", joint.name);
        }
        for finger in retarget::Finger::ALL {
            let a = state.position(model.frames().tip(finger));
            let b = builtin_state.position(builtin.frames().tip(finger));
            assert!((a - b).norm() <= TOLERANCE_M, "{finger} tip");
        }
    }
}

#[test]
fn a_missing_reference_file_is_skipped_outside_ci() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for ci in [false, true] {
        let found = common::reference_file_in(dir, "Cargo.toml", "helper", ci);
        assert_eq!(found, Some(dir.join("Cargo.toml")));
    }
    let missing = common::reference_file_in(dir, "no_such_file.urdf", "helper", false);
    assert_eq!(missing, None);
    assert_eq!(common::reference_file_in(dir, "src", "helper", false), None);
}

#[test]
#[should_panic(expected = "no_such_file.urdf")]
fn a_missing_reference_file_fails_under_ci() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    common::reference_file_in(dir, "no_such_file.urdf", "helper", true);
}
