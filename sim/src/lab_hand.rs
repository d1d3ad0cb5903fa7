//! A lab's own MuJoCo model of the robot hand (the manufacturer's MJCF, with its meshes) as the
//! pieces a task scene assembles, in place of the hand this project writes from the URDF.
//!
//! The lab names the file; the project ships none. What is taken from it, and how:
//!
//! - **Bodies, meshes, materials, actuators and contact exclusions** as the file has them. The
//!   hand's `<worldbody>` content goes inside a body named [`LAB_HAND_ROOT`] at the URDF root
//!   link's frame (the file's world frame), under the arm's mount. Mesh and texture files are
//!   made absolute (the file's directory and its `<compiler meshdir>`), with the file's
//!   default mesh scale written on each mesh.
//! - **Its top-level defaults** become a class, [`LAB_HAND_CLASS`], that its own classes nest
//!   in and its root body and actuators use, so the hand's joint damping and servo gains do
//!   not reach the task's own joints.
//! - **Contact**: every default class whose geoms collide gets the station's contact settings
//!   ([`HandMjcfOptions::contact_attributes`]): the same pads for either hand, chosen by
//!   measurement on the grasp tasks.
//! - **Zeros.** A joint's `ref` is where MuJoCo's `qpos` puts the URDF's zero: `qpos` = URDF
//!   angle + `ref` (measured on the ORCA v1 model: with this conversion every body agrees with
//!   the URDF's forward kinematics). The offsets are returned per degree of freedom
//!   ([`HandMjcf::zero_offsets_rad`]) for the engine to apply to commands and readings.
//! - **Ranges.** The file's joint `range` and actuator `ctrlrange` carry the URDF's limit
//!   numbers unchanged, so for a joint with a `ref` they are not the URDF's physical range.
//!   This reads them as URDF angles: both are shifted by the joint's `ref`, so the twin's hand
//!   moves over the URDF's range as the real hand does.
//!
//! Joints are matched by the URDF's degree-of-freedom names ([`HandModel::ros_dof_names`]),
//! actuators by the joint they drive.

mod xml_copy;

#[cfg(test)]
mod tests;

use retarget::{HandModel, LinkId};
use roxmltree::{Document, Node};

use crate::hand_mjcf::{HandMjcf, HandMjcfOptions, hand_mount};
use xml_copy::{Attributes, copy, get, set};

/// The default class holding the lab hand's top-level defaults.
pub const LAB_HAND_CLASS: &str = "pomdar_lab_hand";
/// The body around the lab hand's world-body content.
pub const LAB_HAND_ROOT: &str = "pomdar_lab_hand_root";

/// A lab's hand file that cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LabHandError {
    /// Not well-formed XML, or not a `<mujoco>` document.
    #[error("{origin}: not an MJCF document: {message}")]
    Parse {
        /// The file.
        origin: String,
        /// What is wrong.
        message: String,
    },
    /// Angles in degrees.
    #[error("{origin}: <compiler angle=\"{angle}\">: only radian models are read")]
    Degrees {
        /// The file.
        origin: String,
        /// The value found.
        angle: String,
    },
    /// Degrees of freedom without a joint or an actuator of that name.
    #[error("{origin}: no {kind} for {names} (the URDF's degrees of freedom)")]
    Missing {
        /// The file.
        origin: String,
        /// `hinge joint` or `actuator`.
        kind: &'static str,
        /// The degrees of freedom, joined.
        names: String,
    },
}

/// The hand of the MJCF text `xml` (from file `origin`, whose directory is `dir`) for the
/// degrees of freedom of `model`, its contacts set from `options`.
pub fn lab_hand_mjcf(
    xml: &str,
    origin: &str,
    dir: &str,
    model: &HandModel,
    options: &HandMjcfOptions,
) -> Result<HandMjcf, LabHandError> {
    let parse_error = |message: String| LabHandError::Parse {
        origin: origin.to_string(),
        message,
    };
    let doc = Document::parse(xml).map_err(|e| parse_error(e.to_string()))?;
    let root = doc.root_element();
    if root.tag_name().name() != "mujoco" {
        return Err(parse_error(format!(
            "the root element is <{}>, not <mujoco>",
            root.tag_name().name()
        )));
    }
    let compiler = child(root, "compiler");
    let angle = compiler
        .and_then(|c| c.attribute("angle"))
        .unwrap_or("degree");
    if angle != "radian" {
        return Err(LabHandError::Degrees {
            origin: origin.to_string(),
            angle: angle.to_string(),
        });
    }
    let refs = dof_refs(root, origin, model)?;
    let (actuators, dof_actuators) = actuators_xml(root, origin, model, &refs)?;
    let bodies = body_names(root);
    Ok(HandMjcf {
        body: body_xml(root, model, &refs),
        defaults: defaults_xml(root, options),
        actuators,
        equalities: children_xml(root, "equality"),
        contact_excludes: children_xml(root, "contact"),
        dof_joints: model.ros_dof_names().to_vec(),
        dof_actuators,
        tip_bodies: model
            .frames()
            .tips
            .map(|tip| present_link(model, tip, &bodies)),
        palm_body: present_link(model, model.frames().palm, &bodies),
        root_body: LAB_HAND_ROOT.to_string(),
        max_speed_rad_s: options.max_speed_rad_s,
        assets: assets_xml(root, dir, compiler),
        zero_offsets_rad: refs,
        eulerseq: compiler
            .and_then(|c| c.attribute("eulerseq"))
            .map(str::to_string),
        // The file's world frame is the URDF root link's, as the project's hand's root is.
        mount: hand_mount(model, options),
    })
}

