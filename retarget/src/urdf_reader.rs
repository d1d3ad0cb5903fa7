//! Reading what a hand model needs of a URDF document: its links, and each joint's type,
//! parent and child links, origin, axis, limits and `<mimic>` (with roxmltree). Everything
//! else (visuals, collisions, inertials, transmissions, Gazebo tags) is skipped unread.
//!
//! The URDF conventions: an absent `<origin>` is the identity, an absent `<axis>` is
//! `1 0 0`, `<limit>`'s `lower` and `upper` default to 0 while `effort` and `velocity` are
//! required, `<mimic>`'s `multiplier` defaults to 1 and `offset` to 0. A problem with one
//! `<joint>` or `<link>` names the element (`joint 'index_mcp'`), the line of its start tag and
//! what is wrong with it.

use roxmltree::{Document, Node};

use crate::error::Error;

/// The links and joints of a URDF document, names as written.
#[derive(Debug, Clone, PartialEq)]
pub struct UrdfRobot {
    /// `<robot name=…>`.
    pub name: String,
    /// Every `<link>`'s name, in document order.
    pub links: Vec<String>,
    /// Every `<joint>`, in document order.
    pub joints: Vec<UrdfJoint>,
}

/// One `<joint>`.
#[derive(Debug, Clone, PartialEq)]
pub struct UrdfJoint {
    /// `name`.
    pub name: String,
    /// `type`, as written (`revolute`, `continuous`, `fixed`, `prismatic`, ...).
    pub kind: String,
    /// `<parent link=…>`.
    pub parent: String,
    /// `<child link=…>`.
    pub child: String,
    /// `<origin xyz=…>`, metres.
    pub xyz_m: [f64; 3],
    /// `<origin rpy=…>`, radians.
    pub rpy_rad: [f64; 3],
    /// `<axis xyz=…>`.
    pub axis: [f64; 3],
    /// `<limit lower=… upper=…>`, radians (0 and 0 without the element).
    pub lower_rad: f64,
    /// See `lower_rad`.
    pub upper_rad: f64,
    /// `<mimic>`, if any.
    pub mimic: Option<UrdfMimic>,
}

/// A `<mimic joint=… multiplier=… offset=…>`.
#[derive(Debug, Clone, PartialEq)]
pub struct UrdfMimic {
    /// The joint followed.
    pub joint: String,
    /// This joint = multiplier · followed + offset.
    pub multiplier: f64,
    /// Radians.
    pub offset_rad: f64,
}

/// Parse `text` as a URDF document.
pub fn read_urdf(text: &str) -> Result<UrdfRobot, Error> {
    let doc = Document::parse(text).map_err(|xml| Error::Urdf {
        reason: format!("not well-formed XML: {xml}"),
    })?;
    let root = doc.root_element();
    if root.tag_name().name() != "robot" {
        return Err(Error::Urdf {
            reason: format!(
                "the root element is <{}>, not <robot>",
                root.tag_name().name()
            ),
        });
    }
    let name = root.attribute("name").ok_or_else(|| Error::Urdf {
        reason: "<robot> has no `name` attribute".into(),
    })?;
    let mut robot = UrdfRobot {
        name: name.to_string(),
        links: Vec::new(),
        joints: Vec::new(),
    };
    for node in root.children().filter(Node::is_element) {
        let located = |reason| element_error(&doc, node, reason);
        match node.tag_name().name() {
            "link" => robot
                .links
                .push(attribute(node, "name").map_err(located)?.to_string()),
            "joint" => robot.joints.push(read_joint(node).map_err(located)?),
            _ => {}
        }
    }
    Ok(robot)
}

/// `reason` about `node`, named by its tag and `name` and located by line.
fn element_error(doc: &Document<'_>, node: Node<'_, '_>, reason: String) -> Error {
    Error::UrdfElement {
        element: format!(
            "{} '{}'",
            node.tag_name().name(),
            node.attribute("name").unwrap_or("?")
        ),
        line: doc.text_pos_at(node.range().start).row,
        reason,
    }
}

/// One `<joint>` element; `Err` says what is wrong with it.
fn read_joint(node: Node<'_, '_>) -> Result<UrdfJoint, String> {
    let origin = child(node, "origin");
    let limit = child(node, "limit");
    if let Some(limit) = limit {
        let missing: Vec<&str> = ["effort", "velocity"]
            .into_iter()
            .filter(|name| limit.attribute(*name).is_none())
            .collect();
        if !missing.is_empty() {
            return Err(format!(
                "<limit> lacks the required `{}`",
                missing.join("` and `")
            ));
        }
        number(limit, "effort", None)?;
        number(limit, "velocity", None)?;
    }
    Ok(UrdfJoint {
        name: attribute(node, "name")?.to_string(),
        kind: attribute(node, "type")?.to_string(),
        parent: link_of(node, "parent")?,
        child: link_of(node, "child")?,
        xyz_m: triple(origin, "xyz", [0.0; 3])?,
        rpy_rad: triple(origin, "rpy", [0.0; 3])?,
        axis: triple(child(node, "axis"), "xyz", [1.0, 0.0, 0.0])?,
        lower_rad: limit.map_or(Ok(0.0), |l| number(l, "lower", Some(0.0)))?,
        upper_rad: limit.map_or(Ok(0.0), |l| number(l, "upper", Some(0.0)))?,
        mimic: child(node, "mimic").map(read_mimic).transpose()?,
    })
}

/// A `<mimic>` element.
fn read_mimic(node: Node<'_, '_>) -> Result<UrdfMimic, String> {
    Ok(UrdfMimic {
        joint: attribute(node, "joint")?.to_string(),
        multiplier: number(node, "multiplier", Some(1.0))?,
        offset_rad: number(node, "offset", Some(0.0))?,
    })
}

