//! The lab hand's pieces from a manufacturer-like file written here: the project's own ORCA
//! hand re-dressed as a vendor would ship it (top-level defaults, a mesh directory, a joint
//! `ref`, actuators named `<joint>_actuator`, contact exclusions).

use retarget::HandModel;
use roxmltree::Document;

use super::*;
use crate::hand_mjcf::{HandMjcfOptions, hand_mjcf};

const REF: f64 = 0.2;

/// A vendor-style file of the ORCA hand; `right_index_mcp` has `ref` = [`REF`].
fn vendor_file(model: &HandModel) -> String {
    let own = hand_mjcf(model, &HandMjcfOptions::default());
    let body = own.body.replace(
        "<joint name=\"right_index_mcp\" type=\"hinge\" axis=\"0 -1 0\" range=\"-0.34907 1.65806\"",
        &format!("<joint name=\"right_index_mcp\" type=\"hinge\" axis=\"0 -1 0\" range=\"-0.34907 1.65806\" ref=\"{REF}\""),
    );
    assert_ne!(body, own.body, "the joint to give a ref");
    let actuators = own
        .actuators
        .lines()
        .map(|l| {
            l.replace(" class=\"pomdar_hand\"", "")
                .replacen("\" joint=", "_actuator\" joint=", 1)
        })
        .collect::<Vec<_>>()
        .join("\n");
    format!(
        r#"<mujoco model="vendor_hand">
  <compiler angle="radian" eulerseq="XYZ" meshdir="meshes"/>
  <default>
    <mesh scale="0.001 0.001 0.001"/>
    <joint damping="0.2"/>
    <default class="visual"><geom contype="0" conaffinity="0"/><default class="skin"><geom rgba="1 1 1 1"/></default></default>
    <default class="collision"><geom contype="1" conaffinity="1" condim="3"/></default>
  </default>
  <asset>
    <mesh name="palm_mesh" file="palm.stl"/>
    <mesh name="tip_mesh" file="/abs/tip.stl" scale="1 1 1"/>
  </asset>
  <worldbody>
{}
  </worldbody>
  <actuator>
{actuators}
  </actuator>
  <contact><exclude body1="right_palm" body2="right_index_mp"/></contact>
</mujoco>"#,
        body
    )
}

fn lab_hand(xml: &str) -> Result<HandMjcf, LabHandError> {
    lab_hand_mjcf(
        xml,
        "vendor.xml",
        "/labs/hand",
        &HandModel::orca_v1_right(),
        &HandMjcfOptions::default(),
    )
}

fn parse(fragment: &str) -> String {
    format!("<x>{fragment}</x>")
}

#[test]
fn zeros_ranges_and_actuators_follow_the_joint_ref() {
    let model = HandModel::orca_v1_right();
    let hand = lab_hand(&vendor_file(&model)).unwrap();
    let index = model
        .ros_dof_names()
        .iter()
        .position(|n| n == "right_index_mcp")
        .unwrap();
    let mut expected = vec![0.0; model.dof()];
    expected[index] = REF;
    assert_eq!(hand.zero_offsets_rad, expected);
    assert_eq!(hand.dof_joints, model.ros_dof_names());
    assert!(hand.dof_actuators.iter().all(|a| a.ends_with("_actuator")));
    // The range and the control range read as URDF angles: shifted by the ref in qpos.
    let shifted = format!("{} {}", -0.34907 + REF, 1.65806 + REF);
    let body = parse(&hand.body);
    let doc = Document::parse(&body).unwrap();
    let joint = doc
        .descendants()
        .find(|n| n.attribute("name") == Some("right_index_mcp"))
        .unwrap();
    assert_eq!(joint.attribute("range"), Some(shifted.as_str()));
    let actuators = parse(&hand.actuators);
    let doc = Document::parse(&actuators).unwrap();
    let actuator = doc
        .descendants()
        .find(|n| n.attribute("joint") == Some("right_index_mcp"))
        .unwrap();
    assert_eq!(actuator.attribute("ctrlrange"), Some(shifted.as_str()));
    assert_eq!(actuator.attribute("class"), Some(LAB_HAND_CLASS));
    // Joints without a ref keep their ranges.
    assert!(hand.body.contains(
        "name=\"right_middle_mcp\" type=\"hinge\" axis=\"0 -1 0\" range=\"-0.34907 1.58825\""
    ));
}

#[test]
fn defaults_assets_and_bodies_are_placed_for_a_task_scene() {
    let hand = lab_hand(&vendor_file(&HandModel::orca_v1_right())).unwrap();
    let defaults = Document::parse(&hand.defaults).unwrap();
    let class = |name: &str| {
        defaults
            .descendants()
            .find(|n| n.has_tag_name("default") && n.attribute("class") == Some(name))
            .and_then(|d| d.children().find(|c| c.has_tag_name("geom")))
            .unwrap()
    };
    // The vendor's top-level defaults in the lab class; the mesh scale moved to the meshes.
    let top = defaults.root_element();
    assert_eq!(top.attribute("class"), Some(LAB_HAND_CLASS));
    assert!(
        top.children()
            .any(|c| c.has_tag_name("joint") && c.attribute("damping") == Some("0.2"))
    );
    assert!(!hand.defaults.contains("<mesh"));
    // Colliding classes get the station's pads; visual ones (and what nests in them) do not.
    assert_eq!(class("collision").attribute("solref"), Some("0.005 1"));
    assert_eq!(class("collision").attribute("condim"), Some("4"));
    assert_eq!(class("visual").attribute("solref"), None);
    assert_eq!(class("skin").attribute("solref"), None);
    assert_eq!(class(LAB_HAND_CLASS).attribute("margin"), Some("0.0005"));
    // Mesh files under the file's directory and mesh directory, with the default scale.
    assert!(
        hand.assets
            .contains("file=\"/labs/hand/meshes/palm.stl\" scale=\"0.001 0.001 0.001\"")
    );
    assert!(
        hand.assets
            .contains("file=\"/abs/tip.stl\" scale=\"1 1 1\"")
    );
    assert!(hand.body.starts_with(&format!(
        "<body name=\"{LAB_HAND_ROOT}\" childclass=\"{LAB_HAND_CLASS}\">"
    )));
    assert_eq!(hand.root_body, LAB_HAND_ROOT);
    assert_eq!(hand.eulerseq.as_deref(), Some("XYZ"));
    assert!(
        hand.contact_excludes
            .contains("body1=\"right_palm\" body2=\"right_index_mp\"")
    );
    // Links the file has are named as in the URDF; the palm is one.
    assert_eq!(hand.palm_body, "right_palm");
}

#[test]
fn a_file_that_does_not_fit_is_refused_with_what_is_missing() {
    let model = HandModel::orca_v1_right();
    let file = vendor_file(&model);
    let message = lab_hand(
        &file
            .replace("right_pinky_pip_actuator", "x")
            .replace("joint=\"right_pinky_pip\"", "joint=\"elsewhere\""),
    )
    .unwrap_err()
    .to_string();
    assert_eq!(
        message,
        "vendor.xml: no actuator for right_pinky_pip (the URDF's degrees of freedom)"
    );
    let message = lab_hand(&file.replace("name=\"right_wrist\"", "name=\"wrist\""))
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("no hinge joint for right_wrist"),
        "{message}"
    );
    let message = lab_hand(&file.replace("angle=\"radian\"", "angle=\"degree\""))
        .unwrap_err()
        .to_string();
    assert!(message.contains("only radian"), "{message}");
    assert!(
        lab_hand("<robot/>")
            .unwrap_err()
            .to_string()
            .contains("not <mujoco>")
    );
}
