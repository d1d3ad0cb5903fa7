//! What the console shows, as plain data built from the session and the station's health: the
//! full-screen console draws it (`teleop::console::screen`), the line console prints its changes
//! (`teleop::console::plain_output`).

use scoring::{ArmConstraint, CorrectnessKind, MeanStd, TaskSpec};
use station::hand_convention::Verification;

use super::health::{Health, StartLimits};
use super::health_lines::health_lines;
use super::manifest::{Manifest, ManifestTrial};
use super::trial_flow::{Slot, TrialFlow, TrialPhase};

/// The console's main states.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Screen {
    /// Between trials, the station not engaged.
    WaitingEngage,
    /// Between trials, engaged: the next trial may start.
    Ready,
    /// Counting down to a trial's start.
    Countdown,
    /// A trial runs.
    Running,
    /// A trial's log is being finished and scored.
    Finishing,
    /// The last trial's result, between trials.
    Summary,
    /// Every planned trial is done.
    Complete,
}

impl Screen {
    /// Every state, in the order of a trial.
    pub const ALL: [Screen; 7] = [
        Screen::WaitingEngage,
        Screen::Ready,
        Screen::Countdown,
        Screen::Running,
        Screen::Finishing,
        Screen::Summary,
        Screen::Complete,
    ];

    /// The name scripts use (`wait running`).
    pub fn name(self) -> &'static str {
        match self {
            Screen::WaitingEngage => "waiting_engage",
            Screen::Ready => "ready",
            Screen::Countdown => "countdown",
            Screen::Running => "running",
            Screen::Finishing => "finishing",
            Screen::Summary => "summary",
            Screen::Complete => "complete",
        }
    }

    /// The state of a name.
    pub fn from_name(name: &str) -> Option<Screen> {
        Screen::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The banner of the full-screen console.
    pub fn banner(self) -> &'static str {
        match self {
            Screen::WaitingEngage => "WAITING FOR ENGAGE",
            Screen::Ready => "READY",
            Screen::Countdown => "COUNTING DOWN",
            Screen::Running => "RUNNING",
            Screen::Finishing => "SAVING THE TRIAL",
            Screen::Summary => "TRIAL SUMMARY",
            Screen::Complete => "SESSION COMPLETE",
        }
    }

    /// The state the session and the health make.
    pub fn of(flow: &TrialFlow, health: &Health) -> Screen {
        match flow.phase() {
            TrialPhase::Countdown { .. } => Screen::Countdown,
            TrialPhase::Running { .. } => Screen::Running,
            TrialPhase::Finishing { .. } | TrialPhase::Quitting => Screen::Finishing,
            TrialPhase::Complete => Screen::Complete,
            TrialPhase::Idle if flow.last_trial().is_some() => Screen::Summary,
            TrialPhase::Idle if health.engaged() => Screen::Ready,
            TrialPhase::Idle
                if !flow.limits().drives_robot && health.glove_ready(flow.limits()) =>
            {
                Screen::Ready
            }
            TrialPhase::Idle => Screen::WaitingEngage,
        }
    }
}

pub use crate::Level;

/// The setting that does not change during a session.
#[derive(Debug, Clone)]
pub struct SessionInfo {
    /// The task.
    pub task: TaskSpec,
    /// The user, operator, embodiment, profile, baseline (label, value).
    pub setup: Vec<(String, String)>,
    /// The baseline's mean time for the task, s.
    pub baseline_s: Option<f64>,
    /// Trial start limits.
    pub limits: StartLimits,
    /// Whether the hand's command conventions (the policy output table) were checked on the
    /// hand; `None` when the station sends no policy output.
    pub hand_convention: Option<Verification>,
}

