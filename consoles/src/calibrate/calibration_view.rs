//! What the calibration console shows, as plain data built from the [`PoseSession`]: teleop's
//! full-screen console draws it (`teleop::calibrate::calibration_screen`), its line console
//! prints its changes (`teleop::calibrate::calibration_view::PlainCalibrationOutput`).

use crate::Level;
use crate::calibrate::capture_quality::QualityLevel;
use crate::calibrate::pose_session::{Policy, PosePhase, PoseSession};

/// The console's states (the names `--script` waits on).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CalState {
    /// Waiting for the glove's first frame.
    WaitingGlove,
    /// The hand shows a pose; the user copies it and settles.
    Settling,
    /// A capture runs.
    Capturing,
    /// A poor or bad capture waits for the operator.
    Review,
    /// The fit runs.
    Fitting,
    /// The profile is written.
    Complete,
    /// The session or the fit failed.
    Failed,
}

impl CalState {
    /// Every state, in session order.
    pub const ALL: [CalState; 7] = [
        CalState::WaitingGlove,
        CalState::Settling,
        CalState::Capturing,
        CalState::Review,
        CalState::Fitting,
        CalState::Complete,
        CalState::Failed,
    ];

    /// The name scripts use.
    pub fn name(self) -> &'static str {
        match self {
            CalState::WaitingGlove => "waiting_glove",
            CalState::Settling => "settling",
            CalState::Capturing => "capturing",
            CalState::Review => "review",
            CalState::Fitting => "fitting",
            CalState::Complete => "complete",
            CalState::Failed => "failed",
        }
    }

    /// The state of a name.
    pub fn from_name(name: &str) -> Option<CalState> {
        CalState::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The banner.
    pub fn banner(self) -> &'static str {
        match self {
            CalState::WaitingGlove => "WAITING FOR THE GLOVE",
            CalState::Settling => "COPY THE POSE",
            CalState::Capturing => "HOLD STILL: CAPTURING",
            CalState::Review => "CAPTURE REVIEW",
            CalState::Fitting => "FITTING",
            CalState::Complete => "CALIBRATION COMPLETE",
            CalState::Failed => "CALIBRATION FAILED",
        }
    }

    /// The state of a session.
    pub fn of(session: &PoseSession) -> CalState {
        match session.phase() {
            PosePhase::WaitingGlove => CalState::WaitingGlove,
            PosePhase::Settling { .. } => CalState::Settling,
            PosePhase::Capturing { .. } => CalState::Capturing,
            PosePhase::Review { .. } => CalState::Review,
            PosePhase::Fitting => CalState::Fitting,
            PosePhase::Complete => CalState::Complete,
            PosePhase::Failed(_) => CalState::Failed,
        }
    }
}

/// One frame of the console.
#[derive(Debug, Clone, PartialEq)]
pub struct CalibrationView {
    /// The state.
    pub state: CalState,
    /// The current pose's line: `[3/7] pinch_ring`.
    pub title: String,
    /// What the user does now.
    pub instruction: String,
    /// (label, value) of the session's setting.
    pub setup: Vec<(String, String)>,
    /// Each pose: name, status, level.
    pub poses: Vec<(String, String, Level)>,
    /// The banner with its clock.
    pub banner: String,
    /// Lines under the banner.
    pub detail: Vec<String>,
    /// The last capture's meter: fill in [0, 1], its line, its level.
    pub meter: Option<(f64, String, Level)>,
    /// The fit's progress: fraction done and its line.
    pub progress: Option<(f64, String)>,
    /// The fit's table and where the profile went.
    pub results: Vec<String>,
    /// Recent messages, oldest first.
    pub messages: Vec<String>,
}

/// The level a capture quality reads as.
pub fn quality_level(level: QualityLevel) -> Level {
    match level {
        QualityLevel::Good => Level::Ok,
        QualityLevel::Poor => Level::Warn,
        QualityLevel::Bad => Level::Bad,
    }
}

impl CalibrationView {
    /// The view at `now_ns`; `setup` is the session's setting, `results` the fit's lines.
    pub fn build(
        session: &PoseSession,
        setup: &[(String, String)],
        results: &[String],
        now_ns: i64,
    ) -> CalibrationView {
        let state = CalState::of(session);
        let current = current_pose(session);
        let (title, instruction) = pose_title(session, state, current);
        let (banner, mut detail) = phase_banner(session, state, current, now_ns);
        detail.extend(policy_line(session));
        CalibrationView {
            state,
            title,
            instruction,
            setup: setup.to_vec(),
            poses: pose_rows(session, current),
            banner,
            detail,
            meter: capture_meter(session),
            progress: fit_progress(session),
            results: results.to_vec(),
            messages: session.messages().map(str::to_string).collect(),
        }
    }
}

/// The pose and attempt the session is at, while it is at one.
fn current_pose(session: &PoseSession) -> Option<(usize, u32)> {
    match *session.phase() {
        PosePhase::Settling { pose, attempt, .. }
        | PosePhase::Capturing { pose, attempt, .. }
        | PosePhase::Review { pose, attempt } => Some((pose, attempt)),
        _ => None,
    }
}

