//! The shipped presets' tables against the facts they are taken from (ETH lab hand-control
//! node, orca_core), and the default configuration's output unchanged.

use retarget::{HandModel, ORCA_CORE_JOINTS};

use crate::hand_convention::{Basis, JointConvention, RefZero, Units};
use crate::policy_output::{PolicyOutput, PolicyOutputConfig};
use crate::station_config::StationConfig;

const ETH_LAB: &str = include_str!("../../launch_configs/station/eth_lab.toml");
const ORCA_CORE: &str = include_str!("../../launch_configs/station/orca_core.toml");

fn table(text: &str) -> PolicyOutputConfig {
    StationConfig::from_toml_str(text).unwrap().policy_output
}

fn urdf_deg(model: &HandModel, joint: &str) -> (f64, f64) {
    let l = model.dofs()[model.dof_index(joint).unwrap()].limits;
    (l.lower_rad.to_degrees(), l.upper_rad.to_degrees())
}

/// The row's range is the URDF's limits mapped through `sign` and `offset` (degrees).
fn assert_mapped_range(model: &HandModel, row: &JointConvention, offset: f64) {
    let (lo, hi) = urdf_deg(model, &row.joint);
    let s = f64::from(row.sign);
    let (a, b) = (s * lo + offset, s * hi + offset);
    assert!(
        (row.lower_deg - a.min(b)).abs() < 2e-3 && (row.upper_deg - a.max(b)).abs() < 2e-3,
        "{}: [{}, {}] vs [{}, {}]",
        row.joint,
        row.lower_deg,
        row.upper_deg,
        a.min(b),
        a.max(b)
    );
}

#[test]
fn eth_lab_is_the_lab_nodes_table() {
    let model = HandModel::orca_v1_right();
    let config = table(ETH_LAB);
    assert_eq!(config.topic, "/hand/policy_output");
    assert_eq!(config.consumer, "eth_hand_control");
    assert_eq!(config.units, Units::Rad);
    assert!(!config.provenance.is_empty());
    let order: Vec<&str> = config.joints.iter().map(|r| r.joint.as_str()).collect();
    let mut expected = vec!["wrist"];
    expected.extend(&ORCA_CORE_JOINTS[..16]);
    assert_eq!(order, expected);
    for row in &config.joints {
        let (sign, offset, basis) = match row.joint.as_str() {
            "index_abd" => (-1, 14.5, Basis::Sources),
            "middle_abd" => (-1, 0.0, Basis::Sources),
            "ring_abd" => (-1, 0.0, Basis::Approximate),
            "pinky_abd" => (1, 1.8, Basis::Sources),
            j if j.starts_with("thumb") || j == "wrist" => (1, 0.0, Basis::Assumed),
            _ => (1, 0.0, Basis::Sources),
        };
        assert_eq!(
            (row.sign, row.offset_deg, row.basis),
            (sign, offset, basis),
            "{}",
            row.joint
        );
        assert_eq!(row.ref_deg, 0.0);
        assert!(!row.verified, "{}", row.joint);
        assert!(
            !row.note.is_empty(),
            "{}: every row says where it stands",
            row.joint
        );
        assert_mapped_range(&model, row, offset);
    }
    // index_abd at URDF zero is 14.5° of the lab's model, sent in radians.
    let output = PolicyOutput::new(&model, &config).unwrap();
    let values = output.values(&model.zero_pose());
    assert!((f64::from(values[5]) - 14.5f64.to_radians()).abs() < 1e-6);
    assert!(!config.verification().is_verified());
}

#[test]
fn orca_core_is_degrees_wrist_last_with_the_ref_choice() {
    let model = HandModel::orca_v1_right();
    let config = table(ORCA_CORE);
    assert_eq!(config.consumer, "orca_core");
    assert_eq!(config.units, Units::Deg);
    assert_eq!(config.ref_zero, Some(RefZero::MinusRef));
    let order: Vec<&str> = config.joints.iter().map(|r| r.joint.as_str()).collect();
    assert_eq!(order, ORCA_CORE_JOINTS);
    let refs = [
        ("thumb_abd", -42.0),
        ("thumb_dip", -28.92),
        ("index_abd", -22.92),
        ("pinky_abd", 29.98),
        ("thumb_pip", -33.52),
        ("ring_abd", 9.74),
    ];
    for row in &config.joints {
        let reference = refs
            .iter()
            .find(|(j, _)| *j == row.joint)
            .map_or(0.0, |r| r.1);
        assert_eq!(row.ref_deg, reference, "{}", row.joint);
        assert_eq!(row.offset_deg, 0.0, "{}", row.joint);
        assert_eq!(row.sign, if row.joint == "wrist" { -1 } else { 1 });
        // orca_core's ranges: the URDF's limits − ref (the wrist's mirrored).
        assert_mapped_range(&model, row, -reference);
        assert!(!row.verified);
    }
    // Under minus_ref the URDF's limits land on orca_core's range ends; under equal the
    // URDF's zero is orca_core's zero.
    let output = PolicyOutput::new(&model, &config).unwrap();
    let thumb_abd = model.dof_index("thumb_abd").unwrap();
    let mut q = model.zero_pose();
    q[thumb_abd] = urdf_deg(&model, "thumb_abd").0.to_radians();
    assert!((f64::from(output.values(&q)[1]) - (-20.0)).abs() < 1e-3);
    assert!((f64::from(output.values(&model.zero_pose())[1]) - 42.0).abs() < 1e-3);
    let equal = PolicyOutputConfig {
        ref_zero: Some(RefZero::Equal),
        ..config
    };
    let output = PolicyOutput::new(&model, &equal).unwrap();
    assert_eq!(output.values(&model.zero_pose())[1], 0.0);
    let mut q = model.zero_pose();
    q[model.dof_index("wrist").unwrap()] = 0.3;
    assert!((f64::from(output.values(&q)[16]) + 0.3f64.to_degrees()).abs() < 1e-4);
}

#[test]
fn the_default_configuration_sends_what_it_always_sent() {
    let model = HandModel::orca_v1_right();
    let config = StationConfig::default().policy_output;
    assert!(config.joints.is_empty());
    let output = PolicyOutput::new(&model, &config).unwrap();
    let q: Vec<f64> = (0..17).map(|i| (i as f64 - 8.0) * 0.37).collect();
    let mut expected = vec![q[model.dof_index("wrist").unwrap()] as f32];
    expected.extend(
        ORCA_CORE_JOINTS[..16]
            .iter()
            .map(|j| q[model.dof_index(j).unwrap()] as f32),
    );
    assert_eq!(output.values(&q), expected);
}