/// One frame of the console.
#[derive(Debug, Clone, PartialEq)]
pub struct ConsoleView {
    /// The state.
    pub screen: Screen,
    /// Task line.
    pub title: String,
    /// What the operator does in this task.
    pub instruction: String,
    /// (label, value) of the session's setting.
    pub setup: Vec<(String, String)>,
    /// (label, value, level) of the live health.
    pub health: Vec<(String, String, Level)>,
    /// The banner with its clock: `RUNNING  00:12.4`.
    pub banner: String,
    /// Lines under the banner: the trial, its marks, what to press.
    pub detail: Vec<String>,
    /// The last trial and the series so far.
    pub results: Vec<String>,
    /// Recent messages, oldest first.
    pub messages: Vec<String>,
}

/// The task's instruction for the operator: what to mark and how the arm moves (with a robot),
/// or that the participant uses their own hand (a human study).
pub fn instruction(task: &TaskSpec, drives_robot: bool) -> String {
    let marks = match task.correctness {
        CorrectnessKind::Notches { count } => {
            format!("press + at each of the {count} notches passed (- takes one back)")
        }
        CorrectnessKind::Curves { count } => {
            format!("press + at each of the {count} curves cleared (- takes one back)")
        }
        CorrectnessKind::Rotation { full_deg } => {
            format!("press p and type the degrees turned (full: {full_deg}°)")
        }
        CorrectnessKind::Distance { full_mm } => {
            format!("press p and type the millimetres slid (full: {full_mm} mm)")
        }
        CorrectnessKind::Grasp {} => {
            "press p and type the level: 1 relocated, 0.5 lifted then dropped, 0 not lifted; d marks a drop".to_string()
        }
    };
    let arm = match task.arm {
        _ if !drives_robot => "the participant does the task with their own right hand",
        ArmConstraint::Fixed => "arm fixed",
        ArmConstraint::VerticalAxis => "arm moves on the vertical axis only",
        ArmConstraint::HorizontalAxis => "arm moves on the horizontal axis only",
        ArmConstraint::Free => "arm free",
    };
    format!("{}: {marks}; {arm}.", task.name)
}

fn clock(seconds: f64) -> String {
    let seconds = seconds.max(0.0);
    let minutes = (seconds / 60.0).floor();
    format!("{:02}:{:04.1}", minutes as u64, seconds - minutes * 60.0)
}

fn fmt_opt(value: Option<f64>, decimals: usize) -> String {
    value.map_or("-".to_string(), |v| format!("{v:.decimals$}"))
}

/// One trial's result in a line.
pub fn trial_result_line(trial: &ManifestTrial, baseline_s: Option<f64>) -> String {
    let which = if trial.practice {
        format!("practice {}", trial.index)
    } else {
        format!("trial {}", trial.index)
    };
    let score = match (trial.score, baseline_s) {
        (Some(s), Some(b)) => format!("score {s:.3} (baseline {b:.1} s)"),
        _ => "score - (no baseline for this task)".to_string(),
    };
    format!(
        "{which}: {} · time {} s · correctness {} · {score} · {}",
        trial.outcome.as_deref().unwrap_or("not scored"),
        fmt_opt(trial.time_s, 1),
        fmt_opt(trial.correctness, 3),
        trial.file
    )
}

impl ConsoleView {
    /// The view at `now_ns`.
    pub fn build(
        flow: &TrialFlow,
        health: &Health,
        info: &SessionInfo,
        now_ns: i64,
    ) -> ConsoleView {
        let screen = Screen::of(flow, health);
        let (banner, mut detail) = phase_banner(flow, health, screen, now_ns);
        detail.extend(next_step(flow, health));
        ConsoleView {
            screen,
            title: title(info, &flow.manifest),
            instruction: instruction(&info.task, info.limits.drives_robot),
            setup: info.setup.clone(),
            health: with_convention(health_lines(health, &info.limits, now_ns), info),
            banner,
            detail,
            results: result_lines(flow, info),
            messages: flow.messages().map(str::to_string).collect(),
        }
    }
}

