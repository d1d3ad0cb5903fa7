//! # scoring: POMDAR scores from trial logs
//!
//! Pure and synchronous: no I/O, no clocks (checked by `tests/tests/suite/dependency_rule.rs`).
//! `teleop` reads the MCAP files and the configuration files and hands this crate text and
//! [`TrialLog`]s; this crate checks, scores, aggregates and renders.
//!
//! ## The score (POMDAR paper, arXiv 2604.09294)
//!
//! Per trial *i* of task *t*:
//!
//! ```text
//! time_i        = t(stop) − t(start)                       seconds, from the trial events
//! correctness_i ∈ [0, 1]                                   from the progress events:
//!     notches, curves:  min(Σ progress, N) / N             N = the task's count
//!     rotation:         clamp(Σ degrees / 360°, 0, 1)
//!     distance (H4, H5): clamp(Σ mm / 200 mm, 0, 1)        (rule unverified: catalog data)
//!     grasp:            last level ∈ {0, 0.5, 1}; a drop means 0.5
//! speed_i       = baseline_t / time_i                      unbounded above (> 1: superhuman)
//! score_i       = 0.8 · correctness_i + 0.2 · speed_i      (weights configurable)
//! ```
//!
//! `baseline_t` is the mean completion time of human trials of task *t*
//! ([`compute_baseline`]). Without a baseline for *t* there is no score, only correctness,
//! and every report says so: this crate never makes up a time.
//!
//! Aborted and timed-out trials follow [`UnfinishedRule`] (default `partial`: correctness
//! reached, speed term 0; the paper does not say, so this is configuration). Practice
//! trials are scored but never enter a mean.
//!
//! ## Aggregation
//!
//! ```text
//! s_{t,e}          = mean ± sample std of score_i over recorded trials of task t, embodiment e
//! overall_e        = Σ_{t ∈ A_e} s_{t,e} / |A_e|        A_e = tasks e attempted
//! overall_e (all)  = Σ_{t ∈ A_e} s_{t,e} / 18           tasks not attempted count 0
//! ```
//!
//! ## Comparing groups of trials (the source ablation)
//!
//! [`compare_by`] groups the counted trials by a metadata entry *f* (`keypoint_source`:
//! Rokoko gloves against Apple Vision Pro, or `user`, `station_version`, …; trials without
//! it form [`MISSING_GROUP`]) and puts the groups side by side per task × embodiment:
//!
//! ```text
//! per t, e, group g:  n, correctness, time, score (with a baseline): mean ± sample std
//! d_g  = mean_g − mean_r                                  r = the reference group
//! SE²  = s_g²/n_g + s_r²/n_r,   ν = SE⁴ / Σ (s²/n)²/(n − 1)      (Welch–Satterthwaite)
//! CI   = d_g ± t_ν(0.975) · SE                            none if n < 2 or SE = 0
//! ```
//!
//! `t_ν` is the Student-t quantile for real ν, from the regularized incomplete beta function
//! (`student_t.rs`).
//!
//! ## Files
//!
//! | file | what |
//! |---|---|
//! | `catalog.rs` | [`TaskCatalog`]: the 18 tasks as data (`data/tasks_pomdar.toml`), validated |
//! | `catalog/physics_mapping.rs` | [`PhysicsMapping`]: where a task's progress is read in a simulated scene |
//! | `rules.rs` | [`ScoringRules`]: weights, time limits, unfinished trials |
//! | `baseline.rs` | [`BaselineTable`] and [`compute_baseline`] from human trials |
//! | `baseline_report.rs` | [`baseline_study`]: the study per participant × task, rendered |
//! | `trial_log.rs` | [`TrialLog`] and its checks ([`TrialRecord`]) |
//! | `correctness.rs` | [`correctness()`] per kind |
//! | `trial_score.rs` | [`score_trial`]: outcome, time, speed, score |
//! | `stats.rs` | [`MeanStd`] |
//! | `aggregate.rs` | [`aggregate()`]: per task × embodiment and per embodiment |
//! | `report.rs` | [`ScoreReport`]: all of the above with its warnings |
//! | `report_terminal.rs`, `report_markdown.rs`, `report_csv.rs` | the renderers (JSON is serde) |
//! | `figures.rs` | [`render_figures`]: the report's radars and overall-vs-DoF charts |
//! | `compare.rs` | [`compare_by`]: trials grouped by a metadata entry (`keypoint_source`, …), per task × embodiment, differences from a reference group |
//! | `student_t.rs`, `welch.rs` | the t distribution (CDF, quantile via the incomplete beta) and Welch's interval for a difference of means |
//! | `compare_render.rs`, `compare_csv.rs`, `compare_figures.rs` | the comparison as terminal text, Markdown, CSV and grouped-bar figures |
//! | `tracking.rs` | [`tracking_report`]: commanded against measured joint angles of a trial (RMS, max, lag, share over a threshold) |
//! | `plot/` | the figures' drawing (radar, overall vs DoF, grouped bars) as SVG and PNG |

