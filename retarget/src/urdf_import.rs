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
    let robot = urdf_rs::read_from_string(urdf).map_err(|e| Error::Urdf {
        reason: e.to_string(),
    })?;
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
    Ok((
        ModelSpec {
            name: robot.name,
            frames: import.frames.clone(),
            joints,
        },
        links,
    ))
}
