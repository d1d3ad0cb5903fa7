//! Property tests: analytic positional Jacobians equal central finite differences of FK, for
//! every link of the built-in ORCA model and of a model with a linear coupling.

use nalgebra::Matrix3xX;
use proptest::prelude::*;
use retarget::HandModel;

const STEP_RAD: f64 = 1e-6;
const TOLERANCE: f64 = 1e-6; // m/rad, elementwise

/// A finger with a coupled distal joint (DIP = 0.58333 · PIP + 0.05, as on an early ORCA
/// prototype) so the coupling's column folding is exercised.
const COUPLED_FINGER: &str = r#"
name = "coupled_finger"
[frames]
palm = "palm"
wrist = "base"
thumb_base = "thumb_root"
index_base = "f_root"
middle_base = "mid_root"
ring_base = "ring_root"
little_base = "little_root"
thumb_tip = "thumb_root"
index_tip = "tip"
middle_tip = "mid_root"
ring_tip = "ring_root"
little_tip = "little_root"

[[joint]]
name = "palm_mount"
kind = "fixed"
parent = "base"
child = "palm"
xyz_m = [0.0, 0.0, 0.05]
[[joint]]
name = "thumb_mount"
kind = "fixed"
parent = "palm"
child = "thumb_root"
xyz_m = [0.03, 0.0, 0.0]
[[joint]]
name = "mid_mount"
kind = "fixed"
parent = "palm"
child = "mid_root"
xyz_m = [0.0, 0.0, 0.04]
[[joint]]
name = "ring_mount"
kind = "fixed"
parent = "palm"
child = "ring_root"
xyz_m = [-0.015, 0.0, 0.038]
[[joint]]
name = "little_mount"
kind = "fixed"
parent = "palm"
child = "little_root"
xyz_m = [-0.03, 0.0, 0.03]
[[joint]]
name = "f_abd"
kind = "revolute"
parent = "palm"
child = "f_root"
xyz_m = [0.015, 0.0, 0.04]
rpy_rad = [0.1, -0.2, 0.3]
axis = [1.0, 0.0, 0.0]
lower_rad = -0.5
upper_rad = 0.5
[[joint]]
name = "f_pip"
kind = "revolute"
parent = "f_root"
child = "f_mid"
xyz_m = [0.0, 0.0, 0.04]
axis = [0.0, 1.0, 0.2]
lower_rad = 0.0
upper_rad = 1.8
[[joint]]
name = "f_dip"
kind = "revolute"
parent = "f_mid"
child = "f_dist"
xyz_m = [0.0, 0.0, 0.03]
axis = [0.0, 1.0, 0.0]
lower_rad = 0.0
upper_rad = 1.0
coupled = { joint = "f_pip", multiplier = 0.58333, offset_rad = 0.05 }
[[joint]]
name = "f_tip"
kind = "fixed"
parent = "f_dist"
child = "tip"
xyz_m = [0.0, 0.002, 0.02]
"#;

fn pose_in_limits(model: &HandModel, unit: &[f64]) -> Vec<f64> {
    model
        .limits()
        .zip(unit)
        .map(|(l, u)| l.lower_rad + u * (l.upper_rad - l.lower_rad))
        .collect()
}

/// Largest elementwise difference between analytic and central-difference Jacobians over
/// every link of `model` at `q`.
fn worst_jacobian_error(model: &HandModel, q: &[f64]) -> f64 {
    let state = model.forward_new(q).unwrap();
    let mut jacobian = Matrix3xX::zeros(model.dof());
    let mut worst = 0.0_f64;
    for link in (0..model.link_count()).map(|i| model.link(&model.link_names()[i]).unwrap()) {
        model
            .position_jacobian(&state, link, &mut jacobian)
            .unwrap();
        for dof in 0..model.dof() {
            let mut plus = q.to_vec();
            let mut minus = q.to_vec();
            plus[dof] += STEP_RAD;
            minus[dof] -= STEP_RAD;
            let p = model.forward_new(&plus).unwrap().position(link);
            let m = model.forward_new(&minus).unwrap().position(link);
            let numeric = (p - m) / (2.0 * STEP_RAD);
            worst = worst.max((numeric - jacobian.column(dof)).amax());
        }
    }
    worst
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn orca_jacobians_equal_central_differences(unit in prop::collection::vec(0.0..=1.0_f64, 17)) {
        let model = HandModel::orca_v1_right();
        let q = pose_in_limits(&model, &unit);
        let worst = worst_jacobian_error(&model, &q);
        prop_assert!(worst <= TOLERANCE, "worst {worst} at q = {q:?}");
    }

    #[test]
    fn coupled_jacobians_equal_central_differences(unit in prop::collection::vec(0.0..=1.0_f64, 2)) {
        let model = HandModel::from_toml_str(COUPLED_FINGER).unwrap();
        let q = pose_in_limits(&model, &unit);
        let worst = worst_jacobian_error(&model, &q);
        prop_assert!(worst <= TOLERANCE, "worst {worst} at q = {q:?}");
    }
}

#[test]
fn coupling_drives_the_follower_and_folds_its_limits() {
    let model = HandModel::from_toml_str(COUPLED_FINGER).unwrap();
    assert_eq!(model.dof_names().collect::<Vec<_>>(), ["f_abd", "f_pip"]);
    // f_dip ∈ [0, 1] ⇒ f_pip ∈ [(0 − 0.05)/0.58333, (1 − 0.05)/0.58333] ∩ [0, 1.8].
    let pip = model.dofs()[1].limits;
    assert_eq!(pip.lower_rad, 0.0);
    assert!((pip.upper_rad - 0.95 / 0.58333).abs() < 1e-12);

    // The distal link turns by 0.58333·q + 0.05 about its axis relative to the middle link.
    let q = [0.0, 1.2];
    let state = model.forward_new(&q).unwrap();
    let mid = state.pose(model.link("f_mid").unwrap());
    let dist = state.pose(model.link("f_dist").unwrap());
    let relative = mid.rotation.inverse() * dist.rotation;
    assert!((relative.angle() - (0.58333 * 1.2 + 0.05)).abs() < 1e-12);
}

#[test]
fn jacobian_of_a_link_ignores_joints_below_it() {
    let model = HandModel::orca_v1_right();
    let state = model.forward_new(&model.zero_pose()).unwrap();
    let mut jacobian = Matrix3xX::zeros(model.dof());
    let index_tip = model.frames().tip(retarget::Finger::Index);
    model
        .position_jacobian(&state, index_tip, &mut jacobian)
        .unwrap();
    for (dof, name) in model.dof_names().enumerate() {
        let moves = jacobian.column(dof).norm() > 0.0;
        let expected = name.starts_with("index_") || name == "wrist";
        assert_eq!(moves, expected, "{name}");
        assert_eq!(model.moves(dof, index_tip), expected, "{name}");
    }
}

#[test]
fn wrong_shapes_are_errors_not_panics() {
    let model = HandModel::orca_v1_right();
    let mut state = model.fk_state();
    let err = model.forward(&[0.0; 3], &mut state).unwrap_err();
    assert_eq!(err.to_string(), "expected 17 joint values, got 3");
    let mut small = Matrix3xX::zeros(4);
    let tip = model.frames().tip(retarget::Finger::Thumb);
    let err = model
        .position_jacobian(&state, tip, &mut small)
        .unwrap_err();
    assert!(err.to_string().contains("3 x 17"), "{err}");
}
