#![allow(clippy::unwrap_used)]

use super::*;

const MS: i64 = NS_PER_MS;

/// A slow sine (0.5 Hz, 0.6 rad) commanded every `period_ms` for `duration_ms`.
fn sine_commands(period_ms: i64, duration_ms: i64) -> Vec<(i64, f64)> {
    (0..duration_ms / period_ms)
        .map(|k| {
            let t = k * period_ms * MS;
            (t, 0.6 * (std::f64::consts::PI * t as f64 * 1e-9).sin())
        })
        .collect()
}

/// The command in force at `t_ns`.
fn in_force(commands: &[(i64, f64)], t_ns: i64) -> Option<f64> {
    commands
        .iter()
        .rev()
        .find(|(s, _)| *s <= t_ns)
        .map(|(_, c)| *c)
}

/// Measured every 10 ms from `first_ms`: the command in force `lag_ms` earlier, plus
/// `offset_deg`.
fn measured_as(
    commands: &[(i64, f64)],
    first_ms: f64,
    duration_ms: i64,
    lag_ms: f64,
    offset_deg: f64,
) -> Vec<(i64, f64)> {
    (0..duration_ms / 10)
        .filter_map(|i| {
            let t = ((first_ms + 10.0 * i as f64) * 1e6) as i64;
            let c = in_force(commands, t - (lag_ms * 1e6) as i64)?;
            Some((t, c + offset_deg.to_radians()))
        })
        .collect()
}

fn track(commanded: Vec<(i64, f64)>, measured: Vec<(i64, f64)>) -> JointTrack {
    JointTrack {
        joint: "index_mcp".into(),
        commanded,
        measured,
    }
}

#[test]
fn a_constant_offset_is_the_rms_and_max_error_at_no_lag() {
    let commands = sine_commands(2, 4000);
    let small = track(
        commands.clone(),
        measured_as(&commands, 1.5, 4000, 0.0, 3.0),
    );
    let j = track_joint(&small, TrackingSettings::default());
    assert_eq!(j.commanded_samples, 2000);
    assert_eq!(j.measured_samples, 400);
    assert_eq!(j.compared_samples, 400);
    assert!((j.rms_error_deg.unwrap() - 3.0).abs() < 1e-9, "{j:?}");
    assert!((j.max_error_deg.unwrap() - 3.0).abs() < 1e-9, "{j:?}");
    assert_eq!(j.over_threshold_share, Some(0.0));
    assert_eq!(j.lag_ms, Some(0.0));
    assert!((j.lag_correlation.unwrap() - 1.0).abs() < 1e-9, "{j:?}");
    let large = track(
        commands.clone(),
        measured_as(&commands, 1.5, 4000, 0.0, -6.0),
    );
    let j = track_joint(&large, TrackingSettings::default());
    assert!((j.rms_error_deg.unwrap() - 6.0).abs() < 1e-9, "{j:?}");
    assert_eq!(j.over_threshold_share, Some(1.0));
}

#[test]
fn a_known_lag_is_found_whatever_the_offset() {
    let commands = sine_commands(2, 4000);
    for (lag_ms, offset_deg) in [(40.0, 0.0), (40.0, 4.0), (123.0, -2.0), (0.0, 1.0)] {
        let t = track(
            commands.clone(),
            measured_as(&commands, 1.5, 4000, lag_ms, offset_deg),
        );
        let j = track_joint(&t, TrackingSettings::default());
        let found = j.lag_ms.unwrap();
        assert!((found - lag_ms).abs() <= 1.0, "lag {lag_ms}: {j:?}");
        assert!(j.lag_correlation.unwrap() > 0.999, "{j:?}");
        // A lag makes an error beyond the offset: the command moved meanwhile.
        if lag_ms > 0.0 {
            assert!(j.rms_error_deg.unwrap() > offset_deg.abs(), "{j:?}");
        }
    }
}

