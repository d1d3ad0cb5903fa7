//! A [`HandModel`] written as a MuJoCo MJCF body tree, for simulating the robot hand.
//!
//! [`hand_mjcf`] turns the kinematic tree into the pieces a scene assembles ([`HandMjcf`]): one
//! `<body>` subtree to place inside a mount body, a default class, the actuators, the
//! equality constraints of coupled joints and the names the simulator publishes.
//!
//! # Modelling choices
//!
//! - **Frames.** Every link is a body named by [`HandModel::ros_link_names`] (the root is
//!   renamed when it is called `world`, MuJoCo's own name for the world body), posed by its
//!   joint's origin. A revolute joint becomes a hinge at the child body's origin with the axis
//!   in the child frame, exactly the model's `T_child = T_parent · origin · Rot(axis, q)`; a
//!   fixed joint becomes a child body without a joint. Hinges driving a degree of freedom are
//!   named by [`HandModel::ros_dof_names`], so the simulator's joint states carry the names
//!   the real hand's URDF uses. The XML needs `<compiler angle="radian"/>`: ranges are radians.
//! - **Coupled joints** (URDF mimic, `q_j = k · q_i + c`) are hinges of their own held on the
//!   driving joint by `<equality><joint polycoef="c k 0 0 0"/>` (MuJoCo: `joint1 = poly(joint2)`
//!   about the reference pose, which is zero here); they have no actuator.
//! - **Collision geometry** follows the station's drawing of the hand from primitives: a
//!   capsule from each link's origin to each child joint's origin, a sphere at every moving
//!   joint (a knuckle, which also gives every hinged body mass of its own, as MuJoCo requires),
//!   and a fingertip whose rounded end sits on the tip frame (the last capsule of a chain stops
//!   one radius short of the leaf link). The palm is a box through the wrist and the five digit
//!   bases, aligned with the palm frame the retargeter uses, `2 · palm_radius_m` thick.
//! - **Mass** comes from the geometry at [`HAND_DENSITY_KG_M3`]: 10–18 g per finger segment,
//!   about 120 g of palm, 350 g below the wrist, in line with the 3D-printed, tendon-driven
//!   ORCA (its motors sit in the tower, which hangs rigidly from the mount and does not move).
//! - **Self-collision between digits, not within one.** Every digit has its own contact bit:
//!   a digit's geoms collide with the other digits (a thumb presses on an index finger as the
//!   real one does) and with everything of MuJoCo's default contact type (bit 0), never with
//!   its own segments or the palm, which touch at every joint by construction and would push
//!   the hand apart from the first step. The palm collides with the world only. Hence
//!   [`HandMjcf::contact_excludes`] is empty for these models; the field stays for models
//!   whose geometry needs pair exclusions.
//! - **Actuation.** One `<position>` actuator per degree of freedom (`kp`, force limit), its
//!   `ctrlrange` the degree of freedom's limits. Armature stands for the geared servo's rotor;
//!   joint damping (`max_torque / max_speed` by default, a servo's linear torque–speed curve)
//!   caps the speed of a saturated actuator at the real hand's. A hinge whose load needs more
//!   damping for its servo to be critically damped (`2 √(kp · I)`, `I` its armature plus what
//!   it moves, from the geometry and density MuJoCo uses) gets it: the wrist, carrying the
//!   whole hand, does not overshoot, and turns at most `max_torque / damping`.
//! - **Gravity.** The real servos hold a pose against gravity with the integral term of their
//!   position loop, which a MuJoCo position actuator lacks: every hand body is
//!   gravity-compensated (`gravcomp="1"`) through its joints' actuators (`actuatorgravcomp`),
//!   within the same torque limit, so a pose is held without the steady sag `m g l / kp` of a
//!   pure PD servo. Objects keep their weight.
//! - **Speed.** A joint speed limit is not expressible in MJCF: the engine rate-limits its
//!   controls with [`HandMjcf::max_speed_rad_s`].

use std::f64::consts::PI;

use nalgebra::{Isometry3, Matrix3, Point3, Translation3, Unit, UnitQuaternion, Vector3};
use retarget::{Finger, FkState, HandModel, JointMotion, LinkId, PalmFrame};

/// The MJCF default class of every hand element.
pub const HAND_CLASS: &str = "pomdar_hand";

/// Density of the hand's collision geometry, kg/m³: printed shells with a light infill
/// weigh about as much as water; ORCA's finger segments come out at 10–18 g.
pub const HAND_DENSITY_KG_M3: f64 = 1000.0;