fn child<'a, 'input>(node: Node<'a, 'input>, tag: &str) -> Option<Node<'a, 'input>> {
    node.children().find(|n| n.tag_name().name() == tag)
}

/// The `ref` of every degree of freedom's hinge, in the model's order.
fn dof_refs(root: Node<'_, '_>, origin: &str, model: &HandModel) -> Result<Vec<f64>, LabHandError> {
    let joints: Vec<Node<'_, '_>> = root
        .descendants()
        .filter(|n| {
            n.tag_name().name() == "joint" && n.parent().is_some_and(|p| p.has_tag_name("body"))
        })
        .collect();
    let mut missing = Vec::new();
    let refs = model
        .ros_dof_names()
        .iter()
        .map(
            |name| match joints.iter().find(|j| j.attribute("name") == Some(name)) {
                Some(joint) => joint
                    .attribute("ref")
                    .and_then(|r| r.parse().ok())
                    .unwrap_or(0.0),
                None => {
                    missing.push(name.clone());
                    0.0
                }
            },
        )
        .collect();
    if missing.is_empty() {
        Ok(refs)
    } else {
        Err(LabHandError::Missing {
            origin: origin.to_string(),
            kind: "hinge joint",
            names: missing.join(", "),
        })
    }
}

/// `"lo hi"` shifted by `offset`.
fn shifted_range(range: &str, offset: f64) -> Option<String> {
    let values: Vec<f64> = range
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .ok()?;
    match values[..] {
        [lo, hi] => Some(format!("{} {}", lo + offset, hi + offset)),
        _ => None,
    }
}

/// The offset of the degree of freedom named `name`, if it is one.
fn dof_offset(model: &HandModel, refs: &[f64], name: Option<&str>) -> Option<f64> {
    let name = name?;
    let index = model.ros_dof_names().iter().position(|n| n == name)?;
    Some(refs[index])
}

/// The hand's world-body content inside [`LAB_HAND_ROOT`], its hinges' ranges shifted by their
/// `ref`.
fn body_xml(root: Node<'_, '_>, model: &HandModel, refs: &[f64]) -> String {
    let mut out = format!("<body name=\"{LAB_HAND_ROOT}\" childclass=\"{LAB_HAND_CLASS}\">\n");
    let mut edit = |node: Node<'_, '_>, attributes: &mut Attributes| {
        if node.has_tag_name("joint") {
            shift_range(
                attributes,
                "range",
                dof_offset(model, refs, node.attribute("name")),
            );
        }
    };
    if let Some(world) = child(root, "worldbody") {
        for node in world.children().filter(|n| n.has_tag_name("body")) {
            out.push_str(&copy(node, 1, &mut edit));
        }
    }
    out.push_str("</body>\n");
    out
}

fn shift_range(attributes: &mut Attributes, name: &str, offset: Option<f64>) {
    let Some(offset) = offset.filter(|o| *o != 0.0) else {
        return;
    };
    if let Some(range) = get(attributes, name).and_then(|r| shifted_range(r, offset)) {
        set(attributes, name, range);
    }
}

/// The actuators in the lab class, each degree of freedom's found by the joint it drives, their
/// control ranges shifted by the joint's `ref`.
fn actuators_xml(
    root: Node<'_, '_>,
    origin: &str,
    model: &HandModel,
    refs: &[f64],
) -> Result<(String, Vec<String>), LabHandError> {
    let elements: Vec<Node<'_, '_>> = child(root, "actuator")
        .map(|a| a.children().filter(Node::is_element).collect())
        .unwrap_or_default();
    let mut names = Vec::new();
    let mut missing = Vec::new();
    for dof in model.ros_dof_names() {
        let found = elements
            .iter()
            .find(|a| a.attribute("joint") == Some(dof.as_str()))
            .and_then(|a| a.attribute("name"));
        match found {
            Some(name) => names.push(name.to_string()),
            None => missing.push(dof.clone()),
        }
    }
    if !missing.is_empty() {
        return Err(LabHandError::Missing {
            origin: origin.to_string(),
            kind: "actuator",
            names: missing.join(", "),
        });
    }
    let mut edit = |node: Node<'_, '_>, attributes: &mut Attributes| {
        if get(attributes, "class").is_none() {
            set(attributes, "class", LAB_HAND_CLASS.to_string());
        }
        shift_range(
            attributes,
            "ctrlrange",
            dof_offset(model, refs, node.attribute("joint")),
        );
    };
    let xml = elements.iter().map(|a| copy(*a, 0, &mut edit)).collect();
    Ok((xml, names))
}