/// The current pose's line and what the user does now.
fn pose_title(
    session: &PoseSession,
    state: CalState,
    current: Option<(usize, u32)>,
) -> (String, String) {
    let poses = session.poses();
    let n = poses.len();
    match current {
        Some((k, attempt)) => (
            format!(
                "[{}/{n}] {}{}",
                k + 1,
                poses[k].name,
                if attempt > 1 {
                    format!(" · capture {attempt}")
                } else {
                    String::new()
                }
            ),
            poses[k].instruction.clone(),
        ),
        None => (
            "seven poses, then the fit".to_string(),
            match state {
                CalState::WaitingGlove => "Put the glove on and start streaming.".to_string(),
                CalState::Fitting => "The fit runs: the user may rest.".to_string(),
                _ => String::new(),
            },
        ),
    }
}

/// The banner with its clock, and the lines under it.
fn phase_banner(
    session: &PoseSession,
    state: CalState,
    current: Option<(usize, u32)>,
    now_ns: i64,
) -> (String, Vec<String>) {
    let mut detail = Vec::new();
    let timing = session.timing();
    let banner = match *session.phase() {
        PosePhase::Settling { capture_ns, .. } => {
            detail.push(format!(
                "the hand shows the pose: copy it and settle; capture of {:.1} s in a moment",
                timing.capture_s
            ));
            format!(
                "{}  {:.1} s",
                state.banner(),
                ((capture_ns - now_ns) as f64 * 1e-9).max(0.0)
            )
        }
        PosePhase::Capturing { end_ns, .. } => {
            detail.push("keep the pose still until the capture ends".to_string());
            format!(
                "{}  {:.1} s",
                state.banner(),
                ((end_ns - now_ns) as f64 * 1e-9).max(0.0)
            )
        }
        PosePhase::Review { .. } => {
            let bad = current
                .and_then(|(k, _)| session.attempts()[k].last())
                .is_some_and(|a| a.quality.level == QualityLevel::Bad);
            detail.push(if bad {
                "bad capture: r captures the pose again".to_string()
            } else {
                "poor capture: space / Enter accepts it · r captures the pose again".to_string()
            });
            state.banner().to_string()
        }
        PosePhase::Failed(ref reason) => {
            detail.push(reason.clone());
            detail.push("q quits".to_string());
            state.banner().to_string()
        }
        PosePhase::Complete => {
            detail.push(match session.redo_offer() {
                Some(k) => format!(
                    "r captures {} again and fits again · q keeps this fit and quits",
                    session.poses()[k].name
                ),
                None => "q quits".to_string(),
            });
            state.banner().to_string()
        }
        _ => state.banner().to_string(),
    };
    (banner, detail)
}

/// Without an operator: how captures that are not good are decided.
fn policy_line(session: &PoseSession) -> Option<String> {
    match session.policy() {
        Policy::Automatic { max_attempts } => Some(format!(
            "no operator: poor captures are accepted, bad ones retried (at most {max_attempts} per pose)"
        )),
        Policy::Operator => None,
    }
}

/// The last capture's meter: fill, line and level.
fn capture_meter(session: &PoseSession) -> Option<(f64, String, Level)> {
    let poses = session.poses();
    session.last_capture().map(|(k, i)| {
        let a = &session.attempts()[k][i];
        (
            a.quality.meter_fill(),
            format!(
                "{} capture {}: {} · {}",
                poses[k].name,
                i + 1,
                a.quality.level.name().to_uppercase(),
                a.quality.summary()
            ),
            quality_level(a.quality.level),
        )
    })
}

/// Each pose: its name, its captures so far and whether one was accepted.
fn pose_rows(session: &PoseSession, current: Option<(usize, u32)>) -> Vec<(String, String, Level)> {
    session
        .poses()
        .iter()
        .zip(session.attempts())
        .enumerate()
        .map(|(k, (p, attempts))| {
            let history: Vec<&str> = attempts.iter().map(|a| a.quality.level.name()).collect();
            let accepted = session.accepted(k);
            let (status, level) = match (accepted, current) {
                (_, Some((c, _))) if c == k => (
                    if history.is_empty() {
                        "now".to_string()
                    } else {
                        format!("now (so far: {})", history.join(", "))
                    },
                    Level::Warn,
                ),
                (Some(a), _) => (
                    format!("accepted ({})", history.join(", ")),
                    quality_level(a.quality.level),
                ),
                _ => ("-".to_string(), Level::Ok),
            };
            (p.name.clone(), status, level)
        })
        .collect()
}

/// The fit's progress: fraction done and its line.
fn fit_progress(session: &PoseSession) -> Option<(f64, String)> {
    session.fit_progress().map(|p| {
        (
            if p.budget == 0 {
                0.0
            } else {
                (p.done as f64 / p.budget as f64).min(1.0)
            },
            format!(
                "{}/{} evaluations · best {:.3} rad",
                p.done, p.budget, p.best
            ),
        )
    })
}