#[test]
fn a_first_order_lag_shows_as_about_its_time_constant() {
    // The mock hand: commands at 25 Hz, a 100 Hz first-order lag of 30 ms.
    let commands = sine_commands(40, 6000);
    let alpha = 1.0 - (-10.0_f64 / 30.0).exp();
    let mut state = 0.0;
    let mut measured = Vec::new();
    for i in 0..600 {
        let t = (i * 10 + 5) * MS;
        state += alpha * (in_force(&commands, t).unwrap_or(0.0) - state);
        measured.push((t, state));
    }
    let j = track_joint(&track(commands, measured), TrackingSettings::default());
    let lag = j.lag_ms.unwrap();
    // The discrete filter's delay at low frequency is (1 − α) / α samples ≈ 25 ms.
    assert!((15.0..=45.0).contains(&lag), "{j:?}");
    assert!(j.rms_error_deg.unwrap() > 0.5, "{j:?}");
}

#[test]
fn the_share_over_the_threshold_is_a_share_of_time() {
    let commands = vec![(0, 0.0)];
    let deg = |d: f64| d.to_radians();
    // 0–10 ms: 1°, 10–40 ms: 8°, 40–100 ms: 2°, then a last sample without duration.
    let measured = vec![
        (0, deg(1.0)),
        (10 * MS, deg(8.0)),
        (40 * MS, deg(2.0)),
        (100 * MS, deg(20.0)),
    ];
    let j = track_joint(&track(commands, measured), TrackingSettings::default());
    assert!(
        (j.over_threshold_share.unwrap() - 0.3).abs() < 1e-12,
        "{j:?}"
    );
    assert!((j.max_error_deg.unwrap() - 20.0).abs() < 1e-9, "{j:?}");
    // A command that never moves gives nothing to align.
    assert_eq!(j.lag_ms, None);
}

#[test]
fn samples_before_the_first_command_are_not_compared_and_order_does_not_matter() {
    let commands = vec![(50 * MS, 0.2), (20 * MS, 0.1)];
    let measured = vec![(60 * MS, 0.2), (10 * MS, 0.0), (30 * MS, 0.1)];
    let j = track_joint(&track(commands, measured), TrackingSettings::default());
    assert_eq!(j.measured_samples, 3);
    assert_eq!(j.compared_samples, 2);
    assert_eq!(j.max_error_deg, Some(0.0));
    assert_eq!(j.over_threshold_share, Some(0.0));
    let nothing = track_joint(&track(vec![(0, 0.1)], vec![]), TrackingSettings::default());
    assert_eq!(nothing.compared_samples, 0);
    assert_eq!(nothing.rms_error_deg, None);
    assert_eq!(nothing.over_threshold_share, None);
    assert_eq!(nothing.lag_ms, None);
}

#[test]
fn the_report_keeps_the_order_and_names_the_worst_joint() {
    let commands = sine_commands(2, 1000);
    let mut good = track(
        commands.clone(),
        measured_as(&commands, 1.5, 1000, 0.0, 1.0),
    );
    good.joint = "thumb_mcp".into();
    let mut bad = track(
        commands.clone(),
        measured_as(&commands, 1.5, 1000, 0.0, 7.0),
    );
    bad.joint = "wrist".into();
    let report = tracking_report(&[good, bad], TrackingSettings::default());
    let names: Vec<_> = report.joints.iter().map(|j| j.joint.as_str()).collect();
    assert_eq!(names, ["thumb_mcp", "wrist"]);
    assert_eq!(report.worst_joint().unwrap().joint, "wrist");
}

#[test]
fn the_chart_has_a_panel_per_joint_in_seconds_and_degrees() {
    let commands = vec![(2_000 * MS, 0.0), (2_500 * MS, 1.0)];
    let measured = vec![(2_100 * MS, 0.0), (3_000 * MS, std::f64::consts::FRAC_PI_2)];
    let tracks = [track(commands, measured), JointTrack::default()];
    let report = tracking_report(&tracks, TrackingSettings::default());
    let chart = tracking_chart(&tracks, &report, "Commanded vs measured", None);
    assert_eq!(chart.panels.len(), 2);
    let p = &chart.panels[0];
    assert!(p.title.starts_with("index_mcp  RMS "), "{}", p.title);
    assert_eq!(p.commanded[1].0, 0.5);
    assert!((p.commanded[1].1 - 1.0_f64.to_degrees()).abs() < 1e-9);
    assert_eq!(p.measured[1], (1.0, 90.0));
    assert_eq!(chart.panels[1].title, "  RMS -");
}
