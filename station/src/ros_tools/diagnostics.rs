//! The station's health as `diagnostic_msgs/DiagnosticArray` (`/diagnostics`), for
//! rqt_robot_monitor and Foxglove's diagnostics panels: one status each for the glove input,
//! the hand and the arm, with the levels an operator acts on.

use msgs::{DiagnosticArray, DiagnosticStatus, KeyValue};

use crate::convert::header;
use crate::station::StationStatus;
use crate::watchdog::{DriveState, WatchdogConfig};

/// The station's diagnostics at `stamp_ns`, `node` naming the statuses (`pomdar_station`).
pub fn diagnostics(
    status: &StationStatus,
    watchdog: &WatchdogConfig,
    node: &str,
    stamp_ns: i64,
) -> DiagnosticArray {
    DiagnosticArray {
        header: header(stamp_ns, ""),
        status: vec![
            glove(status, watchdog, node),
            hand(status, node),
            arm(status, node),
        ],
    }
}

fn value(key: &str, value: impl std::fmt::Display) -> KeyValue {
    KeyValue {
        key: key.to_string(),
        value: value.to_string(),
    }
}

fn glove(status: &StationStatus, watchdog: &WatchdogConfig, node: &str) -> DiagnosticStatus {
    let rejected: u64 = status.counters.rejected.values().sum();
    let (level, message) = match status.input_age_ms {
        None => (DiagnosticStatus::STALE, "no glove frame yet".to_string()),
        Some(age) if age > watchdog.disengage_timeout_ms as f64 => (
            DiagnosticStatus::STALE,
            format!("no new glove frame for {age:.0} ms"),
        ),
        Some(age) if age > watchdog.hold_timeout_ms as f64 => (
            DiagnosticStatus::WARN,
            format!("glove frame {age:.0} ms old: holding"),
        ),
        Some(_) => (
            DiagnosticStatus::OK,
            format!("{:.1} frames/s", status.input_rate_hz),
        ),
    };
    let mut values = vec![
        value("input_rate_hz", format!("{:.1}", status.input_rate_hz)),
        value(
            "input_age_ms",
            status
                .input_age_ms
                .map_or("none".to_string(), |a| format!("{a:.1}")),
        ),
        value("frames_new", status.counters.frames_new),
        value("frames_rejected", rejected),
    ];
    values.extend(
        (status.counters.rejected.iter()).map(|(why, n)| value(&format!("rejected.{why}"), n)),
    );
    DiagnosticStatus {
        level,
        name: format!("{node}: glove"),
        message,
        hardware_id: String::new(),
        values,
    }
}

fn hand(status: &StationStatus, node: &str) -> DiagnosticStatus {
    let c = &status.counters;
    let failed = c.solves_qp_failed;
    let (level, message) = match status.state {
        DriveState::Engaged if failed > 0 => (
            DiagnosticStatus::WARN,
            format!("engaged; {failed} solves failed (held)"),
        ),
        DriveState::Engaged => (DiagnosticStatus::OK, "engaged".to_string()),
        DriveState::Held => (DiagnosticStatus::WARN, "held: input stale".to_string()),
        DriveState::Disengaged => (DiagnosticStatus::OK, "disengaged".to_string()),
    };
    DiagnosticStatus {
        level,
        name: format!("{node}: hand"),
        message,
        hardware_id: String::new(),
        values: vec![
            value("state", format!("{:?}", status.state).to_lowercase()),
            value("output_rate_hz", format!("{:.1}", status.output_rate_hz)),
            value("hand_commands", status.totals.hand_commands),
            value("solves", c.solves),
            value("solves_qp_failed", failed),
            value("last_tip_error_mm", format!("{:.2}", c.last_tip_error_mm)),
        ],
    }
}

fn arm(status: &StationStatus, node: &str) -> DiagnosticStatus {
    let a = &status.arm;
    let refused: u64 = status.totals.arm_refused.values().sum();
    let (level, message) = if !a.enabled {
        (DiagnosticStatus::OK, "no arm".to_string())
    } else if a.second_publisher {
        (
            DiagnosticStatus::ERROR,
            "another publisher drives the arm topic: arm stopped".to_string(),
        )
    } else if a.engaged {
        (DiagnosticStatus::OK, "following the glove".to_string())
    } else {
        (DiagnosticStatus::OK, "clutch released".to_string())
    };
    DiagnosticStatus {
        level,
        name: format!("{node}: arm"),
        message,
        hardware_id: String::new(),
        values: vec![
            value("enabled", a.enabled),
            value("engaged", a.engaged),
            value("constraint", format!("{:?}", a.constraint).to_lowercase()),
            value("arm_targets", status.totals.arm_targets),
            value("arm_refused", refused),
            value("arm_engage_failed", status.totals.arm_engage_failed),
        ],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Station, StationConfig};
    use retarget::HandModel;

    #[test]
    fn a_station_without_input_is_stale_and_names_its_parts() {
        let model = HandModel::orca_v1_right();
        let mut station = Station::new(&StationConfig::default(), model, None).unwrap();
        let status = station.status(1_000_000_000);
        let array = diagnostics(&status, &WatchdogConfig::default(), "pomdar_station", 9);
        let names: Vec<&str> = array.status.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "pomdar_station: glove",
                "pomdar_station: hand",
                "pomdar_station: arm"
            ]
        );
        assert_eq!(array.status[0].level, DiagnosticStatus::STALE);
        assert_eq!(array.status[0].message, "no glove frame yet");
        assert!(
            array.status[0]
                .values
                .iter()
                .any(|v| v.key == "frames_rejected")
        );
    }
}
