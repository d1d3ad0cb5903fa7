//! # study: do participants adopt one strategy per task?
//!
//! In the POMDAR human study participants wear a motion-capture glove (keypoints, e.g. the
//! lab's 22 points at 100 Hz) and do each task three times. The paper checks that they adopt
//! the same strategy per task: a PCA of the recorded hand motion in 1.5 s segments, coloured
//! by task, clusters by task. This crate is that analysis, pure and synchronous: `teleop`
//! reads the recordings and hands over [`TrialMotion`]s; [`analyse`] returns numbers,
//! [`strategy_figure`] and [`report_markdown`] turn them into a figure and a report section.
//!
//! ## Method
//!
//! **1. Hand frame, per frame.** The palm frame `(c, R)` is built from the layout's wrist
//! and five digit bases (`retarget::PalmFrame`, the same frame the retargeter uses), and
//! every keypoint `p` becomes `R⁻¹ (p − c) / L`, where `L` is the trial's hand length: the
//! median over its frames of the mean wrist → finger-base distance (index, middle, ring,
//! little). Why: a participant's strategy is the hand's shape and its change, not where the
//! hand is or how it is turned. Expressing points in the palm frame removes the global
//! translation and rotation (and whatever frame the glove reports in); dividing by `L`
//! removes hand size, so a large and a small hand making the same grasp give the same
//! numbers and participants do not separate by size. `L` is a per-trial median of rigid palm
//! distances, so finger motion does not change it and a few bad frames do not move it; the
//! thumb base is left out because it moves with the thumb. Frames whose palm frame collapses
//! (landmarks closer than 2 mm) are skipped and counted.
//!
//! **2. Segments.** Consecutive, non-overlapping windows of `segment_s` (1.5 s) from the
//! trial's first frame. The trial covers its first frame time to its last plus one median
//! frame interval (so 6 s at 100 Hz is four windows); a trailing partial window is dropped,
//! and so is a window with fewer than `min_frames_per_segment` usable frames. Each segment
//! becomes one feature vector of `6 n` numbers for `n` keypoints:
//!
//! ```text
//! f = [ mean_t x_i,k  for every point i, axis k ;  std_t x_i,k  for every point i, axis k ]
//! ```
//!
//! The mean is the segment's posture (a power grasp and a pinch hold the fingers
//! differently); the (population) standard deviation is its movement (spreading the fingers
//! or opening and closing the hand moves different points by different amounts). Neither
//! depends on the order of the frames within the window, so they are far less sensitive than
//! raw trajectories to where in its cycle a segment starts and to the motion's speed, which
//! differ between participants and trials without being a different strategy. Not
//! insensitive: a window shorter than a slow motion's cycle sees only part of it, so such a
//! task's segments spread over the phases they caught (in the simulated study, the 4 s
//! open–close cycle cut into 1.5 s windows separates least, silhouette about 0.2–0.35, the
//! other two tasks 0.65–0.8).
//!
//! **3. PCA.** Every feature is standardised over all segments (z-score; a feature whose
//! standard deviation is below 1e-9 hand lengths is constant and set to 0), so a coordinate
//! that moves a lot (a fingertip) does not drown one that moves little but consistently
//! (a knuckle), and means and standard deviations weigh alike. The principal components come
//! from the SVD of the standardised matrix `Z = U Σ Vᵀ`: component *j* has loadings `v_j`,
//! scores `Z v_j` and explains `σ_j² / ‖Z‖²_F` of the total variance. The first
//! `min(components, segments − 1, varying features)` components are kept (`components` = 3
//! by default; the number kept is [`StrategyAnalysis::components_kept`]). Each component is signed so its
//! largest-magnitude loading is positive: the same data always gives the same figure.
//!
//! **4. Separation by task.** The silhouette (Rousseeuw 1987) of every segment, Euclidean in
//! the kept components' score space, clusters = tasks: `a` = mean distance to the segments
//! of its own task, `b` = the smallest mean distance to another task's segments,
//! `s = (b − a) / max(a, b)` (0 for a task with one segment). Computed in the PC space because
//! that is the space the figures show and the claim is about; the mean over all segments is
//! read with Kaufman & Rousseeuw's bands ([`ClusterStrength`]): above 0.70 strong, above 0.50
//! reasonable, above 0.25 weak, otherwise no substantial structure. The analysis needs at
//! least two tasks and two segments.
//!
//! **Checks.** A trial with no frames, a frame with the wrong number of points for its
//! layout, a non-finite time or point, or times that do not strictly increase is skipped
//! with the reason ([`SkippedTrial`]), as is a trial too short for one segment or whose
//! palm frame always collapses. If nothing remains the analysis fails ([`StudyError`]);
//! trials with different layouts cannot share a feature space and are an error too.
//!
//! ## Files
//!
//! | file | what |
//! |---|---|
//! | `motion.rs` | [`TrialMotion`], [`MotionFrame`] and their checks |
//! | `palm_coordinates.rs` | keypoints in the palm frame, in hand lengths |
//! | `segments.rs` | windows and their features ([`trial_segments`], [`feature_names`]) |
//! | `pca.rs`, `silhouette.rs` | the PCA and the silhouette |
//! | `analysis.rs` | [`analyse`] and [`StrategyAnalysis`] |
//! | `cluster_strength.rs` | [`ClusterStrength`]: Kaufman & Rousseeuw's bands |
//! | `report.rs`, `figure.rs` | [`report_markdown`], [`StrategyAnalysis::sentence`], [`strategy_figure`] |

mod analysis;
mod cluster_strength;
mod error;
mod figure;
mod motion;
mod palm_coordinates;
mod pca;
mod report;
mod segments;
mod settings;
mod silhouette;
mod skip;

pub use analysis::{SegmentScore, StrategyAnalysis, TaskSeparation, analyse};
pub use cluster_strength::ClusterStrength;
pub use error::StudyError;
pub use figure::{strategy_chart, strategy_figure};
pub use motion::{MotionFrame, TrialMotion};
pub use pca::CONSTANT_TOLERANCE;
pub use report::report_markdown;
pub use segments::{Segment, TrialSegments, feature_names, trial_segments};
pub use settings::{MAX_SEGMENT_S, StrategySettings};
pub use silhouette::silhouette_values;
pub use skip::{SkipReason, SkippedTrial};
