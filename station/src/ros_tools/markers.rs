//! Markers for viewers: the glove keypoints as the retargeter sees them, beside the robot's
//! fingertips, and a drawing of the robot hand from primitive shapes.
//!
//! The glove points are placed as the retargeting energy compares them: each point in the
//! human palm frame, mapped by the user's calibration (`scale · R`), then set on the robot's
//! palm frame at the commanded pose. A glove fingertip that sits away from the robot's is
//! a key vector the robot cannot reproduce (a pinch that does not close shows as two tips
//! apart).

use msgs::{ColorRGBA, Header, Marker, MarkerArray, Point, Pose, Quaternion, Vector3};
use nalgebra::{Point3, UnitQuaternion, Vector3 as V3};
use retarget::{
    CalibrationTransform, Finger, FkState, HandModel, JointMotion, KeypointLayout, PalmFrame,
};

use crate::convert::header;
use crate::ros_tools::hand_tf::HandTf;

/// Glove keypoints: orange.
const GLOVE: ColorRGBA = ColorRGBA {
    r: 1.0,
    g: 0.55,
    b: 0.1,
    a: 1.0,
};
/// Robot fingertips: blue.
const ROBOT: ColorRGBA = ColorRGBA {
    r: 0.2,
    g: 0.45,
    b: 1.0,
    a: 1.0,
};
/// The drawn hand: grey, a little transparent so the glove shows through.
const BODY: ColorRGBA = ColorRGBA {
    r: 0.75,
    g: 0.75,
    b: 0.78,
    a: 0.8,
};

/// Marker ids of the keypoint markers (namespace `pomdar`).
pub mod ids {
    /// The glove keypoints (`SPHERE_LIST`).
    pub const GLOVE_POINTS: i32 = 0;
    /// The glove's bones (`LINE_LIST`: wrist to each digit's base, then along each digit).
    pub const GLOVE_BONES: i32 = 1;
    /// The robot's fingertips (`SPHERE_LIST`, thumb to little).
    pub const ROBOT_TIPS: i32 = 2;
}

/// The glove keypoints on the robot's palm, in the model's base frame.
///
/// `Err` when either palm frame cannot be built (collapsed or non-finite points).
pub fn glove_points_on_robot(
    model: &HandModel,
    state: &FkState,
    layout: KeypointLayout,
    calibration: &CalibrationTransform,
    points: &[Point3<f64>],
) -> Result<Vec<Point3<f64>>, retarget::Error> {
    retarget::validate_keypoints(layout, points)?;
    let human = PalmFrame::from_landmarks(&layout.palm_landmarks(points))?;
    let robot = model.palm_frame(state)?;
    let map = calibration.matrix();
    Ok(points
        .iter()
        .map(|p| robot.origin + robot.rotation * (map * human.point_to_palm(p)))
        .collect())
}

/// The keypoint markers: glove points and bones, robot fingertips; in the tree's root frame.
pub fn keypoint_markers(
    tree: &HandTf,
    model: &HandModel,
    state: &FkState,
    layout: KeypointLayout,
    glove: &[Point3<f64>],
    stamp_ns: i64,
) -> MarkerArray {
    let head = header(stamp_ns, tree.root_frame());
    let mut bones = Vec::new();
    for finger in Finger::ALL {
        let chain = layout.chain(finger);
        bones.push(point(&glove[layout.wrist()]));
        bones.push(point(&glove[chain[0]]));
        for pair in chain.windows(2) {
            bones.push(point(&glove[pair[0]]));
            bones.push(point(&glove[pair[1]]));
        }
    }
    let tips = Finger::ALL.map(|f| point(&state.position(model.frames().tip(f))));
    MarkerArray {
        markers: vec![
            list(
                &head,
                ids::GLOVE_POINTS,
                Marker::SPHERE_LIST,
                0.008,
                GLOVE,
                glove.iter().map(point).collect(),
            ),
            list(
                &head,
                ids::GLOVE_BONES,
                Marker::LINE_LIST,
                0.002,
                GLOVE,
                bones,
            ),
            list(
                &head,
                ids::ROBOT_TIPS,
                Marker::SPHERE_LIST,
                0.011,
                ROBOT,
                tips.to_vec(),
            ),
        ],
    }
}