/// Contact bit of geoms with MuJoCo's default `contype`/`conaffinity` (tables, objects).
const WORLD_BIT: u32 = 1;
/// Contact bit of the palm and the links above it (wrist, mount).
const PALM_BIT: u32 = 1 << 1;
/// Contact bit of the first digit; digit `f` uses `FIRST_DIGIT_BIT << f`.
const FIRST_DIGIT_BIT: u32 = 1 << 2;
/// All five digits' contact bits.
const ALL_DIGIT_BITS: u32 = 0b11111 << 2;

/// Joint offsets shorter than this draw no segment, metres (the markers' threshold).
const MIN_SEGMENT_M: f64 = 1e-4;
/// Coordinates smaller than this are written as 0 (rounding noise of the rotations).
const ZERO_SNAP: f64 = 1e-12;
/// Time constant of the joint limits, seconds: stiffer than MuJoCo's 0.02 s, so a joint
/// driven into its stop at full speed passes it by under 0.01 rad (about 0.05 rad with
/// MuJoCo's default).
/// MuJoCo raises it to twice the time step when the step is longer than 2.5 ms.
const LIMIT_TIME_CONSTANT_S: f64 = 0.005;
/// Grey of the hand's geoms (the station's marker colour, opaque).
const HAND_RGBA: &str = "0.75 0.75 0.78 1";

/// How the hand is simulated: servo, joint and contact parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct HandMjcfOptions {
    /// Stiffness of the position actuators, N·m/rad.
    pub position_gain: f64,
    /// Viscous damping of every hinge, N·m·s/rad; raised where a hinge's load needs more for
    /// its servo to be critically damped (the wrist).
    pub joint_damping: f64,
    /// Reflected rotor inertia added to every hinge, kg·m².
    pub armature: f64,
    /// Largest torque an actuator applies (gravity compensation included), N·m.
    pub max_torque_nm: f64,
    /// The real hand's joint speed, rad/s. MJCF cannot limit speed: the engine rate-limits
    /// its controls with it ([`HandMjcf::max_speed_rad_s`]).
    pub max_speed_rad_s: f64,
    /// Capsule radius of finger segments and knuckles, metres.
    pub finger_radius_m: f64,
    /// Half thickness of the palm box, radius of the wrist and mount capsules, metres.
    pub palm_radius_m: f64,
    /// MuJoCo friction coefficients: sliding, torsional (m), rolling (m). The contact
    /// dimension follows: 6 with rolling friction, 4 with torsional, else 3.
    pub friction: [f64; 3],
    /// MuJoCo `solref` of the hand's contacts: time constant (s) and damping ratio. Stiff
    /// enough that a squeezed object sinks a fraction of a millimetre into the pads, not
    /// several millimetres, so a grip holds its shape while the arm carries it.
    pub contact_solref: [f64; 2],
    /// MuJoCo `solimp` of the hand's contacts: impedance at zero and at full penetration and
    /// the width (m) between them.
    pub contact_solimp: [f64; 3],
    /// Distance (m) at which a hand contact becomes active, before the geoms touch.
    pub contact_margin_m: f64,
}

impl Default for HandMjcfOptions {
    fn default() -> Self {
        HandMjcfOptions {
            // A command ramping at the speed limit is followed `joint_damping / position_gain`
            // = 20 ms behind; a 1 rad step reaches 90 % in 0.1 s and settles (2 %) in 0.12 s.
            position_gain: 5.0,
            // max_torque_nm / max_speed_rad_s: a saturated actuator turns no faster than the
            // real servo, even on an unlimited step; with the armature below, about critical
            // for a finger (the hinges carrying more are raised to critical, the wrist ×2.3).
            joint_damping: 0.1,
            // A small servo's rotor (~6e-9 kg·m²) through its ~1:288 gearbox, as seen at the
            // joint through tendon spools of about 1:1; dwarfs a finger segment's own
            // ~5e-5 kg·m².
            armature: 5e-4,
            // The order of a small Dynamixel servo's stall torque (~1 N·m) at ~1:1 spools:
            // 10–15 N at a fingertip.
            max_torque_nm: 1.0,
            // About 100 rpm at no load; below the retargeter's 12 rad/s command limit.
            max_speed_rad_s: 10.0,
            // ORCA fingers are about 18 mm wide; adjacent finger bases sit 23 mm apart.
            finger_radius_m: 0.009,
            // A palm about 24 mm thick.
            palm_radius_m: 0.012,
            // Rubber-like pads on printed plastic: sliding 1; torsional friction over a
            // contact patch of about 1 cm, so a pinched object does not spin; no rolling.
            friction: [1.0, 0.01, 0.0],
            // Stiff, quickly saturating pads (the settings of the benchmark authors' own ORCA
            // scene). The shipped G4 grasp in lock step, seeds 201–220: 20 of 20 with these,
            // 1 of 20 with MuJoCo's soft default (solref 0.02 1, solimp 0.9 0.95 0.001, no
            // margin), under which the squeezed cylinder sinks millimetres into the palm and
            // rolls out of the grip while carried (README, "The simulated benchmark").
            contact_solref: [0.005, 1.0],
            contact_solimp: [0.5, 0.99, 0.0001],
            contact_margin_m: 0.0005,
        }
    }
}

