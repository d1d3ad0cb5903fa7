//! Task progress read from the physics state, turned into the events an operator's keys make.
//!
//! The simulator reads the task's progress source every few milliseconds, a joint's position
//! ([`Reading::Joint`]) or the object's body position and speed ([`Reading::Body`]), and feeds
//! it to a [`ProgressTracker`], built from the task's [`CorrectnessKind`] and its
//! [`PhysicsMapping`]. The tracker returns [`ProgressEvent`]s in the catalog's unit, so that
//! `scoring::correctness` gives the paper's correctness from a simulated trial exactly as from
//! a trial marked by hand:
//!
//! | kind | reading | events | correctness |
//! |---|---|---|---|
//! | notches, curves | slide (m) or hinge (rad) | +1 when a mark is passed, −1 when passed back | passed / count |
//! | rotation | hinge (rad) | whole degrees turned forward, best angle only | degrees / 360 |
//! | distance | slide (m) | whole millimetres slid forward, best position only | mm / 200 |
//! | grasp | free body (m, m/s) | level 0.5 lifted, 1 at rest in the target, 0.5 when it leaves; `Drop` when set down elsewhere | last level |
//!
//! Modelling choices (this project's, not the paper's):
//!
//! - Marks have a hysteresis band (`mark_band`): a mark counts once the joint is the band past
//!   it and is taken back once the joint is the band back before it, so that an object resting
//!   on a mark emits one event, not a stream of ±1. Marks already passed in the first reading
//!   are the start, not progress: going back past them emits nothing.
//! - Rotation and distance are ratchets on the best position reached. The paper's C tasks sit
//!   behind a gravity clutch, so turning back does not undo progress; the H4/H5 rule is not
//!   published (distance / 200 mm is the catalog's guess) and is treated the same way. Events
//!   come in whole degrees or millimetres, so the total is never more than the truth and at
//!   most one unit below it. Hinge readings are unwrapped (consecutive readings must be less
//!   than half a turn apart, true for any reading rate above a few hertz).
//! - Grasp: lifted means the body origin rose `lift_m` above its height in the first reading;
//!   relocated means it then rested (slower than `rest_speed_m_s` for `rest_time_s`) with its
//!   origin inside the target box. The paper gives the levels, not these thresholds.
//! - A reading of the wrong shape or with a non-finite value is skipped and counted
//!   ([`ProgressTracker::skipped_readings`]); the caller reports it.

mod grasp_watch;
mod mark_counter;
mod ratchet;

#[cfg(test)]
mod tests;

use scoring::{CorrectnessKind, Mark};

pub use scoring::{Direction, GraspMapping, InvalidMapping, PhysicsMapping};

use grasp_watch::GraspWatch;
use mark_counter::MarkCounter;
use ratchet::Ratchet;

/// One reading of a task's progress source.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reading {
    /// A slide's position (m) or a hinge's angle (rad).
    Joint(f64),
    /// A free object's body origin in the world frame (m) and its linear speed (m/s): in
    /// MuJoCo the body's `xpos` and the norm of its free joint's `qvel[0..3]`.
    Body {
        /// The body origin's position in the world frame, m.
        position_m: [f64; 3],
        /// The body origin's linear speed, m/s.
        speed_m_s: f64,
    },
}

impl Reading {
    fn is_finite(&self) -> bool {
        match self {
            Reading::Joint(q) => q.is_finite(),
            Reading::Body {
                position_m,
                speed_m_s,
            } => position_m.iter().all(|v| v.is_finite()) && speed_m_s.is_finite(),
        }
    }
}

/// What a tracker reports, as an operator's key would.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ProgressEvent {
    /// A progress value in the catalog's unit: ±1 notch or curve, degrees, millimetres, or a
    /// grasp level (0.5, 1).
    Progress(f64),
    /// A lifted object came to rest outside the target (grasp only; its level stays 0.5).
    Drop,
}

impl ProgressEvent {
    /// The trial log's mark for this event.
    pub fn mark(self) -> Mark {
        match self {
            ProgressEvent::Progress(v) => Mark::Progress(v),
            ProgressEvent::Drop => Mark::Drop,
        }
    }
}