/// The robot hand drawn in its link frames (frame-locked, so it follows `/tf`): a cylinder
/// along every joint's offset from its parent's origin, a sphere at every moving joint and at
/// every fingertip. Namespace `pomdar_hand`.
pub fn hand_model_markers(tree: &HandTf, model: &HandModel, stamp_ns: i64) -> MarkerArray {
    let mut markers = Vec::new();
    let mut next_id = 0;
    let mut push = |mut marker: Marker| {
        marker.id = next_id;
        next_id += 1;
        markers.push(marker);
    };
    for joint in model.joints() {
        let offset = joint.origin.translation.vector;
        let head = header(stamp_ns, tree.frame(joint.parent));
        if offset.norm() > 1e-4 {
            push(bone(head, &offset));
        }
        if matches!(joint.motion, JointMotion::Revolute { .. }) {
            push(ball(header(stamp_ns, tree.frame(joint.child)), 0.012));
        }
    }
    for finger in Finger::ALL {
        push(ball(
            header(stamp_ns, tree.frame(model.frames().tip(finger))),
            0.010,
        ));
    }
    MarkerArray { markers }
}

fn point(p: &Point3<f64>) -> Point {
    Point {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

fn list(
    head: &Header,
    id: i32,
    kind: i32,
    size_m: f64,
    color: ColorRGBA,
    points: Vec<Point>,
) -> Marker {
    Marker {
        header: head.clone(),
        ns: "pomdar".into(),
        id,
        kind,
        action: Marker::ADD,
        scale: Vector3 {
            x: size_m,
            y: size_m,
            z: size_m,
        },
        color,
        points,
        ..Marker::default()
    }
}

/// A cylinder from the frame's origin to `offset` (in that frame).
fn bone(head: Header, offset: &V3<f64>) -> Marker {
    let length = offset.norm();
    let middle = offset / 2.0;
    let turn = UnitQuaternion::rotation_between(&V3::z(), offset)
        .unwrap_or_else(|| UnitQuaternion::from_axis_angle(&V3::x_axis(), std::f64::consts::PI));
    let q = turn.quaternion();
    Marker {
        header: head,
        ns: "pomdar_hand".into(),
        kind: Marker::CYLINDER,
        action: Marker::ADD,
        frame_locked: true,
        pose: Pose {
            position: Point {
                x: middle.x,
                y: middle.y,
                z: middle.z,
            },
            orientation: Quaternion {
                x: q.i,
                y: q.j,
                z: q.k,
                w: q.w,
            },
        },
        scale: Vector3 {
            x: 0.014,
            y: 0.014,
            z: length,
        },
        color: BODY,
        ..Marker::default()
    }
}

/// A sphere at the frame's origin.
fn ball(head: Header, diameter_m: f64) -> Marker {
    Marker {
        header: head,
        ns: "pomdar_hand".into(),
        kind: Marker::SPHERE,
        action: Marker::ADD,
        frame_locked: true,
        scale: Vector3 {
            x: diameter_m,
            y: diameter_m,
            z: diameter_m,
        },
        color: BODY,
        ..Marker::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ros_tools::ros_tools_config::RosToolsConfig;

    #[test]
    fn the_robots_own_keypoints_land_on_its_fingertips() {
        // Keypoints made from the robot itself (robot-as-human) at identity calibration: each
        // glove fingertip must sit on the robot fingertip it came from.
        let model = HandModel::orca_v1_right();
        let layout = KeypointLayout::Lab22;
        let q: Vec<f64> = model
            .limits()
            .map(|l| 0.5 * (l.lower_rad + l.upper_rad))
            .collect();
        let state = model.forward_new(&q).unwrap();
        let points = model.synthetic_keypoints(&state, layout);
        let glove = glove_points_on_robot(
            &model,
            &state,
            layout,
            &CalibrationTransform::IDENTITY,
            &points,
        )
        .unwrap();
        let tree = HandTf::new(&model, &RosToolsConfig::default());
        let markers = keypoint_markers(&tree, &model, &state, layout, &glove, 5).markers;
        assert_eq!(markers.len(), 3);
        assert_eq!(markers[0].points.len(), layout.len());
        assert_eq!(markers[0].header.frame_id, "world");
        for finger in Finger::ALL {
            let g = &glove[layout.tip(finger)];
            let r = state.position(model.frames().tip(finger));
            assert!(
                (g - r).norm() < 1e-9,
                "{finger:?} is {} m off",
                (g - r).norm()
            );
        }
    }

    #[test]
    fn the_drawn_hand_hangs_on_urdf_frames() {
        let model = HandModel::orca_v1_right();
        let tree = HandTf::new(&model, &RosToolsConfig::default());
        let markers = hand_model_markers(&tree, &model, 0).markers;
        assert!(markers.len() > 30);
        assert!(markers.iter().all(|m| m.frame_locked));
        assert!(
            markers
                .iter()
                .any(|m| m.header.frame_id == "right_index_fingertip")
        );
        let ids: std::collections::BTreeSet<i32> = markers.iter().map(|m| m.id).collect();
        assert_eq!(ids.len(), markers.len());
    }
}
