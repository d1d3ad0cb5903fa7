//! Placeholder: the hand written as MJCF (the real module is written on another branch).
//!
//! Only the struct the scenes are assembled from, so that `scene` compiles on this branch;
//! the real module replaces this file, with the same fields.

use nalgebra::Isometry3;

/// A hand model written as MJCF pieces, ready to be placed into a scene.
#[derive(Debug, Clone)]
pub struct HandMjcf {
    /// The hand's `<body …>…</body>` subtree, its root at the parent body's origin.
    pub body: String,
    /// The hand's `<default class="pomdar_hand">…</default>` element.
    pub defaults: String,
    /// One `<position/>` actuator element per degree of freedom.
    pub actuators: String,
    /// `<joint/>` equality elements (coupled joints), maybe empty.
    pub equalities: String,
    /// `<exclude/>` contact elements, maybe empty.
    pub contact_excludes: String,
    /// The names of the actuated joints, in degree-of-freedom order.
    pub dof_joints: Vec<String>,
    /// The names of the position actuators, in the same order as `dof_joints`.
    pub dof_actuators: Vec<String>,
    /// The fingertip bodies: thumb, index, middle, ring, little.
    pub tip_bodies: [String; 5],
    /// The palm body's name.
    pub palm_body: String,
    /// The fastest joint speed the hand can follow, rad/s.
    pub max_speed_rad_s: f64,
    /// The hand root's pose in the arm's flange frame (m).
    pub mount: Isometry3<f64>,
}