/// The first child element of `node` named `tag`.
fn child<'a, 'input>(node: Node<'a, 'input>, tag: &str) -> Option<Node<'a, 'input>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == tag)
}

/// A required attribute.
fn attribute<'a>(node: Node<'a, '_>, name: &str) -> Result<&'a str, String> {
    node.attribute(name)
        .ok_or_else(|| format!("<{}> has no `{name}` attribute", node.tag_name().name()))
}

/// `<parent link=…/>` or `<child link=…/>` of a joint.
fn link_of(joint: Node<'_, '_>, role: &str) -> Result<String, String> {
    let element = child(joint, role).ok_or_else(|| format!("no <{role} link=\"…\"/> element"))?;
    Ok(attribute(element, "link")?.to_string())
}

/// A number attribute of `node`: `default` when absent, required when `default` is `None`.
fn number(node: Node<'_, '_>, name: &str, default: Option<f64>) -> Result<f64, String> {
    match (node.attribute(name), default) {
        (Some(text), _) => text.trim().parse().map_err(|_| {
            format!(
                "`{name}` of <{}> is not a number: {text:?}",
                node.tag_name().name()
            )
        }),
        (None, Some(value)) => Ok(value),
        (None, None) => Err(format!(
            "<{}> has no `{name}` attribute",
            node.tag_name().name()
        )),
    }
}

/// Three numbers separated by white space in attribute `name` of `node`; `default` when the
/// element or the attribute is absent.
fn triple(node: Option<Node<'_, '_>>, name: &str, default: [f64; 3]) -> Result<[f64; 3], String> {
    let Some((node, text)) = node.and_then(|n| n.attribute(name).map(|t| (n, t))) else {
        return Ok(default);
    };
    let invalid = || {
        format!(
            "`{name}` of <{}> is not three numbers: {text:?}",
            node.tag_name().name()
        )
    };
    let values: Vec<f64> = text
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|_| invalid())?;
    <[f64; 3]>::try_from(values).map_err(|_| invalid())
}

#[cfg(test)]
mod tests {
    use super::*;

    const ROBOT: &str = r#"<?xml version="1.0"?>
<robot name="two">
  <link name="palm"><visual><geometry><box size="1 1 1"/></geometry></visual></link>
  <link name="tip"/>
  <joint name="flex" type="revolute">
    <parent link="palm"/><child link="tip"/>
    <origin xyz="0 0 0.04" rpy="0.1 0 -0.2"/><axis xyz="0 1 0"/>
    <limit lower="-0.5" upper="1.5" effort="1" velocity="2"/>
  </joint>
  <joint name="follow" type="continuous"><parent link="tip"/><child link="palm"/>
    <mimic joint="flex" multiplier="0.5"/></joint>
  <transmission name="ignored"/>
</robot>"#;

    #[test]
    fn links_joints_and_their_defaults_are_read() {
        let robot = read_urdf(ROBOT).unwrap();
        assert_eq!(robot.name, "two");
        assert_eq!(robot.links, ["palm", "tip"]);
        let flex = &robot.joints[0];
        assert_eq!(
            (flex.kind.as_str(), flex.parent.as_str()),
            ("revolute", "palm")
        );
        assert_eq!(flex.xyz_m, [0.0, 0.0, 0.04]);
        assert_eq!(flex.rpy_rad, [0.1, 0.0, -0.2]);
        assert_eq!(flex.axis, [0.0, 1.0, 0.0]);
        assert_eq!((flex.lower_rad, flex.upper_rad), (-0.5, 1.5));
        let follow = &robot.joints[1];
        assert_eq!(follow.xyz_m, [0.0; 3]);
        assert_eq!(follow.axis, [1.0, 0.0, 0.0]);
        assert_eq!((follow.lower_rad, follow.upper_rad), (0.0, 0.0));
        let mimic = follow.mimic.as_ref().unwrap();
        assert_eq!(
            (mimic.joint.as_str(), mimic.multiplier, mimic.offset_rad),
            ("flex", 0.5, 0.0)
        );
    }

    #[test]
    fn a_bad_element_is_named_with_its_line() {
        let bad = ROBOT.replace(r#"xyz="0 0 0.04""#, r#"xyz="0 0""#);
        let e = read_urdf(&bad).unwrap_err().to_string();
        assert!(
            e.contains("joint 'flex' (line 5)") && e.contains("three numbers"),
            "{e}"
        );
        let bad = ROBOT.replace(r#" effort="1""#, "");
        let e = read_urdf(&bad).unwrap_err().to_string();
        assert!(
            e.contains("joint 'flex'") && e.contains("lacks the required `effort`"),
            "{e}"
        );
        let bad = ROBOT.replace(r#" effort="1" velocity="2""#, "");
        let e = read_urdf(&bad).unwrap_err().to_string();
        assert!(e.contains("`effort` and `velocity`"), "{e}");
        let bad = ROBOT.replace(r#"<link name="tip"/>"#, "<link/>");
        let e = read_urdf(&bad).unwrap_err().to_string();
        assert!(
            e.contains("link '?' (line 4)") && e.contains("`name`"),
            "{e}"
        );
    }

    #[test]
    fn a_document_that_is_no_robot_is_an_error() {
        for (text, words) in [
            ("<robot", "not well-formed XML"),
            ("<model name=\"x\"/>", "<model>, not <robot>"),
            ("<robot/>", "no `name`"),
        ] {
            let e = read_urdf(text).unwrap_err().to_string();
            assert!(e.contains(words), "{text}: {e}");
        }
    }
}