/// The hand as MJCF fragments and the names a scene and an engine need.
#[derive(Debug, Clone, PartialEq)]
pub struct HandMjcf {
    /// One `<body name="{root_body}" childclass="pomdar_hand">…</body>` subtree: the hand's
    /// root link at its parent's origin, to be placed inside a mount body.
    pub body: String,
    /// `<default class="pomdar_hand">…</default>`, to be placed inside the scene's `<default>`.
    pub defaults: String,
    /// `<position …/>` elements (no enclosing `<actuator>`), one per degree of freedom, in
    /// [`HandModel::dofs`] order.
    pub actuators: String,
    /// `<joint joint1=… joint2=… polycoef=…/>` elements (no enclosing `<equality>`) holding
    /// coupled joints on their drivers; empty without coupled joints.
    pub equalities: String,
    /// `<exclude body1=… body2=…/>` elements (no enclosing `<contact>`); empty: contact bits
    /// keep a digit from colliding with itself and the palm (see the module docs).
    pub contact_excludes: String,
    /// MJCF joint name per degree of freedom ([`HandModel::ros_dof_names`]).
    pub dof_joints: Vec<String>,
    /// MJCF actuator name per degree of freedom (the same names as the joints).
    pub dof_actuators: Vec<String>,
    /// Body names of the five fingertip links, in [`Finger::ALL`] order.
    pub tip_bodies: [String; 5],
    /// Body name of the palm link.
    pub palm_body: String,
    /// Body name of the hand's root link (the outermost body of [`HandMjcf::body`]).
    pub root_body: String,
    /// The real hand's joint speed, rad/s, for the engine's rate limit on controls.
    pub max_speed_rad_s: f64,
    /// `<mesh>`, `<material>` and `<texture>` elements (no enclosing `<asset>`) the hand's
    /// geoms use; empty for a hand of primitives.
    pub assets: String,
    /// Per degree of freedom, MuJoCo's `qpos` minus the URDF angle (a joint's `ref`): a command
    /// in URDF angles is sent as angle + offset and a measured `qpos` read as qpos − offset.
    /// Zero for a hand written from the URDF.
    pub zero_offsets_rad: Vec<f64>,
    /// The Euler sequence the hand's `euler` attributes use (`<compiler eulerseq>`), if not
    /// MuJoCo's default.
    pub eulerseq: Option<String>,
    /// Suggested pose of the hand's root in an arm flange frame whose +z points away from the
    /// arm: fingers extended along +z, palm facing +x, the wrist on the flange axis and the
    /// hand's nearest link origin one `palm_radius_m` beyond the flange face.
    pub mount: Isometry3<f64>,
}

/// [`HandMjcf::mount`] of `model`'s hand, without writing the hand.
pub(crate) fn hand_mount(model: &HandModel, options: &HandMjcfOptions) -> Isometry3<f64> {
    mount_pose(&HandTree::new(model, options))
}

/// Write `model` as MJCF with the servo and contact parameters of `options`.
pub fn hand_mjcf(model: &HandModel, options: &HandMjcfOptions) -> HandMjcf {
    let tree = HandTree::new(model, options);
    let dof_joints = model.ros_dof_names().to_vec();
    let name_of = |link: LinkId| tree.body_names[link.index()].clone();
    let frames = model.frames();
    HandMjcf {
        body: tree.body_xml(),
        defaults: defaults_xml(options),
        actuators: actuators_xml(model),
        equalities: tree.equalities_xml(),
        contact_excludes: String::new(),
        dof_actuators: dof_joints.clone(),
        dof_joints,
        tip_bodies: frames.tips.map(name_of),
        palm_body: name_of(frames.palm),
        root_body: tree.body_names[0].clone(),
        assets: String::new(),
        zero_offsets_rad: vec![0.0; model.dof()],
        eulerseq: None,
        max_speed_rad_s: options.max_speed_rad_s,
        mount: mount_pose(&tree),
    }
}

