//! Malformed or incomplete URDFs and model files are rejected with an error that names the
//! element and the problem, and never panic.

use proptest::prelude::*;
use retarget::{FrameSpec, HandModel, ORCA_V1_RIGHT_TOML, UrdfImport};

fn frames_all(link: &str) -> FrameSpec {
    FrameSpec {
        palm: link.into(),
        wrist: link.into(),
        thumb_base: link.into(),
        index_base: link.into(),
        middle_base: link.into(),
        ring_base: link.into(),
        little_base: link.into(),
        thumb_tip: link.into(),
        index_tip: link.into(),
        middle_tip: link.into(),
        ring_tip: link.into(),
        little_tip: link.into(),
        thumb_mid: None,
        index_mid: None,
        middle_mid: None,
        ring_mid: None,
        little_mid: None,
    }
}

/// A small valid two-finger URDF; tests break one element of it at a time.
fn urdf(joints: &str, extra_links: &str) -> String {
    format!(
        r#"<?xml version="1.0"?>
<robot name="mini">
  <link name="base"/> <link name="palm"/> <link name="a"/> <link name="b"/> <link name="c"/>
  <link name="d"/> <link name="e"/> <link name="f"/> {extra_links}
  <joint name="palm_mount" type="fixed"><parent link="base"/><child link="palm"/>
    <origin xyz="0 0 0.05" rpy="0 0 0"/></joint>
  <joint name="a_mount" type="fixed"><parent link="palm"/><child link="a"/><origin xyz="0.03 0 0"/></joint>
  <joint name="b_mount" type="fixed"><parent link="palm"/><child link="b"/><origin xyz="0.015 0 0.04"/></joint>
  <joint name="c_mount" type="fixed"><parent link="palm"/><child link="c"/><origin xyz="0 0 0.04"/></joint>
  <joint name="d_mount" type="fixed"><parent link="palm"/><child link="d"/><origin xyz="-0.015 0 0.04"/></joint>
  <joint name="e_mount" type="fixed"><parent link="palm"/><child link="e"/><origin xyz="-0.03 0 0.03"/></joint>
  {joints}
</robot>"#
    )
}

const GOOD_JOINT: &str = r#"<joint name="b_flex" type="revolute"><parent link="b"/><child link="f"/>
    <origin xyz="0 0 0.04"/><axis xyz="0 1 0"/><limit lower="0" upper="1.5" effort="1" velocity="1"/></joint>"#;

fn import() -> UrdfImport {
    UrdfImport {
        strip_prefix: String::new(),
        frames: FrameSpec {
            palm: "palm".into(),
            wrist: "base".into(),
            thumb_base: "a".into(),
            index_base: "b".into(),
            middle_base: "c".into(),
            ring_base: "d".into(),
            little_base: "e".into(),
            thumb_tip: "a".into(),
            index_tip: "f".into(),
            middle_tip: "c".into(),
            ring_tip: "d".into(),
            little_tip: "e".into(),
            thumb_mid: None,
            index_mid: None,
            middle_mid: None,
            ring_mid: None,
            little_mid: None,
        },
    }
}

fn urdf_error(joints: &str, extra_links: &str) -> String {
    HandModel::from_urdf_str(&urdf(joints, extra_links), &import())
        .unwrap_err()
        .to_string()
}

fn assert_mentions(message: &str, words: &[&str]) {
    for word in words {
        assert!(
            message.contains(word),
            "error should mention '{word}': {message}"
        );
    }
}

#[test]
fn the_test_urdf_itself_is_valid() {
    let model = HandModel::from_urdf_str(&urdf(GOOD_JOINT, ""), &import()).unwrap();
    assert_eq!(model.dof_names().collect::<Vec<_>>(), ["b_flex"]);
}

