//! The world around a task: options, contact classes, table, light, the arm's mocap body
//! with the hand, and the hand's actuator, equality and contact sections.

use std::fmt::Write as _;

use super::mjcf::{indent, num, pose_attributes};
use super::{HAND_MOUNT_BODY, MOUNT_BODY, MOUNT_WELD, MountWeld, SceneOptions};
use crate::hand_mjcf::HandMjcf;

/// The task scaffolds' contact and look classes (see the module docs of `scene`).
const TASK_DEFAULTS: &str = r#"    <default class="pomdar_fixture">
      <geom condim="3" friction="0.8 0.005 0.0001" solref="0.004 1" rgba="0.62 0.64 0.68 1"/>
    </default>
    <default class="pomdar_object">
      <geom condim="4" friction="1 0.01 0.0002" solref="0.004 1" rgba="0.92 0.55 0.18 1"/>
      <joint armature="0.0001" solreflimit="0.004 1"/>
    </default>
    <default class="pomdar_free_object">
      <geom condim="6" friction="1 0.01 0.0005" solref="0.004 1" rgba="0.2 0.5 0.9 1"/>
    </default>
    <default class="pomdar_marker">
      <geom contype="0" conaffinity="0" group="1" rgba="0.2 0.8 0.3 0.35"/>
    </default>
"#;

/// The table (a plane at z = 0) and a light above the scaffolds.
const TABLE_AND_LIGHT: &str = r#"    <light name="pomdar_light" pos="0.5 0 1.5" dir="0 0 -1" diffuse="0.8 0.8 0.8"/>
    <geom name="pomdar_table" type="plane" pos="0.5 0 0" size="0.6 0.6 0.01" class="pomdar_fixture" rgba="0.85 0.82 0.75 1"/>
"#;

/// The MJCF document of task `task_id`'s world.
pub(super) fn world_xml(
    task_id: &str,
    scaffold: &str,
    hand: &HandMjcf,
    options: &SceneOptions,
) -> String {
    let mut xml = String::new();
    let _ = writeln!(xml, "<mujoco model=\"pomdar_{task_id}\">");
    let eulerseq = hand
        .eulerseq
        .as_ref()
        .map_or(String::new(), |seq| format!(" eulerseq=\"{seq}\""));
    let _ = writeln!(
        xml,
        "  <compiler angle=\"radian\" autolimits=\"true\"{eulerseq}/>"
    );
    let _ = writeln!(
        xml,
        "  <option timestep=\"{}\" gravity=\"0 0 -9.81\" integrator=\"implicitfast\" cone=\"elliptic\" impratio=\"{}\"/>",
        num(options.timestep_s),
        num(options.impratio)
    );
    let _ = writeln!(
        xml,
        "  <default>\n{}\n{TASK_DEFAULTS}  </default>",
        indent(&hand.defaults, 4)
    );
    xml.push_str(&section("asset", &hand.assets));
    xml.push_str("  <worldbody>\n");
    xml.push_str(TABLE_AND_LIGHT);
    xml.push_str(&arm_mount(hand, options));
    xml.push_str(scaffold);
    xml.push_str("  </worldbody>\n");
    xml.push_str(&section("contact", &hand.contact_excludes));
    xml.push_str(&section(
        "equality",
        &format!("{}\n{}", mount_weld(&options.mount), hand.equalities),
    ));
    xml.push_str(&section("actuator", &hand.actuators));
    xml.push_str("</mujoco>\n");
    xml
}

/// The mocap body at the arm's start pose, and the hand on a free body at its mount pose,
/// welded to it (see [`mount_weld`]).
fn arm_mount(hand: &HandMjcf, options: &SceneOptions) -> String {
    format!(
        "    <body name=\"{MOUNT_BODY}\" mocap=\"true\" {}/>\n    <body name=\"{HAND_MOUNT_BODY}\" {}>\n      <freejoint name=\"pomdar_hand_mount_free\"/>\n{}\n    </body>\n",
        pose_attributes(&options.arm_start),
        pose_attributes(&(options.arm_start * hand.mount)),
        indent(&hand.body, 6)
    )
}

/// The weld that holds the hand to the arm's mocap body at its reference pose.
fn mount_weld(weld: &MountWeld) -> String {
    let [timeconst, damping] = weld.solref;
    let [dmin, dmax, width] = weld.solimp;
    format!(
        "<weld name=\"{MOUNT_WELD}\" body1=\"{MOUNT_BODY}\" body2=\"{HAND_MOUNT_BODY}\" solref=\"{} {}\" solimp=\"{} {} {}\"/>",
        num(timeconst),
        num(damping),
        num(dmin),
        num(dmax),
        num(width)
    )
}

/// `<name>…</name>` around `content`, or nothing when it is empty.
fn section(name: &str, content: &str) -> String {
    if content.trim().is_empty() {
        String::new()
    } else {
        format!("  <{name}>\n{}\n  </{name}>\n", indent(content, 4))
    }
}