/// Which contact group a link's geoms belong to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Group {
    /// The palm, the links above it (wrist, mount) and links shared by several digits.
    Palm,
    /// One digit, by [`Finger::index`].
    Digit(usize),
}

impl Group {
    fn radius(self, options: &HandMjcfOptions) -> f64 {
        match self {
            Group::Palm => options.palm_radius_m,
            Group::Digit(_) => options.finger_radius_m,
        }
    }

    fn contype(self) -> u32 {
        match self {
            Group::Palm => PALM_BIT,
            Group::Digit(f) => FIRST_DIGIT_BIT << f,
        }
    }

    /// Palm: the world only. A digit: the world and the other digits.
    fn conaffinity(self) -> u32 {
        match self {
            Group::Palm => WORLD_BIT,
            Group::Digit(f) => WORLD_BIT | (ALL_DIGIT_BITS & !(FIRST_DIGIT_BIT << f)),
        }
    }
}

/// A collision shape in its link's frame.
#[derive(Debug, Clone, PartialEq)]
enum Shape {
    Sphere {
        center: Vector3<f64>,
        radius: f64,
    },
    Capsule {
        from: Vector3<f64>,
        to: Vector3<f64>,
        radius: f64,
    },
    Box {
        center: Vector3<f64>,
        rotation: UnitQuaternion<f64>,
        half_size: Vector3<f64>,
    },
}

impl Shape {
    /// Mass at [`HAND_DENSITY_KG_M3`] (as MuJoCo computes it), centre of mass in the link
    /// frame, and a bound on its largest central moment of inertia, kg·m².
    fn mass_properties(&self) -> (f64, Vector3<f64>, f64) {
        let ball = |r: f64| 4.0 / 3.0 * PI * r.powi(3);
        match self {
            Shape::Sphere { center, radius } => {
                let mass = HAND_DENSITY_KG_M3 * ball(*radius);
                (mass, *center, 0.4 * mass * radius.powi(2))
            }
            Shape::Capsule { from, to, radius } => {
                let length = (to - from).norm();
                let volume = PI * radius.powi(2) * length + ball(*radius);
                let mass = HAND_DENSITY_KG_M3 * volume;
                let span = length + 2.0 * radius;
                let own = mass * (span.powi(2) / 12.0 + radius.powi(2) / 4.0);
                (mass, (from + to) / 2.0, own)
            }
            Shape::Box {
                center, half_size, ..
            } => {
                let mass = HAND_DENSITY_KG_M3 * 8.0 * half_size.x * half_size.y * half_size.z;
                let squares = half_size.component_mul(half_size);
                let own = mass * (squares.sum() - squares.min()) / 3.0;
                (mass, *center, own)
            }
        }
    }
}

/// The model with the lookups the writer needs.
struct HandTree<'a> {
    model: &'a HandModel,
    options: &'a HandMjcfOptions,
    /// Per link: indices (into [`HandModel::joints`]) of the joints it is the parent of.
    children: Vec<Vec<usize>>,
    /// Per link: the joint it is the child of (none for the root).
    parent_joint: Vec<Option<usize>>,
    /// Per link: its body name.
    body_names: Vec<String>,
    /// Per joint: its hinge name (none for fixed joints).
    hinge_names: Vec<Option<String>>,
    /// Per link: its contact group.
    groups: Vec<Group>,
    /// Every link posed at the zero pose.
    rest: FkState,
    /// Per link: its pose at the zero pose, in the root frame.
    rest_poses: Vec<Isometry3<f64>>,
}

impl<'a> HandTree<'a> {
    fn new(model: &'a HandModel, options: &'a HandMjcfOptions) -> Self {
        let mut children = vec![Vec::new(); model.link_count()];
        let mut parent_joint = vec![None; model.link_count()];
        for (index, joint) in model.joints().iter().enumerate() {
            children[joint.parent.index()].push(index);
            parent_joint[joint.child.index()] = Some(index);
        }
        let rest = zero_pose_fk(model);
        let mut rest_poses = vec![Isometry3::identity(); model.link_count()];
        for joint in model.joints() {
            rest_poses[joint.child.index()] = *rest.pose(joint.child);
        }
        let mut tree = HandTree {
            model,
            options,
            children,
            parent_joint,
            body_names: body_names(model),
            hinge_names: hinge_names(model),
            groups: Vec::new(),
            rest,
            rest_poses,
        };
        tree.groups = tree.contact_groups();
        tree
    }

