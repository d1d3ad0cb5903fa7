//! The arm mapper ([`ArmMapper`]) and its clutch: engage latches the glove and robot poses, each step maps the glove's motion
//! since engage onto the latched robot pose, disengage stops the output.
//!
//! Per step: validate the glove pose → relative motion in the base frame → task constraint →
//! workspace box → step caps relative to the previous command → rounding guard. See the
//! [`arm`](super) module docs for the maths.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use super::arm_command::ArmCommand;
use super::arm_config::ArmConfig;
use super::arm_error::ArmConfigError;
use super::arm_refusal::{ArmRefusal, PoseRole};
use super::constraint::{AllowedTranslation, Constraint, ResolvedConstraint, constrain};
use super::pose_check::checked_pose;
use super::relative_motion::relative_motion;
use super::step_limits::{cap_rotation, cap_translation};
use super::workspace_box::WorkspaceBox;

/// Maps the glove wrist pose to Franka end-effector targets, with a clutch.
///
/// Synchronous and pure: no clock, no I/O. The caller calls [`step`](ArmMapper::step) once per
/// control tick; the step caps are per call.
#[derive(Debug, Clone)]
pub struct ArmMapper {
    config: ArmConfig,
    glove_to_base: UnitQuaternion<f64>,
    start_pose: Isometry3<f64>,
    workspace: WorkspaceBox,
    constraint: ResolvedConstraint,
    /// The two axis constraints, resolved at set-up (a constraint change cannot fail on them).
    vertical_axis: ResolvedConstraint,
    horizontal_axis: ResolvedConstraint,
    engagement: Option<Engagement>,
    last_command: Option<ArmCommand>,
}

/// What engage latched, and the command the next step's caps are relative to.
#[derive(Debug, Clone, Copy)]
struct Engagement {
    glove_at_engage: Isometry3<f64>,
    robot_at_engage: Isometry3<f64>,
    previous_target: Isometry3<f64>,
}

impl ArmMapper {
    /// A disengaged mapper; fails if the configuration does not validate.
    pub fn new(config: ArmConfig) -> Result<ArmMapper, ArmConfigError> {
        config.validate()?;
        Ok(ArmMapper {
            glove_to_base: config.glove_to_base_rotation()?,
            start_pose: config.start_pose_isometry()?,
            workspace: config.workspace(),
            constraint: config.resolved_constraint(config.constraint)?,
            vertical_axis: config.resolved_constraint(Constraint::VerticalAxis)?,
            horizontal_axis: config.resolved_constraint(Constraint::HorizontalAxis)?,
            config,
            engagement: None,
            last_command: None,
        })
    }

    /// The configuration, with the current constraint.
    pub fn config(&self) -> &ArmConfig {
        &self.config
    }

    /// The current task constraint.
    pub fn constraint(&self) -> Constraint {
        self.config.constraint
    }

    /// Change the task constraint (e.g. at the start of a task). Refused while engaged unless
    /// unchanged: a change while engaged would move the target without the operator moving.
    pub fn set_constraint(&mut self, constraint: Constraint) -> Result<(), ArmRefusal> {
        if constraint == self.config.constraint {
            return Ok(());
        }
        if self.is_engaged() {
            return Err(ArmRefusal::ConstraintChangeWhileEngaged);
        }
        self.constraint = match constraint {
            Constraint::Fixed => ResolvedConstraint::Fixed,
            Constraint::Free => ResolvedConstraint::Free,
            Constraint::VerticalAxis => self.vertical_axis,
            Constraint::HorizontalAxis => self.horizontal_axis,
        };
        self.config.constraint = constraint;
        Ok(())
    }

    /// Whether the clutch is engaged (steps produce commands).
    pub fn is_engaged(&self) -> bool {
        self.engagement.is_some()
    }

    /// The poses latched at engage: (glove wrist in the tracker frame, robot end effector in
    /// the base frame), both with renormalised quaternions.
    pub fn latched(&self) -> Option<(Isometry3<f64>, Isometry3<f64>)> {
        self.engagement
            .map(|e| (e.glove_at_engage, e.robot_at_engage))
    }

