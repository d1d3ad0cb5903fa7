//! The built-in calibration poses are what they say, on the ORCA model's own kinematics.

use calibration::{ORCA_V1_POSES_TOML, POSE_NAMES, PoseSet};
use retarget::{Finger, FkState, HandModel};

fn state(model: &HandModel, set: &PoseSet, name: &str) -> FkState {
    model
        .forward_new(&set.get(name).unwrap().joint_vector(model).unwrap())
        .unwrap()
}

/// Mean distance of the four fingertips from the palm frame origin, metres.
fn reach(model: &HandModel, state: &FkState) -> f64 {
    let palm = model.palm_frame(state).unwrap();
    Finger::OPPOSING
        .iter()
        .map(|&f| {
            palm.point_to_palm(&state.position(model.frames().tip(f)))
                .norm()
        })
        .sum::<f64>()
        / 4.0
}

/// Distance between the index and little fingertips, metres.
fn span(model: &HandModel, state: &FkState) -> f64 {
    (state.position(model.frames().tip(Finger::Index))
        - state.position(model.frames().tip(Finger::Little)))
    .norm()
}

#[test]
fn every_pose_is_within_the_model_limits() {
    let model = HandModel::orca_v1_right();
    let set = PoseSet::orca_v1();
    assert_eq!(
        set.poses
            .iter()
            .map(|p| p.name.as_str())
            .collect::<Vec<_>>(),
        POSE_NAMES
    );
    for pose in &set.poses {
        let q = pose.joint_vector(&model).unwrap();
        assert!(model.within_limits(&q), "{}", pose.name);
        assert!(!pose.instruction.is_empty());
    }
}

#[test]
fn pinch_poses_bring_the_thumb_to_their_finger() {
    let model = HandModel::orca_v1_right();
    let set = PoseSet::orca_v1();
    for finger in Finger::OPPOSING {
        let pose = set.poses.iter().find(|p| p.pinch == Some(finger)).unwrap();
        let s = state(&model, &set, &pose.name);
        let gap = (s.position(model.frames().tip(Finger::Thumb))
            - s.position(model.frames().tip(finger)))
        .norm();
        println!(
            "{}: thumb-tip to {finger}-tip {:.1} mm",
            pose.name,
            gap * 1e3
        );
        assert!(gap < 0.012, "{}: {gap} m", pose.name);
    }
}

#[test]
fn open_spread_and_closed_differ_as_described() {
    let model = HandModel::orca_v1_right();
    let set = PoseSet::orca_v1();
    let (open, spread, closed) = (
        state(&model, &set, "open"),
        state(&model, &set, "open_spread"),
        state(&model, &set, "closed"),
    );
    println!(
        "index-little span: open {:.0} mm, spread {:.0} mm; mean fingertip reach: open {:.0} mm, closed {:.0} mm",
        span(&model, &open) * 1e3,
        span(&model, &spread) * 1e3,
        reach(&model, &open) * 1e3,
        reach(&model, &closed) * 1e3
    );
    assert!(
        span(&model, &spread) > span(&model, &open) + 0.02,
        "spread must widen the hand"
    );
    assert!(
        reach(&model, &closed) < 0.6 * reach(&model, &open),
        "closed must curl the fingers"
    );
}

#[test]
fn malformed_pose_sets_are_rejected_by_name() {
    let swapped = ORCA_V1_POSES_TOML.replacen("name = \"open\"", "name = \"flat\"", 1);
    let err = PoseSet::from_toml_str(&swapped).unwrap_err().to_string();
    assert!(err.contains("flat") && err.contains("exactly"), "{err}");
    let wrong_pinch = ORCA_V1_POSES_TOML.replacen("pinch = \"ring\"", "pinch = \"index\"", 1);
    let err = PoseSet::from_toml_str(&wrong_pinch)
        .unwrap_err()
        .to_string();
    assert!(err.contains("pinch_ring"), "{err}");
    let model = HandModel::orca_v1_right();
    let outside = PoseSet::from_toml_str(&ORCA_V1_POSES_TOML.replacen(
        "index_mcp = 1.4",
        "index_mcp = 2.4",
        1,
    ))
    .unwrap();
    let err = outside
        .get("closed")
        .unwrap()
        .joint_vector(&model)
        .unwrap_err()
        .to_string();
    assert!(err.contains("closed") && err.contains("index_mcp"), "{err}");
}