    /// The link and its ancestors up to the root.
    fn ancestors_or_self(&self, link: usize) -> Vec<usize> {
        let mut chain = vec![link];
        let mut current = link;
        while let Some(joint) = self.parent_joint[current] {
            current = self.model.joints()[joint].parent.index();
            chain.push(current);
        }
        chain
    }

    /// A digit's links are those between the palm and its tip (and what hangs from them);
    /// the palm, the links above it and links two digits share form the palm group.
    fn contact_groups(&self) -> Vec<Group> {
        let frames = self.model.frames();
        let above_palm = self.ancestors_or_self(frames.palm.index());
        let mut groups: Vec<Option<Group>> = vec![None; self.model.link_count()];
        for finger in Finger::ALL {
            for link in self.ancestors_or_self(frames.tip(finger).index()) {
                if above_palm.contains(&link) {
                    continue;
                }
                groups[link] = match groups[link] {
                    None => Some(Group::Digit(finger.index())),
                    Some(_) => Some(Group::Palm),
                };
            }
        }
        groups[0].get_or_insert(Group::Palm);
        for joint in self.model.joints() {
            let parent = groups[joint.parent.index()];
            groups[joint.child.index()] = groups[joint.child.index()].or(parent);
        }
        groups
            .into_iter()
            .map(|group| group.unwrap_or(Group::Palm))
            .collect()
    }
}

