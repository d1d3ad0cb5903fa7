//! The hand as MJCF: names, ranges, couplings, contact bits and the kinematics of the written
//! body tree against the model's.

use std::collections::{HashMap, HashSet};

use nalgebra::Quaternion;
use retarget::ModelSpec;
use retarget::model_spec::CouplingSpec;
use roxmltree::{Document, Node};

use super::*;

/// The fragments assembled the way a scene does.
fn scene(hand: &HandMjcf) -> String {
    format!(
        "<mujoco><default>{}</default><worldbody><body name=\"mount\">{}</body></worldbody>\
         <actuator>{}</actuator><equality>{}</equality><contact>{}</contact></mujoco>",
        hand.defaults, hand.body, hand.actuators, hand.equalities, hand.contact_excludes
    )
}

fn floats(node: Node, attribute: &str) -> Vec<f64> {
    node.attribute(attribute)
        .unwrap_or_else(|| panic!("{attribute} missing on {node:?}"))
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect()
}

fn elements<'a>(doc: &'a Document, tag: &str) -> Vec<Node<'a, 'a>> {
    doc.descendants().filter(|n| n.has_tag_name(tag)).collect()
}

fn named<'a>(nodes: &[Node<'a, 'a>], name: &str) -> Vec<Node<'a, 'a>> {
    (nodes.iter().copied())
        .filter(|n| n.attribute("name") == Some(name))
        .collect()
}

fn orca_coupled() -> HandModel {
    let mut spec = ModelSpec::from_toml_str(retarget::ORCA_V1_RIGHT_TOML).unwrap();
    let pip = spec
        .joints
        .iter_mut()
        .find(|j| j.name == "index_pip")
        .unwrap();
    pip.coupled = Some(CouplingSpec {
        joint: "index_mcp".into(),
        multiplier: 1.1,
        offset_rad: 0.05,
    });
    HandModel::from_spec(&spec).unwrap()
}

#[test]
fn every_dof_has_a_hinge_and_an_actuator_with_its_limits() {
    let model = HandModel::orca_v1_right();
    let hand = hand_mjcf(&model, &HandMjcfOptions::default());
    let text = scene(&hand);
    let doc = Document::parse(&text).unwrap();
    let (joints, actuators) = (elements(&doc, "joint"), elements(&doc, "position"));
    assert_eq!(hand.dof_joints, model.ros_dof_names());
    assert_eq!(hand.dof_actuators, model.ros_dof_names());
    assert_eq!(hand.dof_joints[0], "right_thumb_mcp");
    // One position default, then one actuator per degree of freedom in dofs() order.
    let in_order: Vec<&str> = actuators[1..]
        .iter()
        .filter_map(|a| a.attribute("name"))
        .collect();
    assert_eq!(in_order, hand.dof_actuators);
    for (dof, name) in model.dofs().iter().zip(&hand.dof_joints) {
        let limits = vec![dof.limits.lower_rad, dof.limits.upper_rad];
        let [joint] = named(&joints, name)[..] else {
            panic!("one hinge {name}")
        };
        assert_eq!(joint.attribute("type"), Some("hinge"));
        assert_eq!(floats(joint, "range"), limits, "{name}");
        let [actuator] = named(&actuators, name)[..] else {
            panic!("one actuator {name}")
        };
        assert_eq!(actuator.attribute("joint"), Some(name.as_str()));
        assert_eq!(actuator.attribute("class"), Some(HAND_CLASS));
        assert_eq!(floats(actuator, "ctrlrange"), limits, "{name}");
    }
    assert_eq!(hand.equalities, "");
    assert_eq!(
        hand.max_speed_rad_s,
        HandMjcfOptions::default().max_speed_rad_s
    );
}

#[test]
fn bodies_are_the_ros_links_with_the_root_renamed() {
    let model = HandModel::orca_v1_right();
    let hand = hand_mjcf(&model, &HandMjcfOptions::default());
    let text = scene(&hand);
    let doc = Document::parse(&text).unwrap();
    let bodies = elements(&doc, "body");
    let names: Vec<&str> = bodies[1..]
        .iter()
        .filter_map(|b| b.attribute("name"))
        .collect();
    assert_eq!(names.len(), model.link_count());
    assert_eq!(names.iter().collect::<HashSet<_>>().len(), names.len());
    assert_eq!(hand.root_body, "orca_v1_right_root");
    assert_eq!(names[0], hand.root_body);
    assert_eq!(bodies[1].attribute("childclass"), Some(HAND_CLASS));
    for link in &model.ros_link_names()[1..] {
        assert!(names.contains(&link.as_str()), "{link}");
    }
    assert_eq!(hand.palm_body, "right_palm");
    assert_eq!(hand.tip_bodies[0], "right_thumb_fingertip");
    assert_eq!(hand.tip_bodies[4], "right_pinky_fingertip");
    for body in hand.tip_bodies.iter().chain([&hand.palm_body]) {
        assert_eq!(named(&bodies, body).len(), 1, "{body}");
    }
    // Every hinged body carries geometry of its own (MuJoCo needs its mass).
    for joint in elements(&doc, "joint")
        .iter()
        .filter(|j| j.attribute("name").is_some())
    {
        let body = joint.parent().unwrap();
        assert!(body.children().any(|n| n.has_tag_name("geom")), "{body:?}");
    }
}

