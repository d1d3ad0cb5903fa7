//! # retarget: hand models and kinematics for the POMDAR station
//!
//! Pure and synchronous: no I/O, no clocks, no threads. Everything here is a function of its
//! arguments, so the station, the calibration and the tests all run the same code.
//!
//! ## Hand models
//!
//! A [`HandModel`] is a kinematic tree of revolute and fixed joints (origin xyz/rpy, axis,
//! limits, optional linear coupling `q_j = k·q_i + c`) with named frames: the palm, the wrist,
//! the five digit bases and the five fingertips. Build one from
//!
//! - the built-in ORCA v1 right hand, [`HandModel::orca_v1_right`] (the project's own
//!   description in `models/orca_v1_right.toml`),
//! - the project's TOML model format ([`model_spec`]), [`HandModel::from_toml_str`],
//! - any URDF, [`HandModel::from_urdf_str`] with a [`UrdfImport`] naming the frames.
//!
//! ### Conventions
//!
//! - Units: metres and radians everywhere, inside and at the API.
//! - The joint vector `q` holds one value per degree of freedom (an uncoupled revolute
//!   joint), in declaration order; for ORCA that is orca_core's order
//!   `thumb_mcp, thumb_abd, thumb_pip, thumb_dip, index_abd, index_mcp, index_pip,
//!   middle_abd, middle_mcp, middle_pip, ring_abd, ring_mcp, ring_pip, pinky_abd, pinky_mcp,
//!   pinky_pip, wrist`.
//! - **Zero convention: the URDF's.** `q = 0` is the pose the ORCA URDF draws with every joint
//!   at zero, so a `sensor_msgs/JointState` of these values is right for
//!   robot_state_publisher, RViz and Foxglove. orca_core's degree convention differs for
//!   some abduction joints; the conversion belongs to the station's `/hand/policy_output`
//!   stage, in one tested place. The FK cross-check test pins this convention against the
//!   reference URDF.
//! - Frames: every link frame is expressed in the model's base frame (the root link; ORCA's
//!   `world`, under the tower). The child link frame of a joint is the joint frame.
//!
//! ## Kinematics
//!
//! [`HandModel::forward`] poses every link into a reusable [`FkState`];
//! [`HandModel::position_jacobian`] writes `∂p/∂q` of a link origin,
//!
//! ```text
//! J[:, dof(j)] += k_j · a_j × (p − o_j)      for each revolute joint j above the link,
//! ```
//!
//! with `a_j` the joint axis and `o_j` the joint origin in the base frame, `k_j` the coupling
//! gain (1 for independent joints). Neither allocates.
//!
//! ```
//! use nalgebra::Matrix3xX;
//! use retarget::{Finger, HandModel};
//!
//! let model = HandModel::orca_v1_right();
//! let mut state = model.fk_state();
//! let mut q = model.zero_pose();
//! q[model.dof_index("index_mcp").unwrap()] = 0.8;
//! model.forward(&q, &mut state)?;
//! let tip = model.frames().tip(Finger::Index);
//! let mut jacobian = Matrix3xX::zeros(model.dof());
//! model.position_jacobian(&state, tip, &mut jacobian)?;
//! println!("index tip at {} m", state.position(tip));
//! # Ok::<(), retarget::Error>(())
//! ```
//!
//! ## Human keypoints and the palm frame
//!
//! [`KeypointLayout`] names the points of the lab's 22- and 21-point layouts and MediaPipe's
//! 21; [`PalmFrame`] is built the same way from human keypoints and from the robot's named
//! frames, so key vectors compare in one frame.
//!
//! ## Embodiments
//!
//! [`EmbodimentCatalog`] lists which joints each benchmarked embodiment (Orca_2, Orca_3,
//! Orca_5, Orca_full) may move; the others are locked at zero.
//!
//! ## Retargeting: energy minimisation as a sequence of QPs
//!
//! [`Retargeter::retarget`] turns one frame of human keypoints into a joint command.
//!
//! **Frames.** Human points are expressed in the human palm frame `H` built from the wrist and
//! the five digit bases ([`PalmFrame`]); robot points in the robot palm frame `R` built the same
//! way from the model's named frames. Both are metres. The calibration transform
//! `C = s · Rot(roll, pitch, yaw)` ([`CalibrationTransform`], identity by default) maps human
//! vectors into robot proportions: `h ↦ C h`.
//!
//! **Points.** For each digit `i`: the fingertip `p_i` and the mid point `m_i` (finger PIP,
//! thumb MCP; robot: the model's `*_mid` frames). Human: `p̂_i = C ·ᴴp_i`, `m̂_i = C ·ᴴm_i`.
//! Robot: `p_i(q)`, `m_i(q)` in `R`.
//!
//! **Energy** over the free joints `q` (the embodiment's; locked joints are not variables and
//! stay at their neutral value exactly), with `q₋` the previous command:
//!
//! ```text
//! E(q) = Σ_i       w_pt · ρ(‖p_i(q) − p̂_i‖)                    5 palm → tip vectors
//!      + Σ_{i<j}   w_ij · ρ(‖(p_j − p_i)(q) − t_ij‖)            10 tip → tip vectors
//!      + Σ_i       w_pm · ρ(‖m_i(q) − m̂_i‖)                     5 palm → mid vectors
//!      + ½ λ ‖q − q₋‖²  +  ½ μ Σ_{j ∈ abduction} (q_j − q_rest,j)²
//! ```
//!
//! - `ρ` is the Huber function with threshold `δ` (`huber_delta_m`, 2 cm): quadratic for small
//!   residuals, linear beyond, so one bad keypoint pulls with bounded force.
//! - Tip → tip targets start from the human vector `h = p̂_j − p̂_i`. For thumb → finger `k`,
//!   the activation `β_k = smoothstep((release − d_k)/(release − engage))` of the raw human
//!   thumb–finger distance `d_k` (1 below `engage_m`, 0 above `release_m`, C¹ in between: no
//!   snapping) slides the distance aimed for from the human's to `closed_gap_m`: target
//!   `ĥ ((1 − β_k)‖h‖ + β_k · gap)`, weight `w_tt + max(β_k w_pinch, a_k)`. On the way in, the
//!   finger the thumb is nearest gains `a_k`, rising smoothly from 0 at `pinch.approach_m` to
//!   `w_pt − w_tt` at `release_m`, so the robot's gap follows the human's before the pinch
//!   begins ([`energy::approach_weights`]). For finger pairs,
//!   `β = max(β_a, β_b)` adds `β w_sep ‖r − ĥ · max(‖h‖, separation_m)‖²`, keeping a pinching
//!   finger's neighbours away: one quadratic of weight `w_ij = w_tt + β w_sep`, target
//!   `(1 − σ) h + σ · goal`, `σ = β w_sep / w_ij` ([`energy::key_vector_targets`]).
//! - The palm-frame tips and mid points also pass a speed-adaptive low-pass ([`one_euro`],
//!   `[input_filter]`, counted in frames): hard at rest, where glove noise is all there is,
//!   nearly transparent for a finger moving fast. The second solve below takes the filtered
//!   points in the share `x / (1 + x)` of its residual (none for a pinching thumb and finger);
//!   the pinch distances are never filtered.
//! - `λ` (`regularisation.previous_command`) smooths without the lag of an output filter;
//!   `μ` (`regularisation.rest_posture`) keeps abduction joints near a rest posture when the
//!   key vectors leave them free.
//! - Residual-adaptive smoothing ([`SmoothingConfig`]): each frame is solved once with `λ`;
//!   with `ē` the mean palm → fingertip residual of that solve and `x = (ē / r₀)²`
//!   (`smoothing.residual_m`), it is solved again from the same `q₋` with
//!   `λ' = λ + λ_s x / (1 + x)` (`smoothing.previous_command`). A frame the robot reproduces
//!   (`ē ≈ 0`) is tracked without lag; one it cannot (glove noise, a hand outside the robot's
//!   range, where the optimum is ill determined and noise moves it most) is pulled toward the
//!   previous command. The extra pull is released for fast motion: multiplied by
//!   `1 / (1 + (v / v₀)²)`, `v` the fastest key point's speed as the input filter estimates it
//!   and `v₀` `smoothing.release_speed_m_s`. That speed is low-passed and rises over frames,
//!   so a quick pinch's first frames would still be held back: the digits of a pinch closing
//!   within `smoothing.approach_range_m` keep only `1 / (1 + (v_p / v_a)²)` of the extra pull,
//!   `v_p` the raw thumb–finger distance's fall per frame and `v_a`
//!   `smoothing.approach_speed_m_s` (the thumb by its fastest pinch; `pinch_approach`). The command
//!   depends on `q₋`, the frame, `dt` and the input filter's state ([`Retargeter::reset`]
//!   clears both).
//!
//! Units: residuals in metres, weights dimensionless per m², `λ`, `μ` per rad².
//!
//! **Steps.** Each Gauss–Newton step linearises `r(q + Δ) ≈ r(q) + J Δ` (palm-frame positional
//! Jacobians of the points, couplings folded in), reweights every residual by
//! `min(1, δ/‖e‖)` (iteratively reweighted least squares for ρ) and solves the box QP
//!
//! ```text
//! min_Δ ½ Δᵀ (Σ w̃ JᵀJ + (λ + ε) I + μ D_abd) Δ + (Σ w̃ Jᵀe + λ (q − q₋) + μ D_abd (q − q_rest))ᵀ Δ
//! s.t.  max(q_min, q₋ − v τ) − q  ≤  Δ  ≤  min(q_max, q₋ + v τ) − q,     τ = min(dt, max_rate_dt_s)
//! ```
//!
//! with Clarabel ([`qp_step::BoxQp`]): one solver per retargeter, its data updated in place,
//! the problem Jacobi-scaled to unit diagonal and unit gradient so tolerances are relative.
//! A step is accepted when it lowers `E` (halved up to four times otherwise); every iterate is
//! clamped into the box, so commands never leave the joint limits or the rate bound.
//!
//! **Outcome as data.** [`Solution`] carries the status ([`SolveStatus`]: converged, step
//! budget spent, or QP failure with the best iterate before it), the Gauss–Newton steps and
//! interior-point iterations, the energy before and after, the solver time and the mean
//! palm → tip error. Malformed input (wrong point count, non-finite values, a collapsed palm,
//! a bad time step) is an `Err` and leaves the command untouched: the caller holds it.
//!
//! ## Files
//!
//! | file | holds |
//! |---|---|
//! | `model_spec.rs`, `model_build.rs`, `model_file.rs`, `urdf_import.rs`, `urdf_reader.rs` | the model format, its validation, the built-in ORCA, URDF import (the project's own reader: links, joints, origins, axes, limits, mimic) |
//! | `hand_model.rs`, `forward_kinematics.rs`, `jacobian.rs`, `finger.rs` | the validated tree, FK into a reusable state, analytic Jacobians; the five digits |
//! | `keypoint_layout.rs`, `palm_frame.rs`, `synthetic_keypoints.rs` | human layouts, the shared palm frame, robot-as-human keypoints |
//! | `human_key_vectors.rs`, `energy.rs`, `one_euro.rs`, `pinch_approach.rs` | input validation and key vectors; the energy's targets (the pinch blend, a pinching finger giving way to the thumb, the way into a pinch) and Huber terms; the speed-adaptive (1€) input filter, counted in frames; how fast the thumb closes on each finger |
//! | `qp_step.rs`, `box_active_set.rs`, `retargeter.rs` | the box QP (the exact active-set method, certified by KKT, with Clarabel as fallback or for every step); the per-frame Gauss–Newton loop and its outcome |
//! | `retarget_config.rs`, `calibration_transform.rs`, `embodiment.rs`, `error.rs` | configuration, the per-user transform, embodiments, errors |
//! | `human_hand/` | the simulated human hand: shape and proportions (non-uniform hands and glove tip markers), poses, FK, pinch poses, motions, task scripts, the simulated glove, the seeded noise |
//! | `quality/` | retargeting quality over a recording (tip error after a global scale, pinches closed under two definitions, also per finger pair, jerk, max step, limit violations; overall and per digit), for `pomdar eval` |