/// Writing the body tree.
impl HandTree<'_> {
    fn body_xml(&self) -> String {
        let mut out = format!(
            "<body name=\"{}\" childclass=\"{HAND_CLASS}\" gravcomp=\"1\">\n",
            escape(&self.body_names[0])
        );
        self.write_link_contents(0, 1, &mut out);
        out.push_str("</body>\n");
        out
    }

    /// The link's hinge, geoms and child bodies, indented `depth` levels.
    fn write_link_contents(&self, link: usize, depth: usize, out: &mut String) {
        let pad = "  ".repeat(depth);
        if let Some(hinge) = self.parent_joint[link].and_then(|j| self.hinge_xml(j)) {
            out.push_str(&format!("{pad}{hinge}\n"));
        }
        for shape in self.link_shapes(link) {
            out.push_str(&format!("{pad}{}\n", shape_xml(&shape, self.groups[link])));
        }
        for &index in &self.children[link] {
            let joint = &self.model.joints()[index];
            let child = joint.child.index();
            out.push_str(&format!(
                "{pad}<body name=\"{}\" pos=\"{}\" quat=\"{}\" gravcomp=\"1\">\n",
                escape(&self.body_names[child]),
                vec3(&joint.origin.translation.vector),
                quat(&joint.origin.rotation),
            ));
            self.write_link_contents(child, depth + 1, out);
            out.push_str(&format!("{pad}</body>\n"));
        }
    }

    /// A revolute joint's hinge: a degree of freedom's within its limits (the joint's own
    /// intersected with its coupled joints'), a coupled joint's within its own.
    fn hinge_xml(&self, index: usize) -> Option<String> {
        let JointMotion::Revolute {
            axis, dof, limits, ..
        } = &self.model.joints()[index].motion
        else {
            return None;
        };
        let dof = &self.model.dofs()[*dof];
        let range = if dof.joint == index {
            dof.limits
        } else {
            *limits
        };
        let damping = self.hinge_damping(index, axis);
        let raised = if damping > self.options.joint_damping {
            format!(" damping=\"{}\"", num(damping))
        } else {
            String::new()
        };
        Some(format!(
            "<joint name=\"{}\" type=\"hinge\" axis=\"{}\" range=\"{} {}\"{raised}/>",
            escape(self.hinge_names[index].as_deref().unwrap_or_default()),
            vec3(axis),
            num(range.lower_rad),
            num(range.upper_rad),
        ))
    }

    /// `joint_damping`, raised to critical damping of the position servo, `2 √(kp · I)`, for
    /// a hinge whose load `I` (its armature and everything it moves, about its axis at the
    /// zero pose) needs more: the wrist, which carries the whole hand.
    fn hinge_damping(&self, index: usize, axis: &Unit<Vector3<f64>>) -> f64 {
        let child = self.model.joints()[index].child.index();
        let pose = self.rest_poses[child];
        let axis = pose.rotation * axis.into_inner();
        let pivot = Point3::from(pose.translation.vector);
        let mut inertia = self.options.armature;
        for link in 0..self.model.link_count() {
            if !self.ancestors_or_self(link).contains(&child) {
                continue;
            }
            for shape in self.link_shapes(link) {
                let (mass, centre, own) = shape.mass_properties();
                let offset = self.rest_poses[link] * Point3::from(centre) - pivot;
                let radial = offset - axis * offset.dot(&axis);
                inertia += mass * radial.norm_squared() + own;
            }
        }
        let critical = 2.0 * (self.options.position_gain * inertia).sqrt();
        self.options.joint_damping.max(critical)
    }

    /// A knuckle at a hinged link's origin; the palm box on the palm; elsewhere a capsule
    /// along every child joint's offset, stopping one radius short of a leaf link.
    fn link_shapes(&self, link: usize) -> Vec<Shape> {
        let radius = self.groups[link].radius(self.options);
        let mut shapes = Vec::new();
        let hinged = self.parent_joint[link]
            .is_some_and(|j| matches!(self.model.joints()[j].motion, JointMotion::Revolute { .. }));
        if hinged {
            shapes.push(Shape::Sphere {
                center: Vector3::zeros(),
                radius,
            });
        }
        if link == self.model.frames().palm.index() {
            shapes.push(self.palm_box());
            return shapes;
        }
        for &index in &self.children[link] {
            let joint = &self.model.joints()[index];
            let ends_at_leaf = self.children[joint.child.index()].is_empty();
            shapes.extend(segment(
                &joint.origin.translation.vector,
                radius,
                ends_at_leaf,
            ));
        }
        shapes
    }

    /// The palm frame at the zero pose (rigid with the palm link); the palm link's own
    /// frame should the landmarks not span one (a validated model always does).
    fn palm_frame(&self) -> PalmFrame {
        self.model.palm_frame(&self.rest).unwrap_or_else(|_| {
            let palm = self.rest.pose(self.model.frames().palm);
            PalmFrame {
                origin: Point3::from(palm.translation.vector),
                rotation: palm.rotation.to_rotation_matrix(),
            }
        })
    }

    /// A box in the palm frame's axes spanning the wrist and the digit bases across and
    /// along the palm, `2 · palm_radius_m` thick, centred between their lowest and highest.
    fn palm_box(&self) -> Shape {
        let frames = self.model.frames();
        let frame = self.palm_frame();
        let landmarks = std::iter::once(frames.wrist).chain(frames.bases);
        let points: Vec<Vector3<f64>> = landmarks
            .map(|link| frame.point_to_palm(&self.rest.position(link)))
            .collect();
        let lower = points
            .iter()
            .fold(Vector3::repeat(f64::INFINITY), |a, p| a.inf(p));
        let upper = points
            .iter()
            .fold(Vector3::repeat(f64::NEG_INFINITY), |a, p| a.sup(p));
        // At least as wide and long as it is thick (landmarks in a line leave an edge flat).
        let radius = self.options.palm_radius_m;
        let mut half_size = ((upper - lower) / 2.0).map(|v| v.max(radius));
        half_size.z = radius;
        let center_in_palm = (upper + lower) / 2.0;
        let palm = self.rest.pose(frames.palm);
        let center =
            palm.inverse_transform_point(&(frame.origin + frame.rotation * center_in_palm));
        Shape::Box {
            center: center.coords,
            rotation: palm.rotation.inverse()
                * UnitQuaternion::from_rotation_matrix(&frame.rotation),
            half_size,
        }
    }

    /// `<joint joint1=coupled joint2=driver polycoef="offset multiplier 0 0 0"/>` per
    /// coupled joint: MuJoCo's `q1 − q1₀ = Σ aᵢ (q2 − q2₀)ⁱ` with both references zero.
    fn equalities_xml(&self) -> String {
        let mut out = String::new();
        for (index, joint) in self.model.joints().iter().enumerate() {
            let JointMotion::Revolute {
                dof,
                multiplier,
                offset_rad,
                ..
            } = &joint.motion
            else {
                continue;
            };
            let driver = self.model.dofs()[*dof].joint;
            if driver == index {
                continue;
            }
            let name = escape(self.hinge_names[index].as_deref().unwrap_or_default());
            let driver = escape(self.hinge_names[driver].as_deref().unwrap_or_default());
            out.push_str(&format!(
                "<joint name=\"{name}_coupling\" class=\"{HAND_CLASS}\" joint1=\"{name}\" \
                 joint2=\"{driver}\" polycoef=\"{} {} 0 0 0\"/>\n",
                num(*offset_rad),
                num(*multiplier),
            ));
        }
        out
    }

    /// +1 when the palm frame's z points out of the palmar side, the side the fingers flex
    /// towards (a right hand); −1 when it points out of the back (a left hand). Found by
    /// moving every joint below the palm halfway to its farther limit (flexion ranges are
    /// the long ones) and watching the middle fingertip.
    fn palmar_sign(&self, frame: &PalmFrame) -> f64 {
        let above_palm = self.ancestors_or_self(self.model.frames().palm.index());
        let mut flexed = self.model.zero_pose();
        for (value, dof) in flexed.iter_mut().zip(self.model.dofs()) {
            let joint = &self.model.joints()[dof.joint];
            if !above_palm.contains(&joint.child.index()) {
                let (lower, upper) = (dof.limits.lower_rad, dof.limits.upper_rad);
                *value = 0.5
                    * if upper.abs() >= lower.abs() {
                        upper
                    } else {
                        lower
                    };
            }
        }
        let mut state = self.model.fk_state();
        if self.model.forward(&flexed, &mut state).is_err() {
            return 1.0;
        }
        let tip = self.model.frames().tip(Finger::Middle);
        let moved = state.position(tip) - self.rest.position(tip);
        if moved.dot(&(frame.rotation * Vector3::z())) < 0.0 {
            -1.0
        } else {
            1.0
        }
    }
}