    /// Engage (or re-engage) the clutch: latch the glove wrist pose (tracker frame) and the
    /// robot end-effector pose (base frame, from the arm's pose feedback). Until the glove
    /// moves, the target is the robot pose, so engaging never moves the robot.
    ///
    /// Refused, with the state unchanged, for an invalid pose or a robot pose outside the
    /// workspace box.
    pub fn engage(
        &mut self,
        glove_wrist: Isometry3<f64>,
        robot_pose: Isometry3<f64>,
    ) -> Result<(), ArmRefusal> {
        let glove = checked_pose(&glove_wrist, PoseRole::GloveWrist)?;
        let robot = checked_pose(&robot_pose, PoseRole::RobotEndEffector)?;
        if let Some(v) = self.workspace.first_violation(&robot.translation.vector) {
            return Err(ArmRefusal::OutsideWorkspace {
                axis: v.axis,
                value: v.value,
                min_m: v.min_m,
                max_m: v.max_m,
            });
        }
        self.engagement = Some(Engagement {
            glove_at_engage: glove,
            robot_at_engage: robot,
            previous_target: robot,
        });
        Ok(())
    }

    /// Engage at the configured `start_pose`, for when there is no arm pose feedback.
    pub fn engage_at_start_pose(&mut self, glove_wrist: Isometry3<f64>) -> Result<(), ArmRefusal> {
        self.engage(glove_wrist, self.start_pose)
    }

    /// Release the clutch: steps return `None` until the next engage, so the operator can
    /// reposition the hand without moving the robot.
    pub fn disengage(&mut self) {
        self.engagement = None;
    }

    /// The last command [`step`](ArmMapper::step) returned (kept across disengage: the pose
    /// a caller holds).
    pub fn last_command(&self) -> Option<&ArmCommand> {
        self.last_command.as_ref()
    }

    /// Map one glove wrist pose (tracker frame) to an end-effector target.
    ///
    /// `Ok(None)` while disengaged. `Err` for an invalid glove pose (non-finite, implausible
    /// position, non-unit quaternion): the state is unchanged and the caller holds its last
    /// command. The pose is validated even while disengaged, so rejections are counted the
    /// same way in both states.
    pub fn step(&mut self, glove_wrist: Isometry3<f64>) -> Result<Option<ArmCommand>, ArmRefusal> {
        let glove = checked_pose(&glove_wrist, PoseRole::GloveWrist)?;
        let Some(engagement) = self.engagement.as_mut() else {
            return Ok(None);
        };
        let (delta_p, delta_r) = relative_motion(
            &self.glove_to_base,
            self.config.translation_scale,
            &engagement.glove_at_engage,
            &glove,
        );
        let motion = constrain(self.constraint, self.config.orientation, &delta_p, &delta_r);
        let latched = &engagement.robot_at_engage;
        let (position, clamped_to_workspace) = place_in_workspace(
            &self.workspace,
            &latched.translation.vector,
            &motion.translation,
        );
        let rotation = motion.rotation * latched.rotation;

        let previous = &engagement.previous_target;
        let translation = cap_translation(
            &previous.translation.vector,
            &position,
            self.config.max_translation_step_m,
        );
        let orientation = cap_rotation(
            &previous.rotation,
            &rotation,
            self.config.max_rotation_step_rad,
        );
        // Rounding guard: the capped point lies between two points of the box (a convex set),
        // so this moves it by at most an ulp; it is not reported as a workspace clamp.
        let position = self.workspace.clamp(&translation.value);
        let target = Isometry3::from_parts(
            Translation3::from(position),
            UnitQuaternion::new_normalize(orientation.value.into_inner()),
        );
        if !is_finite(&target) {
            return Err(ArmRefusal::NonFiniteTarget);
        }
        engagement.previous_target = target;
        let command = ArmCommand {
            target,
            constrained: motion.constrained,
            clamped_to_workspace,
            translation_capped: translation.capped,
            rotation_capped: orientation.capped,
        };
        self.last_command = Some(command);
        Ok(Some(command))
    }
}

/// The target position for an allowed translation from `latched`, kept in the box: along the
/// axis line for an axis constraint, per coordinate for free motion. Returns whether it moved.
fn place_in_workspace(
    workspace: &WorkspaceBox,
    latched: &Vector3<f64>,
    translation: &AllowedTranslation,
) -> (Vector3<f64>, bool) {
    match translation {
        AllowedTranslation::None => (*latched, false),
        AllowedTranslation::AlongAxis { axis, t } => {
            let (t_lo, t_hi) = workspace.line_interval(latched, axis);
            let t_clamped = t.clamp(t_lo, t_hi);
            (latched + axis.into_inner() * t_clamped, t_clamped != *t)
        }
        AllowedTranslation::Free(delta_p) => {
            let requested = latched + delta_p;
            let clamped = workspace.clamp(&requested);
            (clamped, clamped != requested)
        }
    }
}

fn is_finite(pose: &Isometry3<f64>) -> bool {
    pose.translation.vector.iter().all(|v| v.is_finite())
        && pose.rotation.coords.iter().all(|v| v.is_finite())
}

#[cfg(test)]
#[path = "mapper_tests.rs"]
mod tests;
