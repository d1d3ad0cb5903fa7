//! Importing a hand from any URDF (parsed by the `urdf-rs` crate) into a [`HandModel`].
//!
//! Supported joint types: revolute, continuous (limits `[-π, π]`) and fixed; `<mimic>`
//! becomes a linear coupling. Other types are rejected by name. Frames are named by link, after
//! an optional name prefix (such as `right_`) is stripped from every joint and link name, so a
//! right-hand URDF yields orca_core joint names.

use crate::error::Error;
use crate::hand_model::HandModel;
use crate::model_spec::{CouplingSpec, FrameSpec, JointKindSpec, JointSpec, ModelSpec};

/// How to read a URDF as a hand.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UrdfImport {
    /// Prefix removed from joint and link names where present (`""` for none).
    pub strip_prefix: String,
    /// Link names (after stripping) of the frames the station needs.
    pub frames: FrameSpec,
}

impl HandModel {
    /// Parse a URDF document and build the hand model.
    pub fn from_urdf_str(urdf: &str, import: &UrdfImport) -> Result<HandModel, Error> {
        let (spec, links) = spec_from_urdf(urdf, import)?;
        crate::model_build::build(&spec, Some(&links))
    }
}

/// Convert a URDF document to the project's model description and its declared links.
pub fn spec_from_urdf(urdf: &str, import: &UrdfImport) -> Result<(ModelSpec, Vec<String>), Error> {
    let robot = urdf_rs::read_from_string(urdf).map_err(|e| locate_urdf_error(urdf, &e))?;
    let strip = |name: &str| {
        name.strip_prefix(import.strip_prefix.as_str())
            .unwrap_or(name)
            .to_string()
    };
    let mut joints = Vec::with_capacity(robot.joints.len());
    for j in &robot.joints {
        let name = strip(&j.name);
        let kind = match j.joint_type {
            urdf_rs::JointType::Revolute => JointKindSpec::Revolute,
            urdf_rs::JointType::Continuous => JointKindSpec::Continuous,
            urdf_rs::JointType::Fixed => JointKindSpec::Fixed,
            ref other => {
                return Err(Error::UnsupportedJointType {
                    joint: name,
                    kind: format!("{other:?}").to_lowercase(),
                });
            }
        };
        let moving = kind != JointKindSpec::Fixed;
        let limited = kind == JointKindSpec::Revolute;
        joints.push(JointSpec {
            name,
            kind,
            parent: strip(&j.parent.link),
            child: strip(&j.child.link),
            xyz_m: j.origin.xyz.0,
            rpy_rad: j.origin.rpy.0,
            axis: moving.then_some(j.axis.xyz.0),
            lower_rad: limited.then_some(j.limit.lower),
            upper_rad: limited.then_some(j.limit.upper),
            coupled: j.mimic.as_ref().filter(|_| moving).map(|m| CouplingSpec {
                joint: strip(&m.joint),
                multiplier: m.multiplier.unwrap_or(1.0),
                offset_rad: m.offset.unwrap_or(0.0),
            }),
        });
    }
    let links = robot.links.iter().map(|l| strip(&l.name)).collect();
    let originals = robot.joints.iter().map(|j| &j.name);
    let source_names = originals
        .chain(robot.links.iter().map(|l| &l.name))
        .map(|name| (strip(name), name.clone()))
        .collect();
    Ok((
        ModelSpec {
            name: robot.name,
            name_prefix: import.strip_prefix.clone(),
            source_names,
            frames: import.frames.clone(),
            joints,
        },
        links,
    ))
}

/// Turn the URDF parser's message (which names a field but not the element) into one that
/// names the element: XML syntax errors carry their position; otherwise each `<joint>` and
/// `<link>` is parsed alone until the faulty one is found.
fn locate_urdf_error(urdf: &str, error: &urdf_rs::UrdfError) -> Error {
    let clean = |e: &urdf_rs::UrdfError| {
        let text = e.to_string();
        text.strip_prefix("custom: ").unwrap_or(&text).to_string()
    };
    let doc = match roxmltree::Document::parse(urdf) {
        Ok(doc) => doc,
        Err(xml) => {
            return Error::Urdf {
                reason: format!("not well-formed XML: {xml}"),
            };
        }
    };
    let elements = doc
        .root_element()
        .children()
        .filter(|n| matches!(n.tag_name().name(), "joint" | "link"));
    for node in elements {
        let alone = format!("<robot name=\"probe\">{}</robot>", &urdf[node.range()]);
        if let Err(e) = urdf_rs::read_from_string(&alone) {
            return Error::UrdfElement {
                element: format!(
                    "{} '{}'",
                    node.tag_name().name(),
                    node.attribute("name").unwrap_or("?")
                ),
                line: doc.text_pos_at(node.range().start).row,
                reason: clean(&e),
            };
        }
    }
    Error::Urdf {
        reason: clean(error),
    }
}