/// The suggested pose of the hand's root in an arm flange frame (+z away from the arm):
/// the palm → middle fingertip direction at the zero pose along +z, the palmar normal
/// (orthogonalised) along +x; the wrist on the z axis and the nearest link origin one palm
/// radius beyond the flange face.
fn mount_pose(tree: &HandTree) -> Isometry3<f64> {
    let frames = tree.model.frames();
    let frame = tree.palm_frame();
    let palm_to_tip =
        tree.rest.position(frames.tip(Finger::Middle)) - tree.rest.position(frames.palm);
    let along = palm_to_tip
        .try_normalize(1e-9)
        .unwrap_or_else(|| frame.rotation * Vector3::y());
    let normal = frame.rotation * Vector3::z() * tree.palmar_sign(&frame);
    let across = (normal - along * normal.dot(&along))
        .try_normalize(1e-9)
        .unwrap_or_else(|| frame.rotation * Vector3::x());
    let sideways = along.cross(&across);
    let rows = [across.transpose(), sideways.transpose(), along.transpose()];
    let to_flange = UnitQuaternion::from_matrix(&Matrix3::from_rows(&rows));
    let wrist = to_flange * tree.rest.position(frames.wrist).coords;
    let nearest = (tree.rest_poses.iter())
        .map(|pose| (to_flange * pose.translation.vector).z)
        .fold(f64::INFINITY, f64::min);
    Isometry3::from_parts(
        Translation3::new(-wrist.x, -wrist.y, tree.options.palm_radius_m - nearest),
        to_flange,
    )
}

/// A capsule from a link's origin to `offset`, stopping `radius` short when it ends at a
/// leaf link (a fingertip: the rounded end then sits on the tip frame); none when too short.
fn segment(offset: &Vector3<f64>, radius: f64, ends_at_leaf: bool) -> Option<Shape> {
    let length = offset.norm();
    let reach = if ends_at_leaf {
        length - radius
    } else {
        length
    };
    (reach >= MIN_SEGMENT_M).then(|| Shape::Capsule {
        from: Vector3::zeros(),
        to: offset * (reach / length),
        radius,
    })
}

/// Every link's body name: its ROS name, but a root called `world` (MuJoCo's name for the
/// world body) becomes `{model name}_root`.
fn body_names(model: &HandModel) -> Vec<String> {
    let mut names = model.ros_link_names().to_vec();
    if names.first().is_some_and(|root| root == "world") {
        names[0] = format!("{}_root", model.name());
    }
    names
}

/// Every joint's hinge name: a degree of freedom's ROS name, a coupled joint's name with the
/// model's prefix; none for fixed joints.
fn hinge_names(model: &HandModel) -> Vec<Option<String>> {
    let joints = model.joints().iter().enumerate();
    joints
        .map(|(index, joint)| match joint.motion {
            JointMotion::Fixed => None,
            JointMotion::Revolute { dof, .. } if model.dofs()[dof].joint == index => {
                Some(model.ros_dof_names()[dof].clone())
            }
            JointMotion::Revolute { .. } => Some(format!("{}{}", model.name_prefix(), joint.name)),
        })
        .collect()
}

/// Every link at the zero pose. `zero_pose` has one value per degree of freedom, so the
/// forward kinematics cannot fail; were it to, the poses would stay at the identity.
fn zero_pose_fk(model: &HandModel) -> FkState {
    let mut state = model.fk_state();
    if model.forward(&model.zero_pose(), &mut state).is_err() {
        state = model.fk_state();
    }
    state
}