/// The file's top-level defaults as the class [`LAB_HAND_CLASS`] (its mesh scale left to the
/// meshes), every colliding geom default with the station's contact settings.
fn defaults_xml(root: Node<'_, '_>, options: &HandMjcfOptions) -> String {
    let contact = options.contact_attributes();
    let mut edit = |node: Node<'_, '_>, attributes: &mut Attributes| {
        if node.has_tag_name("geom") && collides(node) {
            for (name, value) in &contact {
                set(attributes, name, value.clone());
            }
        }
    };
    let mut out = format!("<default class=\"{LAB_HAND_CLASS}\">\n");
    let top = child(root, "default");
    let elements: Vec<Node<'_, '_>> = top
        .map(|d| {
            d.children()
                .filter(|n| n.is_element() && !n.has_tag_name("mesh"))
                .collect()
        })
        .unwrap_or_default();
    if !elements.iter().any(|n| n.has_tag_name("geom")) {
        let attributes: String = contact
            .iter()
            .map(|(name, value)| format!(" {name}=\"{value}\""))
            .collect();
        out.push_str(&format!("  <geom{attributes}/>\n"));
    }
    for node in elements {
        out.push_str(&copy(node, 1, &mut edit));
    }
    out.push_str("</default>\n");
    out
}

/// Whether a geom default collides: not both contact bits zero, each bit as the default or
/// the nearest enclosing default class sets it.
fn collides(geom: Node<'_, '_>) -> bool {
    let inherited = |name: &str| {
        geom.ancestors()
            .filter(|a| a.has_tag_name("default"))
            .find_map(|class| child(class, "geom").and_then(|g| g.attribute(name)))
    };
    !(inherited("contype") == Some("0") && inherited("conaffinity") == Some("0"))
}

/// The file's assets, file paths absolute, every mesh with the default mesh scale unless it
/// has its own.
fn assets_xml(root: Node<'_, '_>, dir: &str, compiler: Option<Node<'_, '_>>) -> String {
    let scale = child(root, "default")
        .and_then(|d| child(d, "mesh"))
        .and_then(|m| m.attribute("scale"))
        .map(str::to_string);
    let asset_dir = |kind: &str| {
        let sub = compiler
            .and_then(|c| c.attribute(kind).or_else(|| c.attribute("assetdir")))
            .unwrap_or("");
        join(dir, sub)
    };
    let mut edit = |node: Node<'_, '_>, attributes: &mut Attributes| {
        let base = if node.has_tag_name("texture") {
            asset_dir("texturedir")
        } else {
            asset_dir("meshdir")
        };
        if let Some(file) = get(attributes, "file").map(str::to_string) {
            set(attributes, "file", join(&base, &file));
        }
        if let Some(scale) = scale
            .as_ref()
            .filter(|_| node.has_tag_name("mesh") && get(attributes, "scale").is_none())
        {
            set(attributes, "scale", scale.clone());
        }
    };
    child(root, "asset")
        .map(|a| {
            a.children()
                .filter(Node::is_element)
                .map(|n| copy(n, 0, &mut edit))
                .collect()
        })
        .unwrap_or_default()
}

/// `path` under `base` unless it is absolute.
fn join(base: &str, path: &str) -> String {
    if path.starts_with('/') || base.is_empty() {
        path.to_string()
    } else if path.is_empty() {
        base.to_string()
    } else {
        format!("{}/{path}", base.trim_end_matches('/'))
    }
}

/// The children of the file's `<tag>` section, as text.
fn children_xml(root: Node<'_, '_>, tag: &str) -> String {
    child(root, tag)
        .map(|s| {
            s.children()
                .filter(Node::is_element)
                .map(|n| copy(n, 0, &mut |_, _| {}))
                .collect()
        })
        .unwrap_or_default()
}

/// Every body name of the file.
fn body_names(root: Node<'_, '_>) -> Vec<String> {
    root.descendants()
        .filter(|n| n.has_tag_name("body"))
        .filter_map(|n| n.attribute("name").map(str::to_string))
        .collect()
}

/// `link`'s name, or its nearest ancestor's that the file has as a body (a file may leave
/// out frame-only links such as fingertips).
fn present_link(model: &HandModel, link: LinkId, bodies: &[String]) -> String {
    let mut current = link;
    loop {
        let name = &model.ros_link_names()[current.index()];
        if bodies.contains(name) {
            return name.clone();
        }
        match model.joints().iter().find(|j| j.child == current) {
            Some(joint) => current = joint.parent,
            None => return name.clone(),
        }
    }
}