pub mod plot;

mod aggregate;
mod baseline;
mod baseline_report;
mod catalog;
mod compare;
mod compare_csv;
mod compare_figures;
mod compare_render;
mod correctness;
mod error;
mod figures;
mod report;
mod report_csv;
mod report_markdown;
mod report_terminal;
mod rules;
mod stats;
mod student_t;
mod tracking;
mod trial_log;
mod trial_score;
mod welch;

pub use aggregate::{Aggregate, EmbodimentResult, TaskResult, aggregate, overall_means};
pub use baseline::{
    BaselineComputation, BaselineHeader, BaselineTable, LeftOut, TaskBaseline, UsedTrial,
    compute_baseline,
};
pub use baseline_report::{
    BaselineStudy, POMDAR_STUDY_TRIALS_PER_TASK, ParticipantTimes, StudySummary, StudyTask,
    StudyTrial, UNNAMED_PARTICIPANT, baseline_study, render_study_markdown, render_study_text,
};
pub use catalog::{
    ArmConstraint, BUILTIN_CATALOG_ORIGIN, CatalogHeader, Configuration, CorrectnessKind,
    DEFAULT_LIFT_M, DEFAULT_MARK_BAND, DEFAULT_REST_SPEED_M_S, DEFAULT_REST_TIME_S, Direction,
    GraspMapping, InvalidMapping, POMDAR_TASKS_TOML, PhysicsMapping, TaskCatalog, TaskSpec,
};
pub use compare::{
    CompareGroup, CompareRow, Comparison, GroupResult, MISSING_GROUP, VersusReference, compare_by,
    group_of,
};
pub use compare_csv::render_compare_csv;
pub use compare_figures::render_compare_figures;
pub use compare_render::{render_compare_markdown, render_compare_terminal};
pub use correctness::{Correctness, GRASP_LEVELS, correctness};
pub use error::ScoringError;
pub use figures::{NamedFigure, render_figures};
pub use report::{BaselineInfo, FileProblem, ReportInputs, RulesInfo, ScoreReport, TaskInfo};
pub use report_csv::{render_overall_csv, render_scores_csv, render_trials_csv};
pub use report_markdown::render_markdown;
pub use report_terminal::{TERMINAL_WIDTH, render_terminal};
pub use rules::{DEFAULT_RULES_ORIGIN, ScoringRules, UnfinishedRule};
pub use stats::MeanStd;
pub use student_t::{ln_gamma, regularized_incomplete_beta, student_t_cdf, student_t_quantile};
pub use tracking::{
    JointTrack, JointTracking, MIN_LAG_SAMPLES, TrackingReport, TrackingSettings, track_joint,
    tracking_chart, tracking_report,
};
pub use trial_log::{Ending, HUMAN_EMBODIMENT, Mark, TRIAL_METADATA_NAME, TrialLog, TrialRecord};
pub use trial_score::{Outcome, TrialScore, score_record, score_trial};
pub use welch::{CONFIDENCE_LEVEL, Difference, DifferenceInterval, welch_difference};
