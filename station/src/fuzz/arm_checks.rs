//! Invariants of the arm targets, checked on every output:
//!
//! - `arm_finite`: finite position, unit quaternion;
//! - `arm_stamp`: stamped with the station clock, in the configured frame;
//! - `arm_engaged`: none while disengaged (from a disengage until an engage is granted) or
//!   while another publisher drives the arm topic;
//! - `arm_clutched`: none before the clutch latched afresh after the last engage (at the first
//!   tick with a wrist pose), and the first one is the robot's pose as latched (its feedback,
//!   the start pose without one);
//! - `arm_workspace`: inside the workspace box;
//! - `arm_constraint`: `fixed` stays at the latched pose; an axis constraint stays on the line
//!   through it along its axis (1e-9 m) with the latched orientation;
//! - `arm_step`: within `max_translation_step_m` and `max_rotation_step_rad` of the previous
//!   target of the same engagement.

use msgs::{PoseStamped, Time};
use nalgebra::{Isometry3, Unit, Vector3};

use super::tally::Tally;
use crate::arm::{ArmConfig, Constraint, OrientationPolicy, PoseRole, WorkspaceBox, checked_pose};
use crate::convert::pose_to_isometry;
use crate::station_input::{ControlInput, Notice, StationInput, StationOutputs};

/// Tolerance of "on the axis line" and "at the latched pose", metres.
const ON_LINE_M: f64 = 1e-9;
/// Rounding allowance on the step caps and orientations.
const SLACK_M: f64 = 1e-12;
const SLACK_RAD: f64 = 1e-9;

/// What the arm checks remember between steps.
#[derive(Debug, Clone)]
pub struct ArmTrack {
    workspace: WorkspaceBox,
    axis: Option<Unit<Vector3<f64>>>,
    constraint: Constraint,
    holds_orientation: bool,
    max_step_m: f64,
    max_step_rad: f64,
    start_pose: Isometry3<f64>,
    frame_id: String,
    feedback: Option<Isometry3<f64>>,
    wrist_seen: bool,
    blocked: bool,
    latch_due: bool,
    /// The robot pose latched at the current engagement, and the last target since.
    latched: Option<(Isometry3<f64>, Isometry3<f64>)>,
    /// The next target is the first since the latch.
    first: bool,
}

impl ArmTrack {
    /// The checks for an arm configured by `arm`, targets in frame `frame_id`.
    pub fn new(arm: &ArmConfig, frame_id: &str) -> ArmTrack {
        let constraint = arm.constraint;
        let holds_orientation = match (constraint, arm.orientation) {
            (Constraint::Free, OrientationPolicy::Hold) => true,
            (Constraint::Free, _) => false,
            (Constraint::Fixed, _) => true,
            (_, policy) => policy != OrientationPolicy::TwistAboutAxis,
        };
        ArmTrack {
            workspace: arm.workspace(),
            axis: arm.axis_of(constraint).ok().flatten(),
            constraint,
            holds_orientation,
            max_step_m: arm.max_translation_step_m,
            max_step_rad: arm.max_rotation_step_rad,
            start_pose: arm
                .start_pose_isometry()
                .unwrap_or_else(|_| Isometry3::identity()),
            frame_id: frame_id.to_string(),
            feedback: None,
            wrist_seen: false,
            blocked: false,
            latch_due: false,
            latched: None,
            first: false,
        }
    }

    /// Follow an input (before its outputs are checked).
    pub fn input(&mut self, input: &StationInput) {
        match input {
            StationInput::ArmFeedback(pose) => {
                if let Some(robot) = pose_to_isometry(pose) {
                    self.feedback = Some(robot);
                }
            }
            StationInput::Wrist(pose) => self.wrist_seen |= pose_to_isometry(pose).is_some(),
            StationInput::Control(ControlInput::ArmBlocked { blocked }) => self.blocked = *blocked,
            _ => {}
        }
    }

    /// The station engaged from disengaged: the clutch latches afresh at the next tick with
    /// a wrist pose.
    pub fn engaged(&mut self) {
        self.latch_due = true;
        self.latched = None;
    }

    /// The station disengaged: the clutch is released.
    pub fn disengaged(&mut self) {
        self.latch_due = false;
        self.latched = None;
    }

