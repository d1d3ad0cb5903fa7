//! Validation of a [`ModelSpec`] into a [`HandModel`]: tree structure, numbers, couplings,
//! named frames. Every rejection names the joint, link or frame at fault.

use std::collections::{HashMap, HashSet, VecDeque};

use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

use crate::error::Error;
use crate::hand_model::{Dof, HandModel, Joint, JointMotion, Limits, LinkId, NamedFrames};
use crate::model_spec::{FrameSpec, JointKindSpec, JointSpec, ModelSpec};

impl HandModel {
    /// Validate a model description and build the model.
    pub fn from_spec(spec: &ModelSpec) -> Result<HandModel, Error> {
        build(spec, None)
    }
}

/// Build a model; `declared_links` (URDF `<link>` names) are checked against the joints.
pub(crate) fn build(
    spec: &ModelSpec,
    declared_links: Option<&[String]>,
) -> Result<HandModel, Error> {
    if spec.joints.is_empty() {
        return Err(Error::NoJoints);
    }
    check_names(spec, declared_links)?;
    let tree = Tree::new(spec, declared_links)?;

    // Degrees of freedom: uncoupled revolute joints in declaration order.
    let mut dof_of_joint: HashMap<&str, usize> = HashMap::new();
    let mut dofs = Vec::new();
    for (i, j) in spec.joints.iter().enumerate() {
        check_numbers(j)?;
        if j.kind != JointKindSpec::Fixed && j.coupled.is_none() {
            dof_of_joint.insert(j.name.as_str(), dofs.len());
            dofs.push(Dof {
                name: j.name.clone(),
                joint: i, // spec index for now; remapped to topological index below
                limits: joint_limits(j)?,
            });
        }
    }

    let mut joints = Vec::with_capacity(spec.joints.len());
    let mut topo_index = vec![0; spec.joints.len()];
    for &spec_index in &tree.joint_order {
        let j = &spec.joints[spec_index];
        topo_index[spec_index] = joints.len();
        joints.push(Joint {
            name: j.name.clone(),
            parent: LinkId(tree.link_id[j.parent.as_str()]),
            child: LinkId(tree.link_id[j.child.as_str()]),
            origin: origin(j),
            motion: motion(j, spec, &dof_of_joint, &mut dofs)?,
        });
    }
    for dof in &mut dofs {
        dof.joint = topo_index[dof.joint];
    }

    let mut chains: Vec<Vec<usize>> = vec![Vec::new(); tree.link_names.len()];
    for (ji, joint) in joints.iter().enumerate() {
        let mut chain = chains[joint.parent.0].clone();
        if matches!(joint.motion, JointMotion::Revolute { .. }) {
            chain.push(ji);
        }
        chains[joint.child.0] = chain;
    }

    let published = |name: &str, root: bool| match spec.source_names.get(name) {
        Some(original) => original.clone(),
        None if root => name.to_string(),
        None => format!("{}{name}", spec.name_prefix),
    };
    let model = HandModel {
        name: spec.name.clone(),
        name_prefix: spec.name_prefix.clone(),
        ros_dof_names: dofs.iter().map(|d| published(&d.name, false)).collect(),
        ros_link_names: (tree.link_names.iter().enumerate())
            .map(|(i, name)| published(name, i == 0))
            .collect(),
        frames: named_frames(&spec.frames, &tree.link_id)?,
        link_names: tree.link_names,
        joints,
        dofs,
        chains,
    };
    model.check_palm_frame()?;
    Ok(model)
}

fn check_names(spec: &ModelSpec, declared_links: Option<&[String]>) -> Result<(), Error> {
    let mut seen = HashSet::new();
    for j in &spec.joints {
        if !seen.insert(j.name.as_str()) {
            return Err(Error::DuplicateJoint {
                joint: j.name.clone(),
            });
        }
        if j.parent == j.child {
            return Err(Error::SelfLoop {
                joint: j.name.clone(),
                link: j.parent.clone(),
            });
        }
        if let Some(declared) = declared_links {
            for (role, link) in [("parent", &j.parent), ("child", &j.child)] {
                if !declared.contains(link) {
                    return Err(Error::UndeclaredLink {
                        joint: j.name.clone(),
                        role,
                        link: link.clone(),
                    });
                }
            }
        }
    }
    Ok(())
}

/// The link tree: links in breadth-first order from the root, joints in the same order.
struct Tree<'a> {
    link_names: Vec<String>,
    link_id: HashMap<&'a str, usize>,
    joint_order: Vec<usize>,
}

impl<'a> Tree<'a> {
    fn new(spec: &'a ModelSpec, declared_links: Option<&'a [String]>) -> Result<Self, Error> {
        let mut all_links: Vec<&str> = Vec::new();
        let mut add = |name: &'a str| {
            if !all_links.contains(&name) {
                all_links.push(name);
            }
        };
        for l in declared_links.unwrap_or(&[]) {
            add(l);
        }
        for j in &spec.joints {
            add(&j.parent);
            add(&j.child);
        }

