//! A trial's review, for the operator who ran it: what happened, when, and what to do about it.
//!
//! The application reads a trial's log into a [`TrialInput`] (the trial events, the station's
//! status messages, the glove frames, the hand commands, the hand's measured state, the arm
//! targets); [`review()`] turns it into
//!
//! - [`TrialReview`], the facts on one time axis (seconds from the trial's `start` event):
//!   progress marks and drops; the station's drive state (engaged, held, disengaged); the
//!   holds on a stalled glove, each with the glove's gap around it (a held command is stamped
//!   with its own send time, a fresh one with its glove frame's); the glove's frames, longest
//!   gap and rejected frames; the arm's constraint, clutch, refused steps and time at its
//!   workspace box; the human's sustained pinches and whether the robot closed each
//!   ([`pinches`]); the per-digit tracking error of the measured hand ([`tracking`]);
//! - [`Feedback`]: short sentences from those facts, each said only past its threshold
//!   ([`FeedbackSettings`], [`feedback`]), so a clean trial gets none;
//! - [`ReviewSeries`], the dense series, and [`review_chart`], the figure's data for
//!   `scoring::plot::review_figure`.
//!
//! Pure: no files, no clock.

mod chart;
mod error;
mod facts;
pub mod feedback;
mod feedback_rules;
mod input;
mod joints;
pub mod pinches;
mod review;
mod signals;
mod spans;
pub mod tracking;
mod window;

pub use chart::review_chart;
pub use error::ReviewError;
pub use facts::{ArmFacts, CountAt, GloveFacts, TrialReview};
pub use feedback::{Feedback, FeedbackKind, FeedbackSettings};
pub use input::{GloveFrame, JointSample, TrialInput};
pub use review::{ReviewContext, ReviewSeries, review};
pub use signals::{AT_LIMIT_M, ProgressMark, WorkspaceLimits};
pub use spans::{Hold, StateSpan};
pub use window::TrialWindow;

#[cfg(test)]
mod tests;