mod box_active_set;
mod calibration_transform;
mod embodiment;
pub mod energy;
mod error;
mod finger;
mod forward_kinematics;
mod hand_model;
pub mod human_hand;
mod human_key_vectors;
mod jacobian;
pub mod keypoint_layout;
mod model_build;
mod model_file;
pub mod model_spec;
pub mod one_euro;
mod palm_frame;
mod pinch_approach;
pub mod qp_step;
pub mod quality;
mod retarget_config;
mod retargeter;
mod synthetic_keypoints;
mod urdf_import;
mod urdf_reader;

pub use calibration_transform::CalibrationTransform;
pub use embodiment::{EMBODIMENTS_TOML, Embodiment, EmbodimentCatalog};
pub use error::Error;
pub use finger::Finger;
pub use forward_kinematics::FkState;
pub use hand_model::{Dof, HandModel, Joint, JointMotion, Limits, LinkId, NamedFrames};
pub use human_key_vectors::{HumanKeyVectors, human_key_vectors, validate_keypoints};
pub use keypoint_layout::KeypointLayout;
pub use model_file::{ORCA_CORE_JOINTS, ORCA_V1_RIGHT_TOML};
pub use model_spec::{FrameSpec, ModelSpec};
pub use palm_frame::{MIN_PALM_AXIS_M, PalmFrame, PalmLandmarks};
pub use quality::{DigitQuality, QualityRecorder, QualityReport};
pub use retarget_config::{
    KeyVectorWeights, PinchConfig, QpMethod, Regularisation, RetargetConfig, SmoothingConfig,
    SolverConfig,
};
pub use retargeter::{Retargeter, Solution, SolveStatus};
pub use urdf_import::{UrdfImport, spec_from_urdf};
