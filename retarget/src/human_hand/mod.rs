//! # A parametric human hand: the simulated glove's and the synthetic users' hand
//!
//! A kinematic model of a human hand, pure like the rest of the crate: bone lengths that scale
//! with hand size, joint angles per digit, forward kinematics into any
//! [`KeypointLayout`](crate::KeypointLayout), pinch poses found by a small numeric solve,
//! scripted motions as functions of time, task scripts (a wrist path and hand poses as
//! keyframes), and a simulated glove with deterministic jitter.
//! The station's simulated glove publishes its frames; calibration
//! generates its synthetic users with it (sizes 0.8–1.25×, a rotated glove frame, 2 mm noise),
//! and the evaluation's synthetic users vary its proportions too ([`HandVariation`]).
//!
//! ## Frames and units
//!
//! The **hand frame** `H`: the wrist joint centre at the origin, `+y` towards the middle
//! finger's base, `+z` out of the palm (palmar side), `+x` towards the thumb of a right hand
//! (for a left hand, the mirror image `x ↦ −x`: the thumb on `−x`, the palm still on `+z`).
//! For a right hand these are the axes of [`PalmFrame`](crate::PalmFrame) built from the
//! generated keypoints (its origin is `½(thumb base + little base)`, not the wrist). Metres,
//! radians, seconds.
//!
//! ## Pieces, one file each
//!
//! | file | what |
//! |---|---|
//! | `shape.rs` | [`HumanHandShape`]: bones and joint placements, the average hand, scale, [`Handedness`] |
//! | `pose.rs` | [`HumanHandPose`]: joint angles, ranges, named poses, interpolation |
//! | `hand_kinematics.rs` | forward kinematics ([`HumanHandShape::keypoints`]) and placement ([`place_points`]) |
//! | `pinch.rs` | [`pinch_pose`]: thumb-to-fingertip gap by damped Gauss–Newton |
//! | `motion.rs` | [`Motion`]: open/close, pinches, abduction, a task-like sequence; C¹ and periodic |
//! | `glove_script.rs` | [`GloveScript`]: a task played once, wrist path and hand poses as keyframes |
//! | `noise.rs` | [`SplitMix64`]: deterministic uniform and Gaussian numbers |
//! | `sim_glove.rs` | [`SimGlove`]: shape + motion + placement + jitter → frames |
//! | `variation.rs` | [`HandVariation`]: non-uniform hands (digit lengths, palm breadth, thumb base, tip markers) |
//!
//! ## Example
//!
//! ```
//! use retarget::KeypointLayout;
//! use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove, WristSway};
//!
//! let shape = HumanHandShape::average().scaled(1.1);
//! let motion = Motion::new(MotionKind::Pinches, 2.5, &shape)?;
//! let glove = SimGlove::new(shape, motion, KeypointLayout::Lab22)?
//!     .with_wrist_sway(WristSway::GENTLE)?
//!     .with_jitter(0.002, 7)?;
//! let (keypoints, wrist_pose) = glove.frame(0.04);
//! assert_eq!(keypoints.len(), 22);
//! # let _ = wrist_pose;
//! # Ok::<(), retarget::Error>(())
//! ```

mod glove_script;
mod hand_kinematics;
mod motion;
mod noise;
mod pinch;
mod pose;
mod shape;
mod sim_glove;
mod variation;

pub use glove_script::{
    GloveScript, MAX_WRIST_OFFSET_M, ResolvedScript, ScriptDropout, ScriptKeyframe, ScriptPose,
    ScriptSample,
};
pub use hand_kinematics::{DigitChains, place_points};
pub use motion::{
    CALIBRATION_MOVE_SHARE, KeyPose, MIN_PERIOD_S, Motion, MotionKind, MotionPhase, PINCH_GAP_M,
};
pub use noise::SplitMix64;
pub use pinch::{DIP_PER_PIP, MAX_PINCH_GAP_M, PinchPose, pinch_pose};
pub use pose::{
    ANGLE_NAMES, FingerAngles, HumanHandPose, JOINT_RANGES_RAD, POSE_ANGLES, ThumbAngles,
};
pub use shape::{DigitGeometry, Handedness, HumanHandShape, MAX_TIP_MARKER_M, REALISTIC_SCALE};
pub use sim_glove::{MAX_JITTER_SD_M, SimGlove, WristSway, misalign};
pub use variation::{HandVariation, VariationRanges};
