//! Every scene parses as XML, holds the hand under the mocap body, names its mapping's joint
//! with the right type, and keeps its marks inside the joint's range.

use std::collections::HashSet;

use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use scoring::{CorrectnessKind, TaskCatalog};

use super::*;

/// A one-finger stand-in hand (the real one is written elsewhere).
pub(crate) fn tiny_hand() -> HandMjcf {
    HandMjcf {
        body: r#"<body name="tiny_palm" pos="0 0 0.03">
  <geom class="pomdar_hand" type="box" size="0.03 0.03 0.01" mass="0.2"/>
  <body name="tiny_finger" pos="0 0 0.01">
    <joint name="tiny_finger_joint" class="pomdar_hand" type="hinge" axis="1 0 0" range="0 1.5"/>
    <geom class="pomdar_hand" type="capsule" fromto="0 0 0 0 0 0.04" size="0.007" mass="0.02"/>
  </body>
</body>"#
            .to_string(),
        defaults: r#"<default class="pomdar_hand"><geom condim="4" friction="1 0.01 0.0002"/><joint damping="0.05"/><position kp="2"/></default>"#.to_string(),
        actuators: r#"<position name="tiny_finger_act" joint="tiny_finger_joint" class="pomdar_hand" ctrlrange="0 1.5"/>"#.to_string(),
        equalities: String::new(),
        contact_excludes: String::new(),
        dof_joints: vec!["tiny_finger_joint".into()],
        dof_actuators: vec!["tiny_finger_act".into()],
        tip_bodies: std::array::from_fn(|_| "tiny_finger".to_string()),
        palm_body: "tiny_palm".into(),
        root_body: "tiny_palm".into(),
        max_speed_rad_s: 5.0,
        assets: String::new(),
        zero_offsets_rad: vec![0.0],
        eulerseq: None,
        mount: Isometry3::from_parts(Translation3::new(0.0, 0.0, 0.01), UnitQuaternion::identity()),
    }
}

pub(crate) fn all_scenes() -> Vec<Scene> {
    let catalog = TaskCatalog::builtin();
    TASK_IDS
        .iter()
        .map(|id| {
            let task = catalog.get(id).unwrap();
            task_scene(task, &tiny_hand(), &SceneOptions::default()).unwrap()
        })
        .collect()
}

fn joint_of<'a>(doc: &'a roxmltree::Document, name: &str) -> roxmltree::Node<'a, 'a> {
    doc.descendants()
        .find(|n| {
            matches!(n.tag_name().name(), "joint" | "freejoint")
                && n.attribute("name") == Some(name)
        })
        .unwrap_or_else(|| panic!("no joint {name}"))
}

#[test]
fn the_scenes_are_the_catalogs_18_tasks() {
    assert_eq!(TASK_IDS.join(", "), TaskCatalog::builtin().ids());
}

#[test]
fn every_scene_parses_and_welds_the_hand_to_the_mocap_body() {
    for scene in all_scenes() {
        let doc = roxmltree::Document::parse(&scene.xml)
            .unwrap_or_else(|e| panic!("{}: {e}", scene.task_id));
        let named = |name: &str| {
            doc.descendants()
                .find(|n| n.attribute("name") == Some(name))
                .unwrap_or_else(|| panic!("{}: no {name}", scene.task_id))
        };
        let mount = named(MOUNT_BODY);
        assert_eq!(mount.attribute("mocap"), Some("true"));
        assert_eq!(mount.attribute("pos"), Some("0.45 0 0.4"));
        assert_eq!(mount.attribute("quat"), Some("0 1 0 0"));
        let in_world =
            |n: roxmltree::Node<'_, '_>| n.parent().map(|p| p.tag_name().name().to_string());
        assert_eq!(in_world(mount).as_deref(), Some("worldbody"));
        // The hand hangs on a free body of its own, not inside the mocap body.
        assert!(
            !mount
                .descendants()
                .any(|n| n.attribute("name") == Some("tiny_palm"))
        );
        let hand = named(HAND_MOUNT_BODY);
        assert_eq!(in_world(hand).as_deref(), Some("worldbody"));
        assert!(hand.children().any(|n| n.tag_name().name() == "freejoint"));
        assert!(
            hand.descendants()
                .any(|n| n.attribute("name") == Some("tiny_palm"))
        );
        let weld = named(MOUNT_WELD);
        assert_eq!(weld.tag_name().name(), "weld");
        assert_eq!(weld.attribute("body1"), Some(MOUNT_BODY));
        assert_eq!(weld.attribute("body2"), Some(HAND_MOUNT_BODY));
        assert_eq!(weld.attribute("solref"), Some("0.005 1"));
        assert_eq!(weld.attribute("solimp"), Some("0.97 0.99 0.0005"));
        let root = doc.root_element();
        let sections: Vec<&str> = root
            .children()
            .filter(|n| n.is_element())
            .map(|n| n.tag_name().name())
            .collect();
        assert_eq!(
            sections,
            [
                "compiler",
                "option",
                "default",
                "worldbody",
                "equality",
                "actuator"
            ],
            "{}",
            scene.task_id
        );
        assert_eq!(scene.mount_body, MOUNT_BODY);
        assert_eq!(scene.hand.palm_body, "tiny_palm");
    }
}