/// The task line: `V1 name · correctness · embodiment`.
fn title(info: &SessionInfo, manifest: &Manifest) -> String {
    format!(
        "{} {} · {} · {}",
        info.task.id,
        info.task.name,
        info.task.correctness.describe(),
        manifest.embodiment
    )
}

/// The banner with its clock, and the lines under it about the trial in progress.
fn phase_banner(
    flow: &TrialFlow,
    health: &Health,
    screen: Screen,
    now_ns: i64,
) -> (String, Vec<String>) {
    let manifest = &flow.manifest;
    let mut detail = Vec::new();
    let banner = match flow.phase() {
        TrialPhase::Countdown { slot, ends_ns } => {
            detail.push(format!(
                "{} starts in a moment: a aborts the countdown",
                slot.label(manifest)
            ));
            format!(
                "{}  {:.0}",
                screen.banner(),
                ((ends_ns - now_ns) as f64 * 1e-9).max(0.0).ceil()
            )
        }
        TrialPhase::Running {
            slot,
            started_ns,
            file,
        } => {
            let (progress, drops) = flow.marks();
            detail.push(format!("{} → {file}", slot.label(manifest)));
            detail.push(format!(
                "marked: {progress} {} · drops {drops}",
                flow.kind().progress_unit()
            ));
            detail.push(if health.engaged() || !flow.limits().drives_robot {
                "space stops · a aborts · r aborts and redoes".to_string()
            } else {
                format!(
                    "WARNING: the station is {}: the robot holds (the timer runs; a aborts, r redoes)",
                    health.state
                )
            });
            format!(
                "{}  {}",
                screen.banner(),
                clock((now_ns - started_ns) as f64 * 1e-9)
            )
        }
        TrialPhase::Finishing { slot, time_s, .. } => {
            detail.push(format!(
                "{} stopped at {}: finishing and scoring its log",
                slot.label(manifest),
                clock(*time_s)
            ));
            screen.banner().to_string()
        }
        _ if screen == Screen::WaitingEngage && !flow.limits().drives_robot => {
            "WAITING FOR THE GLOVE".to_string()
        }
        _ => screen.banner().to_string(),
    };
    (banner, detail)
}

/// What the operator does next between trials, or that the plan is done.
fn next_step(flow: &TrialFlow, health: &Health) -> Option<String> {
    let manifest = &flow.manifest;
    match (flow.phase(), manifest.next_slot()) {
        (TrialPhase::Idle, Some((practice, index))) => {
            let slot = Slot { practice, index };
            let next = format!("next: {}", slot.label(manifest));
            let human = !flow.limits().drives_robot;
            Some(
                if health.engaged() || (human && health.glove_ready(flow.limits())) {
                    format!("{next} · space starts it (countdown)")
                } else if human {
                    format!("{next} · waiting for the glove (fresh input at the minimum rate)")
                } else {
                    format!("{next} · press e to engage")
                },
            )
        }
        (TrialPhase::Complete, _) => Some(format!(
            "all {} practice and {} recorded trials done · q quits",
            manifest.practice_planned, manifest.trials_planned
        )),
        _ => None,
    }
}

/// The last trial and the series so far.
fn result_lines(flow: &TrialFlow, info: &SessionInfo) -> Vec<String> {
    let manifest = &flow.manifest;
    let mut results = Vec::new();
    if let Some(last) = flow.last_trial() {
        results.push(format!("last {}", trial_result_line(last, info.baseline_s)));
    }
    let series = manifest.series();
    let what = if info.baseline_s.is_some() {
        "score"
    } else {
        "correctness"
    };
    results.push(match MeanStd::of(&series) {
        Some(m) => format!(
            "recorded trials: {}/{} done · {what} {}",
            series.len(),
            manifest.trials_planned,
            m.format(3)
        ),
        None => format!("recorded trials: 0/{} done", manifest.trials_planned),
    });
    results
}