#[test]
fn coupled_joints_are_hinges_held_on_their_driver() {
    let model = orca_coupled();
    let hand = hand_mjcf(&model, &HandMjcfOptions::default());
    let text = scene(&hand);
    let doc = Document::parse(&text).unwrap();
    assert_eq!(hand.dof_joints.len(), 16);
    assert!(!hand.dof_joints.contains(&"right_index_pip".to_string()));
    let [hinge] = named(&elements(&doc, "joint"), "right_index_pip")[..] else {
        panic!("one hinge for the coupled joint")
    };
    assert_eq!(floats(hinge, "range"), vec![-0.34907, 1.88496]);
    assert!(named(&elements(&doc, "position"), "right_index_pip").is_empty());
    let [equality] = named(&elements(&doc, "joint"), "right_index_pip_coupling")[..] else {
        panic!("one equality: {}", hand.equalities)
    };
    assert_eq!(equality.parent().unwrap().tag_name().name(), "equality");
    assert_eq!(equality.attribute("joint1"), Some("right_index_pip"));
    assert_eq!(equality.attribute("joint2"), Some("right_index_mcp"));
    assert_eq!(floats(equality, "polycoef"), vec![0.05, 1.1, 0.0, 0.0, 0.0]);
}

/// Body positions by name in the hand root's frame: each body's pos/quat, then its hinge
/// turned by `q` (by joint name), as MuJoCo composes them.
fn body_positions(mount: Node, q: &HashMap<String, f64>) -> HashMap<String, Vector3<f64>> {
    fn walk(
        node: Node,
        parent: Isometry3<f64>,
        q: &HashMap<String, f64>,
        out: &mut HashMap<String, Vector3<f64>>,
    ) {
        for body in node.children().filter(|n| n.has_tag_name("body")) {
            let p = body
                .attribute("pos")
                .map_or(vec![0.0; 3], |_| floats(body, "pos"));
            let r = body
                .attribute("quat")
                .map_or(vec![1.0, 0.0, 0.0, 0.0], |_| floats(body, "quat"));
            let rotation = UnitQuaternion::from_quaternion(Quaternion::new(r[0], r[1], r[2], r[3]));
            let mut pose =
                parent * Isometry3::from_parts(Translation3::new(p[0], p[1], p[2]), rotation);
            if let Some(hinge) = body.children().find(|n| n.has_tag_name("joint")) {
                let a = floats(hinge, "axis");
                let axis = Unit::new_normalize(Vector3::new(a[0], a[1], a[2]));
                let angle = q[hinge.attribute("name").unwrap()];
                pose.rotation *= UnitQuaternion::from_axis_angle(&axis, angle);
            }
            out.insert(
                body.attribute("name").unwrap().to_string(),
                pose.translation.vector,
            );
            walk(body, pose, q, out);
        }
    }
    let mut out = HashMap::new();
    walk(mount, Isometry3::identity(), q, &mut out);
    out
}

#[test]
fn the_body_tree_reproduces_the_forward_kinematics() {
    let model = HandModel::orca_v1_right();
    let hand = hand_mjcf(&model, &HandMjcfOptions::default());
    let text = scene(&hand);
    let doc = Document::parse(&text).unwrap();
    let mount = named(&elements(&doc, "body"), "mount")[0];
    for k in 0..4 {
        let q: Vec<f64> = (model.dofs().iter().enumerate())
            .map(|(i, d)| {
                let t = ((i * 7 + k * 3) % 11) as f64 / 10.0;
                d.limits.lower_rad + t * (d.limits.upper_rad - d.limits.lower_rad)
            })
            .collect();
        let by_name = hand
            .dof_joints
            .iter()
            .cloned()
            .zip(q.iter().copied())
            .collect();
        let bodies = body_positions(mount, &by_name);
        let state = model.forward_new(&q).unwrap();
        for (finger, tip) in Finger::ALL.iter().zip(&hand.tip_bodies) {
            let expected = state.position(model.frames().tip(*finger)).coords;
            let error = (bodies[tip] - expected).norm();
            assert!(error < 1e-9, "{tip}: {error} m");
        }
    }
}