#[test]
fn names_are_unique_within_each_kind_of_element() {
    for scene in all_scenes() {
        let doc = roxmltree::Document::parse(&scene.xml).unwrap();
        let mut seen = HashSet::new();
        for node in doc.descendants().filter(|n| n.is_element()) {
            if let Some(name) = node.attribute("name") {
                let kind = match node.tag_name().name() {
                    "freejoint" => "joint",
                    other => other,
                };
                assert!(
                    seen.insert((kind, name)),
                    "{}: {kind} {name} twice",
                    scene.task_id
                );
            }
        }
    }
}

#[test]
fn every_mapping_names_a_joint_of_the_right_type_and_fits_its_task() {
    let catalog = TaskCatalog::builtin();
    for scene in all_scenes() {
        let kind = catalog.get(&scene.task_id).unwrap().correctness;
        assert_eq!(scene.progress.validate(&kind), Ok(()), "{}", scene.task_id);
        let doc = roxmltree::Document::parse(&scene.xml).unwrap();
        let joint = joint_of(&doc, &scene.progress.joint);
        let found = match joint.tag_name().name() {
            "freejoint" => "free",
            _ => joint.attribute("type").unwrap_or("hinge"),
        };
        let expected = match kind {
            CorrectnessKind::Rotation { .. } => "hinge",
            CorrectnessKind::Grasp {} => "free",
            _ => "slide",
        };
        assert_eq!(found, expected, "{}", scene.task_id);
    }
}

#[test]
fn marks_and_the_full_distance_lie_inside_the_joint_range() {
    for scene in all_scenes() {
        let doc = roxmltree::Document::parse(&scene.xml).unwrap();
        let joint = joint_of(&doc, &scene.progress.joint);
        let Some(range) = joint.attribute("range") else {
            continue;
        };
        let range: Vec<f64> = range.split(' ').map(|v| v.parse().unwrap()).collect();
        let band = scene.progress.mark_band;
        for mark in &scene.progress.marks {
            assert!(
                range[0] < mark - band && mark + band < range[1],
                "{}: mark {mark} outside {range:?}",
                scene.task_id
            );
        }
        if scene.task_id.starts_with("H4") || scene.task_id.starts_with("H5") {
            assert!(range[0] <= 0.0 && range[1] > 0.2, "{range:?}");
        }
        if scene.task_id == "C1" {
            assert!(range[1] >= 2.0 * std::f64::consts::PI, "{range:?}");
        }
    }
}

#[test]
fn the_grasp_target_is_on_the_table_away_from_the_start() {
    for scene in all_scenes().iter().filter(|s| s.task_id.starts_with('G')) {
        let grasp = scene.progress.grasp.as_ref().unwrap();
        let doc = roxmltree::Document::parse(&scene.xml).unwrap();
        let object = doc
            .descendants()
            .find(|n| n.tag_name().name() == "body" && n.attribute("name") == Some("object"))
            .unwrap();
        let start: Vec<f64> = object
            .attribute("pos")
            .unwrap()
            .split(' ')
            .map(|v| v.parse().unwrap())
            .collect();
        assert!(
            !grasp.in_target([start[0], start[1], start[2]]),
            "{}",
            scene.task_id
        );
        assert_eq!(grasp.target_min_m[2], 0.0);
        assert!(
            grasp.target_max_m[2] < start[2] + grasp.lift_m,
            "{}: a lifted object would count as placed",
            scene.task_id
        );
    }
}

#[test]
fn unknown_tasks_and_bad_options_are_refused_with_what_is_allowed() {
    let mut task = TaskCatalog::builtin().get("V1").unwrap().clone();
    let hand = tiny_hand();
    let options = SceneOptions {
        timestep_s: 0.05,
        ..SceneOptions::default()
    };
    let message = task_scene(&task, &hand, &options).unwrap_err().to_string();
    assert_eq!(message, "timestep_s = 0.05: s, in [0.0001, 0.01]");
    task.correctness = CorrectnessKind::Notches { count: 5 };
    let message = task_scene(&task, &hand, &SceneOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        message.starts_with("task V1: the scene's progress mapping does not fit"),
        "{message}"
    );
    task.id = "X9".into();
    let message = task_scene(&task, &hand, &SceneOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("\"X9\"") && message.contains("V1, V2, V3, H1"),
        "{message}"
    );
}