/// The health rows, with the hand convention's when the station drives a robot: `eth_hand_control
/// — unverified: wrist, …` (warning) or `… — verified by ana on …`.
fn with_convention(
    mut rows: Vec<(String, String, Level)>,
    info: &SessionInfo,
) -> Vec<(String, String, Level)> {
    if let (true, Some(v)) = (info.limits.drives_robot, &info.hand_convention) {
        let level = if v.is_verified() {
            Level::Ok
        } else {
            Level::Warn
        };
        rows.push(("hand convention".into(), v.line(), level));
    }
    rows
}

#[cfg(test)]
mod tests {
    use scoring::TaskCatalog;
    use serde_json::json;

    use super::*;
    use crate::console::action::Action;
    use crate::console::manifest::test_manifest;

    const S: i64 = 1_000_000_000;

    fn flow(task: &str) -> (TrialFlow, SessionInfo) {
        let spec = TaskCatalog::builtin()
            .get(task)
            .cloned()
            .unwrap_or_else(|| panic!("{task}"));
        let manifest = test_manifest(task, 0, 2);
        let info = SessionInfo {
            task: spec.clone(),
            setup: vec![],
            baseline_s: None,
            limits: StartLimits::default(),
            hand_convention: Some(Verification::Unverified {
                consumer: "eth_hand_control".into(),
                joints: vec!["wrist".into(), "thumb_mcp".into()],
                of: 17,
            }),
        };
        (
            TrialFlow::new(manifest, spec.correctness, 1.0, StartLimits::default()),
            info,
        )
    }

    fn health(state: &str, at: i64) -> Health {
        Health::from_status(
            &json!({"state": state, "input_rate_hz": 100.0, "input_age_ms": 2.0}),
            at,
        )
    }

    #[test]
    fn the_screen_follows_the_session_and_the_health() {
        let (mut flow, info) = flow("V1");
        assert_eq!(
            Screen::of(&flow, &health("disengaged", 0)),
            Screen::WaitingEngage
        );
        assert_eq!(Screen::of(&flow, &health("engaged", 0)), Screen::Ready);
        flow.act(Action::Start, &health("engaged", 0), 0);
        let view = ConsoleView::build(&flow, &health("engaged", 0), &info, S / 2);
        assert_eq!(view.screen, Screen::Countdown);
        assert_eq!(view.banner, "COUNTING DOWN  1");
        flow.tick(&health("engaged", S), S);
        let view = ConsoleView::build(&flow, &health("held", S), &info, S + 12 * S + S / 2);
        assert_eq!(view.banner, "RUNNING  00:12.5");
        assert!(
            view.detail
                .iter()
                .any(|d| d.contains("WARNING: the station is held")),
            "{:?}",
            view.detail
        );
        assert!(
            view.health
                .iter()
                .any(|(k, _, level)| k == "drive" && *level == Level::Warn)
        );
        assert!(view.health.contains(&(
            "hand convention".to_string(),
            "eth_hand_control — unverified: wrist, thumb_mcp".to_string(),
            Level::Warn
        )));
        for name in Screen::ALL.map(Screen::name) {
            assert_eq!(Screen::from_name(name).map(Screen::name), Some(name));
        }
    }

    #[test]
    fn instructions_say_what_to_mark_and_how_the_arm_moves() {
        let catalog = TaskCatalog::builtin();
        let text = |id: &str| instruction(catalog.get(id).unwrap_or_else(|| panic!("{id}")), true);
        assert!(text("V1").contains("6 notches") && text("V1").contains("vertical axis"));
        assert!(text("G2").contains("0.5 lifted then dropped"));
        assert!(
            text("C1").contains("degrees") || text("C1").contains("millimetres"),
            "{}",
            text("C1")
        );
        let human = instruction(catalog.get("V1").unwrap(), false);
        assert!(human.contains("6 notches") && human.contains("own right hand"));
        assert!(!human.contains("arm"), "{human}");
    }
}
