//! Building packets in Rokoko Studio's custom-streaming JSON v3 format (docs/LAB_CONVENTIONS.md §2) from a
//! hand given in ROS's frame: what the tests, the benchmark and a stand-in for Studio send.
//!
//! A built packet has the shape Studio streams: version, fps, a scene with a timestamp, one
//! or more actors each with a full body (hips to toes and both hands, every bone with a
//! position and a rotation), face blendshapes and dimensions, and empty props and
//! characters, so its size and nesting are those of the real stream (about 15 kB for one
//! actor).

use nalgebra::{Isometry3, Point3, UnitQuaternion};
use retarget::KeypointLayout;
use serde_json::{Map, Value, json};

use crate::ingress::ingress_config::Hand;
use crate::ingress::rokoko_frame::{position_from_ros, rotation_from_ros};
use crate::ingress::rokoko_packet::bone_names;

/// Body bones a Studio actor carries besides the two hands' (positions filled in).
const BODY_BONES: [&str; 24] = [
    "hip",
    "spine",
    "chest",
    "neck",
    "head",
    "leftShoulder",
    "leftUpperArm",
    "leftLowerArm",
    "leftHand",
    "rightShoulder",
    "rightUpperArm",
    "rightLowerArm",
    "rightHand",
    "leftUpLeg",
    "leftLeg",
    "leftFoot",
    "leftToe",
    "leftToeEnd",
    "rightUpLeg",
    "rightLeg",
    "rightFoot",
    "rightToe",
    "rightToeEnd",
    "head_end",
];

/// Face blendshape names (a subset of ARKit's 52, as Studio streams them).
const BLENDSHAPES: [&str; 12] = [
    "eyeBlinkLeft",
    "eyeBlinkRight",
    "jawOpen",
    "mouthClose",
    "mouthSmileLeft",
    "mouthSmileRight",
    "browInnerUp",
    "cheekPuff",
    "noseSneerLeft",
    "noseSneerRight",
    "tongueOut",
    "eyeWideLeft",
];

fn bone(position: [f64; 3], rotation: [f64; 4]) -> Value {
    json!({
        "position": {"x": position[0], "y": position[1], "z": position[2]},
        "rotation": {"x": rotation[0], "y": rotation[1], "z": rotation[2], "w": rotation[3]},
    })
}

/// One actor's hand to put in a packet, in ROS's frame, metres.
#[derive(Debug, Clone, PartialEq)]
pub struct HandPose<'a> {
    /// The layout of `keypoints`.
    pub layout: KeypointLayout,
    /// Keypoints (lab22 or lab21).
    pub keypoints: &'a [Point3<f64>],
    /// Orientation of the hand bone.
    pub wrist_rotation: UnitQuaternion<f64>,
}

/// An actor's body with `hand`'s bones placed from `pose` (positions divided by
/// `position_scale_to_m`, i.e. in the stream's unit) and every other bone placed plausibly
/// around it.
pub fn actor(name: &str, hand: Hand, pose: &HandPose<'_>, position_scale_to_m: f64) -> Value {
    let to_stream = |p: &Point3<f64>| {
        let v = position_from_ros(p) / position_scale_to_m;
        [v.x, v.y, v.z]
    };
    let wrist = pose.keypoints[pose.layout.wrist()];
    let rotation = rotation_from_ros(&pose.wrist_rotation);
    let mut body = Map::new();
    for (k, name) in BODY_BONES.iter().enumerate() {
        // Others: a column of bones below the wrist, neutral rotation.
        let p = Point3::new(wrist.x, wrist.y, wrist.z - 0.1 * (k as f64 + 1.0));
        body.insert(
            (*name).to_string(),
            bone(to_stream(&p), [0.0, 0.0, 0.0, 1.0]),
        );
    }
    for (i, bone_name) in bone_names(hand, pose.layout).into_iter().enumerate() {
        let r = if bone_name.ends_with("Hand") {
            rotation
        } else {
            [0.0, 0.0, 0.0, 1.0]
        };
        body.insert(bone_name, bone(to_stream(&pose.keypoints[i]), r));
    }
    // The other hand's fingers, so both hands are present as in Studio's stream.
    let other = match hand {
        Hand::Right => Hand::Left,
        Hand::Left => Hand::Right,
    };
    for (i, bone_name) in bone_names(other, pose.layout).into_iter().enumerate() {
        let p = pose.keypoints[i] + nalgebra::Vector3::new(0.0, 0.4, 0.0);
        body.entry(bone_name)
            .or_insert_with(|| bone(to_stream(&p), [0.0, 0.0, 0.0, 1.0]));
    }
    let face: Map<String, Value> = BLENDSHAPES
        .iter()
        .enumerate()
        .map(|(k, n)| ((*n).to_string(), json!(0.01 * k as f64)))
        .collect();
    json!({
        "name": name,
        "color": [0.5, 0.2, 0.9],
        "meta": {"hasGloves": true, "hasLeftGlove": true, "hasRightGlove": true,
                 "hasBody": true, "hasFace": true},
        "dimensions": {"totalHeight": 180.0, "hipHeight": 95.0},
        "body": body,
        "face": face,
    })
}

/// A whole packet with `actors` at `timestamp_s`, serialised.
pub fn packet(timestamp_s: f64, actors: Vec<Value>) -> Vec<u8> {
    let value = json!({
        "version": "3,0",
        "fps": 100,
        "scene": {
            "timestamp": timestamp_s,
            "actors": actors,
            "props": [],
            "characters": [],
        },
    });
    value.to_string().into_bytes()
}

/// A one-actor packet for a right hand at `wrist` (the hand bone's pose) with `keypoints`.
pub fn right_hand_packet(
    timestamp_s: f64,
    layout: KeypointLayout,
    keypoints: &[Point3<f64>],
    wrist: &Isometry3<f64>,
) -> Vec<u8> {
    let pose = HandPose {
        layout,
        keypoints,
        wrist_rotation: wrist.rotation,
    };
    packet(timestamp_s, vec![actor("Actor1", Hand::Right, &pose, 1.0)])
}
