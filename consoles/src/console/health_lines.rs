//! The console's health rows, built from the station's status: its drive and watchdog, the
//! glove's rate and input age against the start gate, latency, commands, rejected frames, who
//! listens, the arm, the faults and the hand's tracking (the glove's rows alone in a human
//! study).

use super::health::{Faults, Health, StartLimits};
use crate::Level;

/// The health rows: the station starting, or its drive, input, robot and faults (the glove's
/// rows alone in a human study).
pub(super) fn health_lines(
    health: &Health,
    limits: &StartLimits,
    now_ns: i64,
) -> Vec<(String, String, Level)> {
    if health.received_ns.is_none() {
        return vec![("station".into(), "starting…".into(), Level::Warn)];
    }
    let mut lines = all_health_lines(health, limits, now_ns);
    if limits.drives_robot {
        lines.push(hand_tracking_line(health));
        return lines;
    }
    // A human study: the glove is all there is.
    let mut glove: Vec<_> = lines
        .into_iter()
        .filter(|(k, _, _)| matches!(k.as_str(), "glove" | "input age" | "rejected" | "faults"))
        .collect();
    glove.insert(
        0,
        ("mode".into(), "human study: no robot".into(), Level::Ok),
    );
    glove
}

/// Commanded against measured, where the hand publishes its joint state.
fn hand_tracking_line(health: &Health) -> (String, String, Level) {
    let Some(tracking) = &health.hand_tracking else {
        return (
            "tracking".into(),
            "no measured hand state".into(),
            Level::Ok,
        );
    };
    let level = match (tracking.max_error_deg, tracking.age_ms) {
        (_, Some(age)) if age > 500.0 => Level::Warn,
        (Some(error), _) if error > 10.0 => Level::Warn,
        _ => Level::Ok,
    };
    ("tracking".into(), tracking.line(), level)
}

fn all_health_lines(
    health: &Health,
    limits: &StartLimits,
    now_ns: i64,
) -> Vec<(String, String, Level)> {
    let line = |name: &str, text: String, level| (name.to_string(), text, level);
    let state_level = match health.state.as_str() {
        "engaged" => Level::Ok,
        "held" => Level::Warn,
        _ => Level::Bad,
    };
    let rejected_level = match health.rejected {
        0 => Level::Ok,
        _ => Level::Warn,
    };
    vec![
        line("drive", health.state.clone(), state_level),
        glove_rate_line(health, limits),
        input_age_line(health, limits, now_ns),
        line(
            "latency",
            optional(health.latency_ms, |l| format!("{l:.2} ms")),
            Level::Ok,
        ),
        line(
            "commands",
            format!("{:.0} /s", health.output_rate_hz),
            Level::Ok,
        ),
        line("watchdog", watchdog_text(&health.state), state_level),
        line("rejected", health.rejected.to_string(), rejected_level),
        robot_line(health),
        arm_line(health),
        line(
            "faults",
            faults_text(&health.faults),
            faults_level(&health.faults),
        ),
    ]
}

/// `value` as `shown`, or `-` when there is none.
fn optional(value: Option<f64>, shown: impl Fn(f64) -> String) -> String {
    value.map_or("-".to_string(), shown)
}

/// The glove's rate against the start gate's minimum.
fn glove_rate_line(health: &Health, limits: &StartLimits) -> (String, String, Level) {
    let level = match health.glove_rate_hz >= limits.min_glove_rate_hz {
        true => Level::Ok,
        false => Level::Bad,
    };
    let text = format!(
        "{:.0} Hz (min {:.0})",
        health.glove_rate_hz, limits.min_glove_rate_hz
    );
    ("glove".into(), text, level)
}

/// The age of the station's last input at `now_ns` against the start gate's maximum.
fn input_age_line(health: &Health, limits: &StartLimits, now_ns: i64) -> (String, String, Level) {
    let age = health.input_age_at(now_ns);
    let level = match age {
        Some(a) if a <= limits.max_input_age_ms => Level::Ok,
        _ => Level::Bad,
    };
    let text = age.map_or("no input".to_string(), |a| format!("{a:.0} ms"));
    ("input age".into(), text, level)
}

/// What the watchdog is doing in the station's drive state.
fn watchdog_text(state: &str) -> String {
    match state {
        "engaged" => "ok",
        "held" => "holding (input stale)",
        _ => "disengaged",
    }
    .to_string()
}

/// Who listens to the station's targets (bad when no hand does).
fn robot_line(health: &Health) -> (String, String, Level) {
    let text = match (health.hand_listeners, health.arm_listeners) {
        (Some(0), _) => "no hand listening to the targets".to_string(),
        (Some(h), Some(a)) => format!("hand {h} listening · arm {a}"),
        (Some(h), None) => format!("hand {h} listening"),
        (None, _) => "-".to_string(),
    };
    let level = match health.hand_listeners {
        Some(0) => Level::Bad,
        _ => Level::Ok,
    };
    ("robot".into(), text, level)
}

/// The arm's state (bad when a second publisher drives its command topic).
fn arm_line(health: &Health) -> (String, String, Level) {
    let (text, level) = match (health.second_publisher, health.arm_engaged) {
        (true, _) => ("second publisher: not driven", Level::Bad),
        (false, true) => ("engaged", Level::Ok),
        (false, false) => ("holding", Level::Ok),
    };
    ("arm".into(), text.to_string(), level)
}

/// The fault counts as the console shows them: `none`, or each non-zero count.
fn faults_text(faults: &Faults) -> String {
    let counts = [
        (faults.publish_failed, "not published"),
        (faults.samples_lost, "samples lost"),
        (faults.arm_refused, "arm targets refused"),
        (faults.arm_engage_failed, "arm engages refused"),
        (faults.log_dropped, "messages not logged (disk too slow)"),
    ];
    let shown: Vec<String> = counts
        .iter()
        .filter(|(n, _)| *n > 0)
        .map(|(n, what)| format!("{n} {what}"))
        .collect();
    if shown.is_empty() {
        "none".to_string()
    } else {
        shown.join(" · ")
    }
}

fn faults_level(faults: &Faults) -> Level {
    if faults.any() { Level::Warn } else { Level::Ok }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fault_counts_show_only_what_happened_and_warn() {
        let none = Faults::default();
        assert_eq!(
            (faults_text(&none), faults_level(&none)),
            ("none".into(), Level::Ok)
        );
        let some = Faults {
            publish_failed: 2,
            arm_refused: 1,
            ..Faults::default()
        };
        assert_eq!(
            faults_text(&some),
            "2 not published · 1 arm targets refused"
        );
        assert_eq!(faults_level(&some), Level::Warn);
    }
}