        let mut parent_joint: HashMap<&str, usize> = HashMap::new();
        let mut children: HashMap<&str, Vec<usize>> = HashMap::new();
        for (i, j) in spec.joints.iter().enumerate() {
            if let Some(&first) = parent_joint.get(j.child.as_str()) {
                return Err(Error::TwoParents {
                    link: j.child.clone(),
                    first: spec.joints[first].name.clone(),
                    second: j.name.clone(),
                });
            }
            parent_joint.insert(&j.child, i);
            children.entry(&j.parent).or_default().push(i);
        }

        let roots: Vec<&str> = all_links
            .iter()
            .copied()
            .filter(|l| !parent_joint.contains_key(l))
            .collect();
        let [root] = roots[..] else {
            return Err(Error::RootCount {
                roots: roots.iter().map(|r| r.to_string()).collect(),
            });
        };

        let mut link_names = vec![root.to_string()];
        let mut link_id = HashMap::from([(root, 0)]);
        let mut joint_order = Vec::with_capacity(spec.joints.len());
        let mut queue = VecDeque::from([root]);
        while let Some(link) = queue.pop_front() {
            for &ji in children.get(link).map(Vec::as_slice).unwrap_or(&[]) {
                let child = spec.joints[ji].child.as_str();
                link_id.insert(child, link_names.len());
                link_names.push(child.to_string());
                joint_order.push(ji);
                queue.push_back(child);
            }
        }
        if link_names.len() != all_links.len() {
            let links = all_links
                .iter()
                .filter(|l| !link_id.contains_key(*l))
                .map(|l| l.to_string())
                .collect();
            return Err(Error::Cycle {
                root: root.to_string(),
                links,
            });
        }
        Ok(Tree {
            link_names,
            link_id,
            joint_order,
        })
    }
}

/// Largest joint offset a hand model may hold, metres (a hand is well under one metre; the
/// bound catches unit errors and keeps the forward kinematics finite).
const MAX_OFFSET_M: f64 = 10.0;
/// Largest angle (rpy, limits, coupling offset), radians: one turn, with rounding slack.
const MAX_ANGLE_RAD: f64 = std::f64::consts::TAU + 1e-6;
/// Largest axis component before normalisation.
const MAX_AXIS: f64 = 1e3;
/// Largest coupling multiplier.
const MAX_MULTIPLIER: f64 = 100.0;

/// Every number of `j` finite and within the range a hand model can hold.
fn check_numbers(j: &JointSpec) -> Result<(), Error> {
    let angle = (MAX_ANGLE_RAD, "[-2π, 2π] rad");
    let fields = [
        ("xyz_m", &j.xyz_m[..], (MAX_OFFSET_M, "[-10, 10] m")),
        ("rpy_rad", &j.rpy_rad[..], angle),
    ]
    .into_iter()
    .chain(
        j.axis
            .as_ref()
            .map(|a| ("axis", &a[..], (MAX_AXIS, "[-1000, 1000]"))),
    )
    .chain(
        j.lower_rad
            .as_ref()
            .map(|v| ("lower_rad", std::slice::from_ref(v), angle)),
    )
    .chain(
        j.upper_rad
            .as_ref()
            .map(|v| ("upper_rad", std::slice::from_ref(v), angle)),
    )
    .chain(j.coupled.iter().flat_map(|c| {
        [
            (
                "multiplier",
                std::slice::from_ref(&c.multiplier),
                (MAX_MULTIPLIER, "[-100, 100]"),
            ),
            ("offset_rad", std::slice::from_ref(&c.offset_rad), angle),
        ]
    }));
    for (field, values, (max, allowed)) in fields {
        for &value in values {
            if !value.is_finite() {
                return Err(Error::NonFinite {
                    joint: j.name.clone(),
                    field,
                    value,
                });
            }
            if value.abs() > max {
                return Err(Error::OutOfRange {
                    joint: j.name.clone(),
                    field,
                    value,
                    allowed,
                });
            }
        }
    }
    Ok(())
}

fn joint_limits(j: &JointSpec) -> Result<Limits, Error> {
    if j.kind == JointKindSpec::Continuous {
        return Ok(Limits {
            lower_rad: -std::f64::consts::PI,
            upper_rad: std::f64::consts::PI,
        });
    }
    let missing = |field| Error::MissingField {
        joint: j.name.clone(),
        field,
    };
    let lower = j.lower_rad.ok_or_else(|| missing("lower_rad"))?;
    let upper = j.upper_rad.ok_or_else(|| missing("upper_rad"))?;
    if lower >= upper {
        return Err(Error::InvalidLimits {
            joint: j.name.clone(),
            lower,
            upper,
        });
    }
    Ok(Limits {
        lower_rad: lower,
        upper_rad: upper,
    })
}

