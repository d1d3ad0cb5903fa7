//! The `retarget` crate's one error type: malformed models, configurations and inputs.
//!
//! Every variant names the element (joint, link, frame, key) and the problem, so an operator
//! onboarding a new hand can fix the file without reading code.

use std::path::PathBuf;

/// Malformed input to the `retarget` crate: a hand model (URDF or the project's TOML model
/// format), an embodiment or configuration file, or a wrongly shaped argument.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum Error {
    /// The problem was found in this file.
    #[error("{path}: {source}")]
    InFile {
        /// The file that was read.
        path: PathBuf,
        /// What is wrong with it.
        source: Box<Error>,
    },
    /// The file could not be read at all.
    #[error("cannot read the file: {reason}")]
    Read {
        /// The operating system's reason.
        reason: String,
    },
    /// The TOML model description does not parse or has an unknown/missing key.
    #[error("invalid model description: {reason}")]
    Syntax {
        /// The parser's message, with line, column and key.
        reason: String,
    },
    /// The URDF is not well-formed XML or misses a required element or attribute.
    #[error("invalid URDF: {reason}")]
    Urdf {
        /// The URDF parser's message.
        reason: String,
    },
    /// One `<joint>` or `<link>` element of a URDF is incomplete or malformed.
    #[error("invalid URDF: {element} (line {line}): {reason}")]
    UrdfElement {
        /// The element, as `joint 'index_mcp'`.
        element: String,
        /// Line of the element's start tag (1-based).
        line: u32,
        /// What the URDF parser found wrong.
        reason: String,
    },
    /// The model has no joints at all.
    #[error("the model has no joints")]
    NoJoints,
    /// Two joints share a name.
    #[error("joint '{joint}' is defined twice")]
    DuplicateJoint {
        /// The repeated name.
        joint: String,
    },
    /// A joint refers to a link that the URDF never declares.
    #[error("joint '{joint}': {role} link '{link}' is not declared as a <link>")]
    UndeclaredLink {
        /// The joint.
        joint: String,
        /// `parent` or `child`.
        role: &'static str,
        /// The missing link.
        link: String,
    },
    /// A joint has the same link as parent and child.
    #[error("joint '{joint}': parent and child are the same link '{link}'")]
    SelfLoop {
        /// The joint.
        joint: String,
        /// The link.
        link: String,
    },
    /// A link is the child of two joints (the kinematic graph is not a tree).
    #[error("link '{link}' is the child of two joints, '{first}' and '{second}'")]
    TwoParents {
        /// The link.
        link: String,
        /// The first joint naming it as child.
        first: String,
        /// The second joint naming it as child.
        second: String,
    },
    /// The kinematic graph has no single root link.
    #[error(
        "the model must have exactly one root link (a link that is no joint's child); found {roots:?}"
    )]
    RootCount {
        /// The root candidates found (empty when every link is a child: a cycle).
        roots: Vec<String>,
    },
    /// Some links cannot be reached from the root: they form a cycle.
    #[error("links {links:?} are not reachable from root '{root}' (the joints form a cycle)")]
    Cycle {
        /// The root link.
        root: String,
        /// The unreachable links.
        links: Vec<String>,
    },
    /// A joint type the station does not model.
    #[error(
        "joint '{joint}': type '{kind}' is not supported (only revolute, continuous and fixed)"
    )]
    UnsupportedJointType {
        /// The joint.
        joint: String,
        /// The type as written.
        kind: String,
    },
    /// A number in the model is NaN or infinite.
    #[error("joint '{joint}': {field} must be finite, got {value}")]
    NonFinite {
        /// The joint.
        joint: String,
        /// The field (`xyz`, `rpy`, `axis`, `lower`, `upper`, `multiplier`, `offset`).
        field: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A finite number outside the range a hand model can sensibly hold (a unit error or a
    /// corrupted file: offsets of kilometres overflow the forward kinematics).
    #[error("joint '{joint}': {field} = {} is outside the allowed range {allowed}", compact(*.value))]
    OutOfRange {
        /// The joint.
        joint: String,
        /// The field, as in [`Error::NonFinite`].
        field: &'static str,
        /// The offending value.
        value: f64,
        /// The allowed range, with its unit.
        allowed: &'static str,
    },
    /// A revolute joint axis of (near) zero length.
    #[error("joint '{joint}': axis {axis:?} has zero length")]
    ZeroAxis {
        /// The joint.
        joint: String,
        /// The axis as written.
        axis: [f64; 3],
    },
    /// Joint limits missing or not ordered.
    #[error(
        "joint '{joint}': limits must satisfy lower < upper (radians), got lower = {lower}, upper = {upper}"
    )]
    InvalidLimits {
        /// The joint.
        joint: String,
        /// Lower limit as read.
        lower: f64,
        /// Upper limit as read.
        upper: f64,
    },
    /// A revolute joint lacks a field it needs.
    #[error("joint '{joint}': a revolute joint needs '{field}'")]
    MissingField {
        /// The joint.
        joint: String,
        /// The missing field (`axis`, `lower_rad`, `upper_rad`).
        field: &'static str,
    },
    /// A fixed joint carries fields that only a revolute joint may have.
    #[error("joint '{joint}': a fixed joint cannot have '{field}'")]
    FixedJointField {
        /// The joint.
        joint: String,
        /// The field.
        field: &'static str,
    },
    /// A coupled (mimic) joint names a joint that is not an independent revolute joint.
    #[error("joint '{joint}': coupled to '{target}', which {problem}")]
    BadCoupling {
        /// The coupled joint.
        joint: String,
        /// The joint it follows.
        target: String,
        /// What is wrong with the target.
        problem: &'static str,
    },
    /// A named frame refers to a link that is not in the model.
    #[error("frame '{frame}': link '{link}' is not in the model")]
    MissingFrame {
        /// The frame role (`palm`, `index_tip`, ...).
        frame: String,
        /// The link it names.
        link: String,
    },
    /// The palm frame built from the model's named frames is degenerate.
    #[error("the model's palm frame is degenerate: {reason}")]
    DegeneratePalm {
        /// What collapsed.
        reason: String,
    },
    /// The joint vector has the wrong length.
    #[error("expected {expected} joint values, got {got}")]
    DofMismatch {
        /// The model's number of degrees of freedom.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// The output buffer has the wrong shape.
    #[error("Jacobian buffer must be 3 x {expected}, got 3 x {got}")]
    JacobianShape {
        /// The model's number of degrees of freedom.
        expected: usize,
        /// The buffer's number of columns.
        got: usize,
    },
    /// Keypoints whose palm frame cannot be built.
    #[error("collapsed palm frame: {reason}")]
    CollapsedPalm {
        /// Which axis collapsed, with the measured length.
        reason: String,
    },
    /// A frame of keypoints with the wrong number of points for its layout.
    #[error("keypoints: layout {layout} has {expected} points, got {got}")]
    KeypointCount {
        /// The configured layout.
        layout: &'static str,
        /// Points the layout has.
        expected: usize,
        /// Points received.
        got: usize,
    },
    /// A keypoint coordinate is NaN or infinite.
    #[error("keypoints: point {index} ({name}) is not finite")]
    NonFiniteKeypoint {
        /// Index in the layout.
        index: usize,
        /// The point's name in the layout.
        name: String,
    },
    /// A time step that is not a positive finite number of seconds.
    #[error("time step must be positive and finite, got {dt_s} s")]
    InvalidTimeStep {
        /// The time step given, seconds.
        dt_s: f64,
    },
    /// A configuration value out of its allowed range, or inconsistent with another.
    #[error("config key '{key}' = {value}: {allowed}")]
    ConfigRange {
        /// Dotted key (`pinch.engage_m`).
        key: String,
        /// The value as read.
        value: String,
        /// The allowed range or the rule it breaks.
        allowed: String,
    },
    /// An embodiment definition that cannot be used.
    #[error("embodiment '{embodiment}': {problem}")]
    BadEmbodiment {
        /// The embodiment's name.
        embodiment: String,
        /// What is wrong.
        problem: String,
    },
}

impl Error {
    /// Attach the file the error was found in.
    pub fn in_file(self, path: impl Into<PathBuf>) -> Error {
        Error::InFile {
            path: path.into(),
            source: Box::new(self),
        }
    }
}

/// A number short enough for a message: plain in the everyday range, else scientific.
fn compact(value: f64) -> String {
    if value == 0.0 || (1e-3..1e6).contains(&value.abs()) {
        value.to_string()
    } else {
        format!("{value:e}")
    }
}
