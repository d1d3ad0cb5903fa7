//! Importing a hand from any URDF (read by [`crate::urdf_reader`]) into a [`HandModel`].
//!
//! Supported joint types: revolute, continuous (limits `[-π, π]`) and fixed; `<mimic>`
//! becomes a linear coupling. Other types are rejected by name. Frames are named by link, after
//! an optional name prefix (such as `right_`) is stripped from every joint and link name, so a
//! right-hand URDF yields orca_core joint names.

use crate::error::Error;
use crate::hand_model::HandModel;
use crate::model_spec::{CouplingSpec, FrameSpec, JointKindSpec, JointSpec, ModelSpec};
use crate::urdf_reader::read_urdf;

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
    let robot = read_urdf(urdf)?;
    let strip = |name: &str| {
        name.strip_prefix(import.strip_prefix.as_str())
            .unwrap_or(name)
            .to_string()
    };
    let mut joints = Vec::with_capacity(robot.joints.len());
    for j in &robot.joints {
        let name = strip(&j.name);
        let kind = match j.kind.as_str() {
            "revolute" => JointKindSpec::Revolute,
            "continuous" => JointKindSpec::Continuous,
            "fixed" => JointKindSpec::Fixed,
            other => {
                return Err(Error::UnsupportedJointType {
                    joint: name,
                    kind: other.to_string(),
                });
            }
        };
        let moving = kind != JointKindSpec::Fixed;
        let limited = kind == JointKindSpec::Revolute;
        joints.push(JointSpec {
            name,
            kind,
            parent: strip(&j.parent),
            child: strip(&j.child),
            xyz_m: j.xyz_m,
            rpy_rad: j.rpy_rad,
            axis: moving.then_some(j.axis),
            lower_rad: limited.then_some(j.lower_rad),
            upper_rad: limited.then_some(j.upper_rad),
            coupled: j.mimic.as_ref().filter(|_| moving).map(|m| CouplingSpec {
                joint: strip(&m.joint),
                multiplier: m.multiplier,
                offset_rad: m.offset_rad,
            }),
        });
    }
    let links = robot.links.iter().map(|l| strip(l)).collect();
    let originals = robot.joints.iter().map(|j| &j.name);
    let source_names = originals
        .chain(robot.links.iter())
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