fn origin(j: &JointSpec) -> Isometry3<f64> {
    let [x, y, z] = j.xyz_m;
    let [roll, pitch, yaw] = j.rpy_rad;
    // URDF rpy: R = Rz(yaw) · Ry(pitch) · Rx(roll), which is nalgebra's euler convention.
    Isometry3::from_parts(
        Translation3::new(x, y, z),
        UnitQuaternion::from_euler_angles(roll, pitch, yaw),
    )
}

fn motion(
    j: &JointSpec,
    spec: &ModelSpec,
    dof_of_joint: &HashMap<&str, usize>,
    dofs: &mut [Dof],
) -> Result<JointMotion, Error> {
    if j.kind == JointKindSpec::Fixed {
        for (field, present) in [
            ("axis", j.axis.is_some()),
            ("lower_rad", j.lower_rad.is_some()),
            ("upper_rad", j.upper_rad.is_some()),
            ("coupled", j.coupled.is_some()),
        ] {
            if present {
                return Err(Error::FixedJointField {
                    joint: j.name.clone(),
                    field,
                });
            }
        }
        return Ok(JointMotion::Fixed);
    }
    let raw_axis = j.axis.ok_or_else(|| Error::MissingField {
        joint: j.name.clone(),
        field: "axis",
    })?;
    let axis = Unit::try_new(Vector3::from(raw_axis), 1e-9).ok_or_else(|| Error::ZeroAxis {
        joint: j.name.clone(),
        axis: raw_axis,
    })?;
    let limits = joint_limits(j)?;
    let Some(coupling) = &j.coupled else {
        return Ok(JointMotion::Revolute {
            axis,
            dof: dof_of_joint[j.name.as_str()],
            multiplier: 1.0,
            offset_rad: 0.0,
            limits,
        });
    };
    let bad = |problem| Error::BadCoupling {
        joint: j.name.clone(),
        target: coupling.joint.clone(),
        problem,
    };
    let Some(&dof) = dof_of_joint.get(coupling.joint.as_str()) else {
        let exists = spec.joints.iter().any(|o| o.name == coupling.joint);
        return Err(bad(if exists {
            "is fixed or itself coupled"
        } else {
            "is not a joint of the model"
        }));
    };
    if coupling.multiplier == 0.0 {
        return Err(bad("has multiplier 0 (use a fixed joint instead)"));
    }
    // Fold this joint's limits into the driving degree of freedom's bounds.
    let k = coupling.multiplier;
    let (a, b) = (
        (limits.lower_rad - coupling.offset_rad) / k,
        (limits.upper_rad - coupling.offset_rad) / k,
    );
    let dof_limits = &mut dofs[dof].limits;
    dof_limits.lower_rad = dof_limits.lower_rad.max(a.min(b));
    dof_limits.upper_rad = dof_limits.upper_rad.min(a.max(b));
    if dof_limits.lower_rad >= dof_limits.upper_rad {
        return Err(bad(
            "cannot move: the two joints' limits leave no common range",
        ));
    }
    Ok(JointMotion::Revolute {
        axis,
        dof,
        multiplier: k,
        offset_rad: coupling.offset_rad,
        limits,
    })
}

fn named_frames(frames: &FrameSpec, link_id: &HashMap<&str, usize>) -> Result<NamedFrames, Error> {
    let mut ids = [LinkId(0); 12];
    for (slot, (frame, link)) in ids.iter_mut().zip(frames.entries()) {
        *slot = link_id
            .get(link)
            .map(|&i| LinkId(i))
            .ok_or_else(|| Error::MissingFrame {
                frame: frame.to_string(),
                link: link.to_string(),
            })?;
    }
    let [palm, wrist, b0, b1, b2, b3, b4, t0, t1, t2, t3, t4] = ids;
    let given = frames
        .mid_entries()
        .iter()
        .filter(|(_, l)| l.is_some())
        .count();
    let mids =
        match given {
            0 => None,
            5 => {
                let mut mids = [LinkId(0); 5];
                for (slot, (frame, link)) in mids.iter_mut().zip(frames.mid_entries()) {
                    let link = link.unwrap_or_default();
                    *slot = link_id.get(link).map(|&i| LinkId(i)).ok_or_else(|| {
                        Error::MissingFrame {
                            frame: frame.to_string(),
                            link: link.to_string(),
                        }
                    })?;
                }
                Some(mids)
            }
            _ => {
                return Err(Error::MissingFrame {
                    frame: "thumb_mid .. little_mid".into(),
                    link: format!("only {given} of the 5 given (name all five or none)"),
                });
            }
        };
    Ok(NamedFrames {
        palm,
        wrist,
        bases: [b0, b1, b2, b3, b4],
        tips: [t0, t1, t2, t3, t4],
        mids,
    })
}