/// A tracker cannot be built for this task.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProgressError {
    /// The mapping does not fit the task's kind.
    #[error("progress mapping of joint {joint:?}: {source}")]
    Mapping {
        /// The mapping's joint.
        joint: String,
        /// What is wrong.
        source: InvalidMapping,
    },
    /// The first reading is not the kind the task reads, or is not finite.
    #[error("initial reading {found} for a {kind} task: {allowed}")]
    InitialReading {
        /// The task's kind (`6 notches`).
        kind: String,
        /// The reading given.
        found: String,
        /// What is allowed.
        allowed: &'static str,
    },
}

/// Turns a task's progress readings into progress events (see the module docs).
#[derive(Debug, Clone)]
pub struct ProgressTracker {
    watch: Watch,
    total: f64,
    skipped: u64,
}

#[derive(Debug, Clone)]
enum Watch {
    Marks(MarkCounter),
    Ratchet(Ratchet),
    Grasp(GraspWatch),
}

impl ProgressTracker {
    /// A tracker for a task of `kind` read through `mapping`, starting from `initial` (the
    /// reading at the start of the trial). `Err` when the mapping does not fit the kind, or
    /// `initial` is not finite or not the reading the kind needs (a joint position for
    /// notches, curves, rotation and distance; a body reading for grasp).
    pub fn new(
        kind: &CorrectnessKind,
        mapping: &PhysicsMapping,
        initial: Reading,
    ) -> Result<ProgressTracker, ProgressError> {
        mapping
            .validate(kind)
            .map_err(|source| ProgressError::Mapping {
                joint: mapping.joint.clone(),
                source,
            })?;
        let wrong = |allowed| ProgressError::InitialReading {
            kind: kind.describe(),
            found: format!("{initial:?}"),
            allowed,
        };
        if !initial.is_finite() {
            return Err(wrong("finite values"));
        }
        let watch = match (kind, initial, &mapping.grasp) {
            (CorrectnessKind::Grasp {}, Reading::Body { position_m, .. }, Some(grasp)) => {
                Watch::Grasp(GraspWatch::new(grasp.clone(), position_m[2]))
            }
            (CorrectnessKind::Grasp {}, _, _) => {
                return Err(wrong("a body reading (the object's position and speed)"));
            }
            (_, Reading::Body { .. }, _) => return Err(wrong("a joint position (m or rad)")),
            (
                CorrectnessKind::Notches { .. } | CorrectnessKind::Curves { .. },
                Reading::Joint(q),
                _,
            ) => Watch::Marks(MarkCounter::new(mapping, q)),
            (CorrectnessKind::Rotation { .. }, Reading::Joint(q), _) => {
                Watch::Ratchet(Ratchet::rotation(mapping.direction, q))
            }
            (CorrectnessKind::Distance { .. }, Reading::Joint(q), _) => {
                Watch::Ratchet(Ratchet::distance(mapping.direction, q))
            }
        };
        Ok(ProgressTracker {
            watch,
            total: 0.0,
            skipped: 0,
        })
    }

    /// The events the reading at time `t_s` (s, any monotonic clock) causes, in order.
    /// A reading of the wrong shape or with a non-finite value is skipped (no events) and
    /// counted in [`ProgressTracker::skipped_readings`].
    pub fn update(&mut self, reading: Reading, t_s: f64) -> Vec<ProgressEvent> {
        if !reading.is_finite() {
            self.skipped += 1;
            return Vec::new();
        }
        let events = match (&mut self.watch, reading) {
            (Watch::Marks(counter), Reading::Joint(q)) => counter.update(q),
            (Watch::Ratchet(ratchet), Reading::Joint(q)) => ratchet.update(q),
            (
                Watch::Grasp(watch),
                Reading::Body {
                    position_m,
                    speed_m_s,
                },
            ) => watch.update(position_m, speed_m_s, t_s),
            _ => {
                self.skipped += 1;
                return Vec::new();
            }
        };
        for event in &events {
            match (&self.watch, event) {
                (Watch::Grasp(_), ProgressEvent::Progress(level)) => self.total = *level,
                (_, ProgressEvent::Progress(v)) => self.total += v,
                (_, ProgressEvent::Drop) => {}
            }
        }
        events
    }

    /// The progress so far in the catalog's unit: notches or curves passed, degrees turned,
    /// millimetres slid, or the grasp level.
    pub fn total(&self) -> f64 {
        self.total
    }

    /// How many readings were skipped (wrong shape or not finite).
    pub fn skipped_readings(&self) -> u64 {
        self.skipped
    }
}