impl HandMjcfOptions {
    /// The contact attributes of the hand's geoms (`condim`, `friction`, `solref`, `solimp`,
    /// `margin`), as MJCF attribute names and values. The contact dimension follows the
    /// friction: 6 with rolling friction, 4 with torsional, else 3.
    pub fn contact_attributes(&self) -> Vec<(&'static str, String)> {
        let [_, torsional, rolling] = self.friction;
        let condim = if rolling > 0.0 {
            6
        } else if torsional > 0.0 {
            4
        } else {
            3
        };
        vec![
            ("condim", condim.to_string()),
            ("friction", nums(&self.friction)),
            ("solref", nums(&self.contact_solref)),
            ("solimp", nums(&self.contact_solimp)),
            ("margin", num(self.contact_margin_m)),
        ]
    }
}

/// The default class: contact and mass of geoms, hinge dynamics, servo gain and limits.
fn defaults_xml(options: &HandMjcfOptions) -> String {
    let contact: String = options
        .contact_attributes()
        .iter()
        .map(|(name, value)| format!(" {name}=\"{value}\""))
        .collect();
    let torque = num(options.max_torque_nm);
    format!(
        "<default class=\"{HAND_CLASS}\">\n\
         \x20 <geom type=\"capsule\"{contact} density=\"{}\" rgba=\"{HAND_RGBA}\"/>\n\
         \x20 <joint type=\"hinge\" limited=\"true\" solreflimit=\"{LIMIT_TIME_CONSTANT_S} 1\" \
         damping=\"{}\" armature=\"{}\" \
         actuatorgravcomp=\"true\" actuatorfrclimited=\"true\" actuatorfrcrange=\"-{torque} {torque}\"/>\n\
         \x20 <position kp=\"{}\" ctrllimited=\"true\" forcelimited=\"true\" \
         forcerange=\"-{torque} {torque}\"/>\n\
         </default>\n",
        num(HAND_DENSITY_KG_M3),
        num(options.joint_damping),
        num(options.armature),
        num(options.position_gain),
    )
}

/// One position actuator per degree of freedom, on its hinge, commanding within its limits.
fn actuators_xml(model: &HandModel) -> String {
    let mut out = String::new();
    for (dof, name) in model.dofs().iter().zip(model.ros_dof_names()) {
        let name = escape(name);
        out.push_str(&format!(
            "<position name=\"{name}\" class=\"{HAND_CLASS}\" joint=\"{name}\" ctrlrange=\"{} {}\"/>\n",
            num(dof.limits.lower_rad),
            num(dof.limits.upper_rad),
        ));
    }
    out
}

/// A geom element with its group's contact bits.
fn shape_xml(shape: &Shape, group: Group) -> String {
    let bits = format!(
        "contype=\"{}\" conaffinity=\"{}\"",
        group.contype(),
        group.conaffinity()
    );
    match shape {
        Shape::Sphere { center, radius } => format!(
            "<geom type=\"sphere\" size=\"{}\" pos=\"{}\" {bits}/>",
            num(*radius),
            vec3(center)
        ),
        Shape::Capsule { from, to, radius } => format!(
            "<geom type=\"capsule\" size=\"{}\" fromto=\"{} {}\" {bits}/>",
            num(*radius),
            vec3(from),
            vec3(to)
        ),
        Shape::Box {
            center,
            rotation,
            half_size,
        } => format!(
            "<geom type=\"box\" size=\"{}\" pos=\"{}\" quat=\"{}\" {bits}/>",
            vec3(half_size),
            vec3(center),
            quat(rotation)
        ),
    }
}

/// A number as MJCF reads it (shortest round-trip decimal; rounding noise written as 0).
fn num(value: f64) -> String {
    if value.abs() < ZERO_SNAP {
        "0".into()
    } else {
        format!("{value}")
    }
}

/// Numbers separated by spaces (`solref`, `solimp`).
fn nums(values: &[f64]) -> String {
    values.iter().map(|v| num(*v)).collect::<Vec<_>>().join(" ")
}

fn vec3(v: &Vector3<f64>) -> String {
    format!("{} {} {}", num(v.x), num(v.y), num(v.z))
}

/// MJCF's quaternion order: w x y z.
fn quat(q: &UnitQuaternion<f64>) -> String {
    format!("{} {} {} {}", num(q.w), num(q.i), num(q.j), num(q.k))
}

/// `text` safe inside a double-quoted XML attribute.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            _ => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests;
