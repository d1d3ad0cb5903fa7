//! `/tf` and `/tf_static` of the hand from the station's own kinematics: one transform per
//! joint, its parent link's frame to its child link's, named as the robot's URDF names its
//! links (so RViz and Foxglove draw the URDF's meshes on them), and the arm target as a frame.

use msgs::{PoseStamped, Quaternion, TFMessage, Transform, TransformStamped, Vector3};
use nalgebra::Isometry3;
use retarget::{FkState, HandModel, JointMotion, LinkId};

use crate::convert::header;
use crate::ros_tools::ros_tools_config::RosToolsConfig;

/// The hand's transform tree.
#[derive(Debug, Clone, PartialEq)]
pub struct HandTf {
    /// Per link: its `/tf` frame name.
    frames: Vec<String>,
    /// (parent, child) of every revolute joint (moving: `/tf`).
    moving: Vec<(LinkId, LinkId)>,
    /// (parent, child) of every fixed joint (`/tf_static`).
    fixed: Vec<(LinkId, LinkId)>,
    arm_target_frame: String,
}

impl HandTf {
    /// The tree of `model`, named per `config` (the root's name, the URDF names otherwise).
    pub fn new(model: &HandModel, config: &RosToolsConfig) -> HandTf {
        let mut frames = model.ros_link_names().to_vec();
        if !config.root_frame.is_empty() {
            frames[0].clone_from(&config.root_frame);
        }
        let (mut moving, mut fixed) = (Vec::new(), Vec::new());
        for joint in model.joints() {
            match joint.motion {
                JointMotion::Revolute { .. } => moving.push((joint.parent, joint.child)),
                JointMotion::Fixed => fixed.push((joint.parent, joint.child)),
            }
        }
        HandTf {
            frames,
            moving,
            fixed,
            arm_target_frame: config.arm_target_frame.clone(),
        }
    }

    /// The `/tf` frame of `link`.
    pub fn frame(&self, link: LinkId) -> &str {
        &self.frames[link.index()]
    }

    /// The frame of the model's root link (the frame markers are drawn in).
    pub fn root_frame(&self) -> &str {
        &self.frames[0]
    }

    /// Every moving link's transform at the pose in `state` (forward kinematics of the
    /// published joint vector), stamped `stamp_ns`.
    pub fn moving(&self, state: &FkState, stamp_ns: i64) -> TFMessage {
        self.edges(&self.moving, state, stamp_ns)
    }

    /// Every fixed link's transform (they do not depend on the joints), stamped `stamp_ns`.
    pub fn fixed(&self, state: &FkState, stamp_ns: i64) -> TFMessage {
        self.edges(&self.fixed, state, stamp_ns)
    }

    /// The arm target as a frame (child of the target's own frame), if one is configured.
    pub fn arm_target(&self, target: &PoseStamped) -> Option<TFMessage> {
        if self.arm_target_frame.is_empty() {
            return None;
        }
        let p = &target.pose;
        let transform = Transform {
            translation: Vector3 {
                x: p.position.x,
                y: p.position.y,
                z: p.position.z,
            },
            rotation: p.orientation,
        };
        Some(TFMessage {
            transforms: vec![TransformStamped {
                header: target.header.clone(),
                child_frame_id: self.arm_target_frame.clone(),
                transform,
            }],
        })
    }

    fn edges(&self, edges: &[(LinkId, LinkId)], state: &FkState, stamp_ns: i64) -> TFMessage {
        let transforms = edges
            .iter()
            .map(|&(parent, child)| {
                let relative = state.pose(parent).inverse() * state.pose(child);
                TransformStamped {
                    header: header(stamp_ns, self.frame(parent)),
                    child_frame_id: self.frame(child).to_string(),
                    transform: transform_msg(&relative),
                }
            })
            .collect();
        TFMessage { transforms }
    }
}

/// An isometry as a `geometry_msgs/Transform`.
pub fn transform_msg(pose: &Isometry3<f64>) -> Transform {
    let t = pose.translation.vector;
    let q = pose.rotation.quaternion();
    Transform {
        translation: Vector3 {
            x: t.x,
            y: t.y,
            z: t.z,
        },
        rotation: Quaternion {
            x: q.i,
            y: q.j,
            z: q.k,
            w: q.w,
        },
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Translation3, UnitQuaternion};

    use super::*;

    /// Compose a frame's pose in the root from the published edges.
    fn compose(tf: &[TransformStamped], frame: &str, root: &str) -> Isometry3<f64> {
        if frame == root {
            return Isometry3::identity();
        }
        let edge = tf.iter().find(|t| t.child_frame_id == frame).unwrap();
        let (v, r) = (edge.transform.translation, edge.transform.rotation);
        let local = Isometry3::from_parts(
            Translation3::new(v.x, v.y, v.z),
            UnitQuaternion::new_normalize(nalgebra::Quaternion::new(r.w, r.x, r.y, r.z)),
        );
        compose(tf, &edge.header.frame_id, root) * local
    }

    #[test]
    fn composed_edges_reproduce_forward_kinematics_under_urdf_names() {
        let model = HandModel::orca_v1_right();
        let tree = HandTf::new(&model, &RosToolsConfig::default());
        let q: Vec<f64> = model
            .limits()
            .map(|l| 0.3 * l.lower_rad + 0.7 * l.upper_rad)
            .collect();
        let state = model.forward_new(&q).unwrap();
        let mut edges = tree.moving(&state, 7).transforms;
        edges.extend(tree.fixed(&state, 7).transforms);
        assert_eq!(edges.len(), model.joints().len());
        assert_eq!(tree.root_frame(), "world");
        for (i, name) in model.link_names().iter().enumerate().skip(1) {
            let frame = format!("right_{name}");
            let pose = compose(&edges, &frame, "world");
            let expected = state.pose(model.link(name).unwrap());
            let error = (pose.translation.vector - expected.translation.vector).norm();
            assert!(error < 1e-12, "{frame} (link {i}) is {error} m off");
            assert!(pose.rotation.angle_to(&expected.rotation) < 1e-9, "{frame}");
        }
    }

    #[test]
    fn the_root_can_be_renamed_and_the_arm_target_is_a_frame() {
        let model = HandModel::orca_v1_right();
        let config = RosToolsConfig {
            root_frame: "hand_mount".into(),
            ..RosToolsConfig::default()
        };
        let tree = HandTf::new(&model, &config);
        let state = model.forward_new(&model.zero_pose()).unwrap();
        let fixed = tree.fixed(&state, 0).transforms;
        assert!(fixed.iter().any(|t| t.header.frame_id == "hand_mount"));
        let mut target = PoseStamped::default();
        target.header.frame_id = "world".into();
        target.pose.position.x = 0.4;
        let edge = &tree.arm_target(&target).unwrap().transforms[0];
        assert_eq!(edge.child_frame_id, "pomdar_arm_target");
        assert_eq!(edge.header.frame_id, "world");
        assert_eq!(edge.transform.translation.x, 0.4);
    }
}