#[test]
fn urdf_errors_name_the_element_and_the_problem() {
    let cases: [(&str, &str, &[&str]); 11] = [
        (
            r#"<joint name="b_flex" type="revolute"><parent link="b"/><child link="nowhere"/>
               <axis xyz="0 1 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>"#,
            "",
            &["b_flex", "child", "nowhere", "not declared"],
        ),
        (
            r#"<joint name="b_flex" type="revolute"><parent link="b"/><child link="f"/>
               <axis xyz="0 1 0"/><limit lower="1" upper="0" effort="1" velocity="1"/></joint>"#,
            "",
            &["b_flex", "lower < upper"],
        ),
        (
            r#"<joint name="b_slide" type="prismatic"><parent link="b"/><child link="f"/>
               <limit lower="0" upper="0.01" effort="1" velocity="1"/></joint>"#,
            "",
            &["b_slide", "prismatic", "not supported"],
        ),
        (
            r#"<joint name="b_flex" type="revolute"><parent link="b"/><child link="f"/>
               <axis xyz="0 0 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>"#,
            "",
            &["b_flex", "axis", "zero length"],
        ),
        (
            r#"<joint name="b_flex" type="revolute"><parent link="b"/><child link="f"/>
               <origin xyz="0 NaN 0"/><axis xyz="0 1 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>"#,
            "",
            &["b_flex", "xyz_m", "finite"],
        ),
        (
            r#"<joint name="b_flex" type="revolute"><parent link="b"/><child link="f"/>
               <origin xyz="0 1e308 0"/><axis xyz="0 1 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>"#,
            "",
            &["b_flex", "xyz_m", "1e308", "[-10, 10] m"],
        ),
        (
            r#"<joint name="b_flex" type="revolute"><parent link="b"/><child link="f"/>
               <axis xyz="0 1 0"/><limit lower="0" upper="1e9" effort="1" velocity="1"/></joint>"#,
            "",
            &["b_flex", "upper_rad", "[-2π, 2π] rad"],
        ),
        (
            r#"<joint name="b_flex" type="revolute"><parent link="b"/><child link="f"/>
               <axis xyz="0 1 0"/><limit lower="0" upper="1" effort="1" velocity="1"/><mimic joint="ghost"/></joint>"#,
            "",
            &["b_flex", "ghost", "not a joint"],
        ),
        (GOOD_JOINT, r#"<link name="orphan"/>"#, &["root", "orphan"]),
        (
            r#"<joint name="b_flex" type="revolute"><parent link="b"/><child link="c"/>
               <axis xyz="0 1 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>"#,
            "",
            &["link 'c'", "c_mount", "b_flex", "two joints"],
        ),
        (
            &GOOD_JOINT.replace("b_flex", "palm_mount"),
            "",
            &["palm_mount", "twice"],
        ),
    ];
    for (joints, extra, words) in cases {
        assert_mentions(&urdf_error(joints, extra), words);
    }
}

#[test]
fn incomplete_urdf_xml_is_an_error() {
    let text = urdf(GOOD_JOINT, "");
    for cut in [10, text.len() / 2, text.len() - 12] {
        let err = HandModel::from_urdf_str(&text[..cut], &import()).unwrap_err();
        assert_mentions(&err.to_string(), &["invalid URDF", "not well-formed XML"]);
    }
    let no_velocity = urdf(
        r#"<joint name="b_flex" type="revolute"><parent link="b"/><child link="f"/>
           <axis xyz="0 1 0"/><limit lower="0" upper="1"/></joint>"#,
        "",
    );
    let err = HandModel::from_urdf_str(&no_velocity, &import())
        .unwrap_err()
        .to_string();
    assert_mentions(&err, &["joint 'b_flex'", "line 12", "velocity"]);
    let missing_parent = urdf(
        r#"<joint name="b_flex" type="revolute"><child link="f"/><axis xyz="0 1 0"/>
           <limit lower="0" upper="1" effort="1" velocity="1"/></joint>"#,
        "",
    );
    let err = HandModel::from_urdf_str(&missing_parent, &import())
        .unwrap_err()
        .to_string();
    assert_mentions(&err, &["joint 'b_flex'", "parent"]);
}

#[test]
fn a_frame_naming_a_missing_link_is_named() {
    let mut import = import();
    import.frames.index_tip = "fingertip".into();
    let err = HandModel::from_urdf_str(&urdf(GOOD_JOINT, ""), &import)
        .unwrap_err()
        .to_string();
    assert_mentions(&err, &["index_tip", "fingertip", "not in the model"]);
}

#[test]
fn mid_frames_are_all_or_none() {
    let mut import = import();
    import.frames.index_mid = Some("f".into());
    let err = HandModel::from_urdf_str(&urdf(GOOD_JOINT, ""), &import)
        .unwrap_err()
        .to_string();
    assert_mentions(&err, &["only 1 of the 5", "all five or none"]);
}

#[test]
fn a_degenerate_palm_is_rejected() {
    let mut import = import();
    import.frames = frames_all("palm");
    let err = HandModel::from_urdf_str(&urdf(GOOD_JOINT, ""), &import)
        .unwrap_err()
        .to_string();
    assert_mentions(&err, &["palm frame", "degenerate", "wrist to middle base"]);
}

fn toml_error(from: &str, to: &str) -> String {
    assert!(ORCA_V1_RIGHT_TOML.contains(from), "test fixture: {from}");
    HandModel::from_toml_str(&ORCA_V1_RIGHT_TOML.replacen(from, to, 1))
        .unwrap_err()
        .to_string()
}

#[test]
fn model_file_errors_name_the_key_or_joint_and_the_problem() {
    let thumb_dip = "name = \"thumb_dip\"\nkind = \"revolute\"";
    let cases: [(&str, &str, &[&str]); 8] = [
        (thumb_dip, "name = \"thumb_dip\"", &["kind", "missing"]),
        (
            "lower_rad = -0.85384",
            "lower_rad = -0.85384\nlower_deg = 3.0",
            &["lower_deg", "unknown field"],
        ),
        (
            "axis = [1.0, 0.0, 0.0]\nlower_rad = -0.6736",
            "lower_rad = -0.6736",
            &["wrist", "axis"],
        ),
        (
            "lower_rad = -0.85384",
            "lower_rad = 1.9",
            &["thumb_dip", "lower < upper"],
        ),
        (
            "axis = [1.0, 0.0, 0.0]",
            "axis = [0.0, 0.0, 0.0]",
            &["wrist", "zero length"],
        ),
        (
            "name = \"thumb_dip\"",
            "name = \"thumb_pip\"",
            &["thumb_pip", "twice"],
        ),
        (
            "xyz_m = [0.04, 0.0, 0.04575]",
            "xyz_m = [0.04, 0.0, 0.04575]\nlower_rad = 0.0",
            &["tower_mount", "fixed", "lower_rad"],
        ),
        (
            "little_tip = \"pinky_fingertip\"",
            "little_tip = \"pinky_tip\"",
            &["little_tip", "pinky_tip"],
        ),
    ];
    for (from, to, words) in cases {
        assert_mentions(&toml_error(from, to), words);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Truncated and byte-corrupted model files give errors, never panics.
    #[test]
    fn corrupted_model_files_never_panic(cut in 0usize..ORCA_V1_RIGHT_TOML.len(), at in 0usize..ORCA_V1_RIGHT_TOML.len(), byte in any::<u8>()) {
        let _ = HandModel::from_toml_str(&ORCA_V1_RIGHT_TOML[..cut]);
        let mut bytes = ORCA_V1_RIGHT_TOML.as_bytes().to_vec();
        bytes[at] = byte;
        let _ = HandModel::from_toml_str(&String::from_utf8_lossy(&bytes));
    }

    /// Truncated and byte-corrupted URDFs give errors, never panics.
    #[test]
    fn corrupted_urdfs_never_panic(cut_frac in 0.0..1.0_f64, at_frac in 0.0..1.0_f64, byte in any::<u8>()) {
        let text = urdf(GOOD_JOINT, "");
        let cut = (text.len() as f64 * cut_frac) as usize;
        let _ = HandModel::from_urdf_str(&text[..cut], &import());
        let mut bytes = text.into_bytes();
        let at = (bytes.len() as f64 * at_frac) as usize;
        bytes[at] = byte;
        let _ = HandModel::from_urdf_str(&String::from_utf8_lossy(&bytes), &import());
    }
}