    /// A tick while engaged: the clutch latches if due (unless the station said it could
    /// not).
    pub fn engaged_tick(&mut self, outputs: &StationOutputs) {
        if !(self.latch_due && self.wrist_seen) {
            return;
        }
        self.latch_due = false;
        let refused = outputs
            .notices
            .iter()
            .any(|n| matches!(n, Notice::ArmNotEngaged(_)));
        let robot = self.feedback.unwrap_or(self.start_pose);
        let robot = checked_pose(&robot, PoseRole::RobotEndEffector).ok();
        self.latched = robot.filter(|_| !refused).map(|r| (r, r));
        // Blocked at the latch, the first target sent may be a capped step from the robot.
        self.first = !self.blocked;
    }

    /// Check the arm output of one step.
    pub fn check(&mut self, outputs: &StationOutputs, ctx: (u64, i64, bool), tally: &mut Tally) {
        let (step, now_ns, disengaged) = ctx;
        let Some(target) = &outputs.arm else { return };
        tally.count("out.arm");
        let Some(pose) = self.check_message(step, target, now_ns, tally) else {
            return;
        };
        tally.check(step, "arm_engaged", !disengaged && !self.blocked, || {
            format!(
                "an arm target while disengaged ({disengaged}) or blocked ({})",
                self.blocked
            )
        });
        tally.check(step, "arm_clutched", self.latched.is_some(), || {
            "an arm target before the clutch latched afresh".into()
        });
        let inside = self.workspace.contains(&pose.translation.vector);
        tally.check(step, "arm_workspace", inside, || {
            format!("{pose} outside the box")
        });
        let Some((robot, previous)) = self.latched else {
            return;
        };
        if std::mem::take(&mut self.first) {
            let moved = (pose.translation.vector - robot.translation.vector).norm();
            let turned = pose.rotation.angle_to(&robot.rotation);
            tally.check(
                step,
                "arm_clutched",
                moved <= ON_LINE_M && turned <= SLACK_RAD,
                || format!("first target {moved} m, {turned} rad from the latched robot pose"),
            );
        }
        self.check_constraint(step, &pose, &robot, tally);
        let moved = (pose.translation.vector - previous.translation.vector).norm();
        let turned = pose.rotation.angle_to(&previous.rotation);
        let within = moved <= self.max_step_m + SLACK_M && turned <= self.max_step_rad + SLACK_RAD;
        tally.check(step, "arm_step", within, || {
            format!("a step of {moved} m, {turned} rad")
        });
        self.latched = Some((robot, pose));
    }

    fn check_message(
        &self,
        step: u64,
        target: &PoseStamped,
        now_ns: i64,
        tally: &mut Tally,
    ) -> Option<Isometry3<f64>> {
        let p = &target.pose.position;
        let q = &target.pose.orientation;
        let finite = [p.x, p.y, p.z, q.x, q.y, q.z, q.w]
            .iter()
            .all(|v| v.is_finite());
        let norm = (q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w).sqrt();
        let unit = (norm - 1.0).abs() <= SLACK_RAD;
        tally.check(step, "arm_finite", finite && unit, || {
            format!("{:?}", target.pose)
        });
        let stamped = target.header.stamp == Time::from_nanos(now_ns)
            && target.header.frame_id == self.frame_id;
        tally.check(step, "arm_stamp", stamped, || {
            format!("{:?}", target.header)
        });
        pose_to_isometry(&target.pose)
    }

    fn check_constraint(
        &self,
        step: u64,
        pose: &Isometry3<f64>,
        robot: &Isometry3<f64>,
        tally: &mut Tally,
    ) {
        let d = pose.translation.vector - robot.translation.vector;
        let off_line = match (self.constraint, &self.axis) {
            (Constraint::Fixed, _) => d.norm(),
            (Constraint::VerticalAxis | Constraint::HorizontalAxis, Some(a)) => {
                (d - a.into_inner() * a.dot(&d)).norm()
            }
            _ => 0.0,
        };
        let turned = if self.holds_orientation {
            pose.rotation.angle_to(&robot.rotation)
        } else {
            0.0
        };
        if self.constraint != Constraint::Free || self.holds_orientation {
            tally.check(
                step,
                "arm_constraint",
                off_line <= ON_LINE_M && turned <= SLACK_RAD,
                || format!("{off_line} m off the constraint, turned {turned} rad from the latch"),
            );
        }
    }
}