#[test]
fn the_mount_points_the_fingers_along_z_and_the_palm_along_x() {
    let model = HandModel::orca_v1_right();
    let options = HandMjcfOptions::default();
    let mount = hand_mjcf(&model, &options).mount;
    let rest = model.forward_new(&model.zero_pose()).unwrap();
    let frames = model.frames();
    let at = |state: &FkState, link: LinkId| mount * state.position(link);
    let along = (at(&rest, frames.tip(Finger::Middle)) - at(&rest, frames.palm)).normalize();
    assert!((along - Vector3::z()).norm() < 1e-9, "{along}");
    let wrist = at(&rest, frames.wrist);
    assert!(wrist.x.abs() < 1e-9 && wrist.y.abs() < 1e-9, "{wrist}");
    // Fingers flex towards the palmar side, +x (the splayed little finger partly sideways).
    let mut q = model.zero_pose();
    for name in ["index_mcp", "middle_mcp", "ring_mcp", "pinky_mcp"] {
        q[model.dof_index(name).unwrap()] = 1.0;
    }
    let flexed = model.forward_new(&q).unwrap();
    for finger in Finger::OPPOSING {
        let moved = at(&flexed, frames.tip(finger)) - at(&rest, frames.tip(finger));
        assert!(moved.x > 0.6 * moved.norm(), "{finger}: {moved}");
    }
    let tower = at(&rest, model.joint("tower_mount").unwrap().child);
    assert!(tower.z >= options.palm_radius_m - 1e-9, "{tower}");
}

#[test]
fn digits_collide_with_the_other_digits_and_the_world_only() {
    let collide = |a: Group, b: Group| {
        (a.contype() & b.conaffinity()) != 0 || (b.contype() & a.conaffinity()) != 0
    };
    let world = |g: Group| (g.contype() & WORLD_BIT) != 0 || (g.conaffinity() & WORLD_BIT) != 0;
    let groups: Vec<Group> = std::iter::once(Group::Palm)
        .chain((0..5).map(Group::Digit))
        .collect();
    for &a in &groups {
        assert!(world(a), "{a:?} touches objects");
        for &b in &groups {
            let expected = matches!((a, b), (Group::Digit(f), Group::Digit(g)) if f != g);
            assert_eq!(collide(a, b), expected, "{a:?} {b:?}");
        }
    }
    let model = HandModel::orca_v1_right();
    let options = HandMjcfOptions::default();
    let tree = HandTree::new(&model, &options);
    let group = |name: &str| tree.groups[model.link(name).unwrap().index()];
    assert_eq!(group("thumb_mp"), Group::Digit(0));
    assert_eq!(group("index_abd_jointbody"), Group::Digit(1));
    assert_eq!(group("pinky_fingertip"), Group::Digit(4));
    assert_eq!(group("palm"), Group::Palm);
    assert_eq!(group("tower"), Group::Palm);
}

#[test]
fn hinges_carrying_more_are_damped_more() {
    let model = HandModel::orca_v1_right();
    let options = HandMjcfOptions::default();
    let text = scene(&hand_mjcf(&model, &options));
    let doc = Document::parse(&text).unwrap();
    let damping = |name: &str| {
        let hinge = named(&elements(&doc, "joint"), name)[0];
        hinge
            .attribute("damping")
            .map_or(options.joint_damping, |_| floats(hinge, "damping")[0])
    };
    // The wrist moves the whole hand (MuJoCo: 2.5e-3 kg·m² with the armature at qpos0).
    let wrist = damping("right_wrist");
    let critical = 2.0 * (options.position_gain * 2.5e-3_f64).sqrt();
    assert!(
        (wrist / critical - 1.0).abs() < 0.05,
        "{wrist} vs {critical}"
    );
    // A fingertip's last joint moves almost nothing but its armature.
    let pip = damping("right_index_pip");
    assert!(
        pip >= options.joint_damping && pip < 1.05 * options.joint_damping,
        "{pip}"
    );
}

#[test]
fn options_reach_the_defaults_and_names_are_escaped() {
    let options = HandMjcfOptions {
        friction: [0.8, 0.0, 0.0],
        contact_solref: [0.004, 0.9],
        contact_solimp: [0.6, 0.98, 0.0002],
        contact_margin_m: 0.001,
        ..HandMjcfOptions::default()
    };
    let text = format!("<mujoco>{}</mujoco>", defaults_xml(&options));
    let doc = Document::parse(&text).unwrap();
    let geom = elements(&doc, "geom")[0];
    assert_eq!(geom.attribute("condim"), Some("3"));
    assert_eq!(floats(geom, "friction"), vec![0.8, 0.0, 0.0]);
    assert_eq!(floats(geom, "solref"), vec![0.004, 0.9]);
    assert_eq!(floats(geom, "solimp"), vec![0.6, 0.98, 0.0002]);
    assert_eq!(floats(geom, "margin"), vec![0.001]);
    let position = elements(&doc, "position")[0];
    assert_eq!(floats(position, "kp"), vec![options.position_gain]);
    let torque = options.max_torque_nm;
    assert_eq!(floats(position, "forcerange"), vec![-torque, torque]);
    assert_eq!(escape("a\"<b>&'"), "a&quot;&lt;b&gt;&amp;&apos;");
}
