//! # Arm mapping: glove wrist pose → Franka end-effector target
//!
//! Pure and synchronous: no I/O, no clock. The control loop calls [`ArmMapper::step`] once per
//! tick with the latest glove wrist pose and publishes the returned [`ArmCommand`]'s target
//! (e.g. as `geometry_msgs/PoseStamped` on `/franka/end_effector_pose_cmd`, frame = the robot
//! base frame). The step caps are per call, so the loop rate sets the speed they allow.
//!
//! ## Frames
//!
//! - `G`, the **glove tracker frame**: the frame of the incoming wrist pose (the lab's
//!   `/ingress/wrist` is in frame `coil`). Right-handed, metres. A left-handed source (Rokoko
//!   Studio's Y-up, Z-forward) must be converted to right-handed by its adapter first: no
//!   rotation can do that.
//! - `B`, the **robot base frame**: the frame of the arm's pose feedback and command topics.
//!   The workspace box, the constraint axes and the start pose are all in `B`.
//! - `w`, the glove wrist; `e`, the end effector whose pose the arm controller takes.
//! - `R_BG` = `glove_to_base`: the fixed rotation taking tracker coordinates to base
//!   coordinates, `ᴮv = R_BG · ᴳv` (default identity). Relative motion needs no translation
//!   between the frames, and no wrist-to-flange calibration.
//!
//! ## Clutch
//!
//! [`ArmMapper::engage`] latches the glove pose `(ᴳp_w0, ᴳR_w0)` and the robot pose
//! `(p₀, R₀)` (from arm feedback, or the configured `start_pose` via
//! [`ArmMapper::engage_at_start_pose`]); `p₀` must be inside the workspace box.
//! [`ArmMapper::disengage`] stops the output (`step` returns `Ok(None)`; the caller holds).
//! Re-engaging latches both poses afresh, so the operator can move the hand anywhere while
//! disengaged and the robot does not move: right after engage the relative motion is zero and
//! the target is the robot's own pose.
//!
//! ## Relative motion (in `B`)
//!
//! For the current wrist pose `(ᴳp_w, ᴳR_w)` and `translation_scale` `s`:
//!
//! ```text
//! Δp = s · R_BG · (ᴳp_w − ᴳp_w0)
//! ΔR = R_BG · (ᴳR_w · ᴳR_w0ᵀ) · R_BGᵀ
//! ```
//!
//! `ᴳR_w · ᴳR_w0ᵀ` is the wrist's rotation since engage about axes fixed in the tracker frame;
//! conjugation re-expresses it about base-frame axes. It is applied on the left of `R₀`, about
//! the end effector's own origin (rotation does not swing the position):
//!
//! ```text
//! requested target:  p* = p₀ + Δp,   R* = ΔR · R₀
//! ```
//!
//! ## Task constraint and orientation policy
//!
//! The constraint keeps the allowed part `(Δp_c, ΔR_c)`, with `a` the configured unit axis
//! (`vertical_axis`, default `[0, 0, 1]`; `horizontal_axis`, default `[1, 0, 0]`):
//!
//! | `constraint` | POMDAR tasks | `Δp_c` | `ΔR_c` (default policy) |
//! |---|---|---|---|
//! | `fixed` | C4, H4, H5 | `0` | `I` |
//! | `vertical_axis` | V1–V3, C1–C3 | `(aᵀΔp)·a` | `I` |
//! | `horizontal_axis` | H1–H3 | `(aᵀΔp)·a` | `I` |
//! | `free` | G1–G6 | `Δp` | `ΔR` |
//!
//! The `orientation` policy ([`OrientationPolicy`]):
//! - `hold_when_constrained` (default): `free` follows the full relative rotation; `fixed` and
//!   the axis constraints hold `R₀`. On a rod the task is the slide, the hand's own wrist joint
//!   turns the object, and a held orientation cannot twist the fixture.
//! - `hold`: every constraint holds `R₀` (translation-only teleoperation).
//! - `twist_about_axis`: the axis constraints follow only the twist of `ΔR` about `a`
//!   (swing–twist: for `ΔR = (w, v)`, `normalise(w, (aᵀv)·a)`); `free` follows `ΔR`; `fixed`
//!   holds.
//!
//! ## Safety on the output
//!
//! 1. **Input**: a pose with a non-finite value, a coordinate beyond ±100 m, or a quaternion
//!    norm more than 1e-3 from 1 is rejected (`Err`, state unchanged, the caller holds).
//! 2. **Workspace box** `[lo, hi]` in `B`: free motion is clamped per coordinate; axis motion
//!    along the line, `t = aᵀΔp` clamped to `{t : lo ≤ p₀ + t·a ≤ hi}` (an interval containing
//!    0 since `p₀` is inside), so the target stays on its axis.
//! 3. **Step caps, scaled by norm**, relative to the previous command `(p_prev, R_prev)` (at
//!    engage, the latched robot pose): with `d = p_c − p_prev` and
//!    `ρ = log(R_c · R_prevᵀ)` (rotation vector, angle in [0, π]),
//!    `p = p_prev + d · min(1, δp/‖d‖)` and `R = exp(ρ · min(1, δR/‖ρ‖)) · R_prev`.
//!    The whole step is scaled, so the direction is kept. A glove jump becomes a straight
//!    ramp of at most `max_translation_step_m` / `max_rotation_step_rad` per tick. Targets are
//!    recomputed from the latch each tick, not integrated, so a capped command catches up
//!    and never drifts.
//! 4. Both ends of a capped step are in the box and (under an axis constraint) on the axis
//!    line, both convex, so the step's end is too; a final per-coordinate clamp absorbs
//!    rounding (≤ 1 ulp). The quaternion is renormalised; a non-finite result is an `Err`.
//!
//! [`ArmCommand`] carries the target and the flags `constrained`, `clamped_to_workspace`,
//! `translation_capped` and `rotation_capped`.
//!
//! ## Configuration
//!
//! [`ArmConfig`] (TOML, `deny_unknown_fields`, every key defaulted, [`ArmConfig::validate`]
//! names the key and its range). Default step caps 0.01 m and 0.02 rad per tick: at 100 Hz
//! that is 1.0 m/s and 2.0 rad/s, just under DROID's 7.5 cm and 0.15 rad per 15 Hz step
//! (1.125 m/s, 2.25 rad/s); at the default 25 Hz, 0.25 m/s and 0.5 rad/s.

mod arm_command;
mod arm_config;
mod arm_error;
mod arm_refusal;
mod constraint;
mod mapper;
mod pose_check;
mod relative_motion;
mod step_limits;
mod workspace_box;

pub use arm_command::ArmCommand;
pub use arm_config::{
    AXIS_NORM_TOLERANCE, ArmConfig, MAX_ROTATION_STEP_LIMIT_RAD, MAX_TRANSLATION_STEP_LIMIT_M,
    RotationConfig, StartPose, TRANSLATION_SCALE_RANGE, WORKSPACE_LIMIT_M,
};
pub use arm_error::ArmConfigError;
pub use arm_refusal::{ArmRefusal, PoseRole};
pub use constraint::{Constraint, OrientationPolicy, twist_about_axis};
pub use mapper::ArmMapper;
pub use pose_check::{
    MAX_ABS_POSITION_M, QUATERNION_NORM_TOLERANCE, checked_pose, pose_from_parts,
};
pub use step_limits::{Capped, cap_rotation, cap_translation};
pub use workspace_box::{BoxViolation, WorkspaceBox};
