//! The scale-free metrics (own-scale tip error, flexion correlation, lag) on recordings made
//! from the robot's own forward kinematics, where the true answer is known.

use super::*;
use crate::hand_model::Limits;

const FRAMES: usize = 200;
const RATE_HZ: f64 = 100.0;

/// Every joint on its own sinusoid inside its limits (periods 60 to 165 frames), at frame `t`
/// (any real `t`, so shifted copies need no clamping).
fn trajectory(model: &HandModel, t: f64) -> Vec<f64> {
    model
        .limits()
        .enumerate()
        .map(|(j, l)| {
            let j = j as f64;
            let phase = 2.0 * std::f64::consts::PI * t / (60.0 + 7.0 * j) + 0.9 * j;
            l.lower_rad + (l.upper_rad - l.lower_rad) * (0.5 + 0.35 * phase.sin())
        })
        .collect()
}

fn robot_keypoints(model: &HandModel, q: &[f64]) -> Vec<Point3<f64>> {
    model.synthetic_keypoints(&model.forward_new(q).unwrap(), KeypointLayout::Lab22)
}

/// Record `FRAMES` frames at `RATE_HZ`: human keypoints from the trajectory at frame `t`
/// passed through `human`, command `command(t)`.
fn record(
    model: &HandModel,
    human: impl Fn(Vec<Point3<f64>>) -> Vec<Point3<f64>>,
    command: impl Fn(f64) -> Vec<f64>,
) -> QualityReport {
    let mut recorder = QualityRecorder::new(model.clone(), KeypointLayout::Lab22);
    for t in 0..FRAMES {
        let t = t as f64;
        let points = human(robot_keypoints(model, &trajectory(model, t)));
        recorder.push_at(t / RATE_HZ, &points, &command(t)).unwrap();
    }
    recorder.report()
}

fn digits(report: &QualityReport) -> &[DigitQuality] {
    &report.per_digit[..5]
}

#[test]
fn the_robot_as_its_own_human_has_no_own_scale_error_full_correlation_and_no_lag() {
    let model = HandModel::orca_v1_right();
    let report = record(&model, |p| p, |t| trajectory(&model, t));
    for d in digits(&report) {
        assert!(d.tip_error_own_scale_mean_mm.unwrap() < 1e-6, "{d:?}");
        assert!(d.tip_error_own_scale_p95_mm.unwrap() < 1e-6, "{d:?}");
        assert!((d.tip_own_scale.unwrap() - 1.0).abs() < 1e-9, "{d:?}");
        assert!(d.flexion_correlation.unwrap() > 0.999, "{d:?}");
    }
    assert!(report.tip_error_own_scale_mean_mm.unwrap() < 1e-6);
    assert!(report.tip_error_own_scale_p95_mm.unwrap() < 1e-6);
    assert!(report.flexion_correlation_mean.unwrap() > 0.999);
    assert_eq!(report.flexion_lag_frames, Some(0), "{report:?}");
    assert_eq!(report.flexion_lag_s, Some(0.0));
    assert!(report.flexion_lag_correlation.unwrap() > 0.999);
    let wrist = &report.per_digit[5];
    assert_eq!(
        (wrist.tip_own_scale, wrist.flexion_correlation),
        (None, None)
    );
}

#[test]
fn a_larger_human_hand_changes_only_the_scales() {
    let model = HandModel::orca_v1_right();
    let layout = KeypointLayout::Lab22;
    let grow = |points: Vec<Point3<f64>>| {
        let wrist = points[layout.wrist()];
        points.iter().map(|p| wrist + (p - wrist) * 1.2).collect()
    };
    let report = record(&model, grow, |t| trajectory(&model, t));
    for d in digits(&report) {
        assert!(d.tip_error_own_scale_mean_mm.unwrap() < 1e-6, "{d:?}");
        assert!((d.tip_own_scale.unwrap() - 1.0 / 1.2).abs() < 1e-9, "{d:?}");
        assert!(d.flexion_correlation.unwrap() > 0.999, "{d:?}");
    }
    assert!((report.tip_scale - 1.0 / 1.2).abs() < 1e-9);
    assert_eq!(report.flexion_lag_frames, Some(0));
}

#[test]
fn own_scales_keep_unreachable_digits_from_shortening_the_others() {
    // The glove puts the human thumb and index tips 30 % further from the palm origin than
    // the robot's: the global scale shrinks and the middle, ring and little fingers, which
    // match exactly, show an error against it; with their own scales they show none.
    let model = HandModel::orca_v1_right();
    let layout = KeypointLayout::Lab22;
    let stretch = |mut points: Vec<Point3<f64>>| {
        let palm = PalmFrame::from_landmarks(&layout.palm_landmarks(&points)).unwrap();
        for f in [Finger::Thumb, Finger::Index] {
            let tip = &mut points[layout.tip(f)];
            *tip = palm.origin + (*tip - palm.origin) * 1.3;
        }
        points
    };
    let report = record(&model, stretch, |t| trajectory(&model, t));
    assert!(report.tip_scale < 0.95, "{report:?}");
    for d in digits(&report) {
        assert!(d.tip_error_own_scale_mean_mm.unwrap() < 1e-6, "{d:?}");
    }
    let middle = &report.per_digit[Finger::Middle.index()];
    assert!(middle.tip_error_mean_mm.unwrap() > 3.0, "{middle:?}");
    assert!((middle.tip_own_scale.unwrap() - 1.0).abs() < 1e-9);
    let index = &report.per_digit[Finger::Index.index()];
    assert!((index.tip_own_scale.unwrap() - 1.0 / 1.3).abs() < 1e-9);
}

#[test]
fn the_lag_is_the_robots_delay_in_frames_and_seconds() {
    let model = HandModel::orca_v1_right();
    for (delay, seconds) in [(5.0, 0.05), (-3.0, -0.03)] {
        let report = record(&model, |p| p, |t| trajectory(&model, t - delay));
        assert_eq!(report.flexion_lag_frames, Some(delay as i64), "{report:?}");
        assert!((report.flexion_lag_s.unwrap() - seconds).abs() < 1e-9);
        assert!(report.flexion_lag_correlation.unwrap() > 0.999);
        // Unshifted, the delay costs correlation.
        assert!(
            report.flexion_correlation_mean.unwrap() < 0.999,
            "{report:?}"
        );
    }
}

#[test]
fn without_times_the_lag_is_in_frames_only() {
    let model = HandModel::orca_v1_right();
    let mut recorder = QualityRecorder::new(model.clone(), KeypointLayout::Lab22);
    for t in 0..60 {
        let t = f64::from(t);
        let points = robot_keypoints(&model, &trajectory(&model, t));
        recorder
            .push(&points, &trajectory(&model, t - 2.0))
            .unwrap();
    }
    let report = recorder.report();
    assert_eq!(report.flexion_lag_frames, Some(2));
    assert_eq!(report.flexion_lag_s, None);
}

#[test]
fn a_still_robot_finger_has_no_correlation_and_an_opposed_one_a_negative_one() {
    let model = HandModel::orca_v1_right();
    let middle: Vec<bool> = QualityRecorder::new(model.clone(), KeypointLayout::Lab22)
        .dof_digit
        .iter()
        .map(|d| *d == Some(Finger::Middle))
        .collect();
    let limits: Vec<Limits> = model.limits().collect();
    let held = |t: f64| {
        let (q, q0) = (trajectory(&model, t), trajectory(&model, 0.0));
        (0..q.len())
            .map(|j| if middle[j] { q0[j] } else { q[j] })
            .collect()
    };
    let report = record(&model, |p| p, held);
    assert_eq!(
        report.per_digit[Finger::Middle.index()].flexion_correlation,
        None
    );
    assert!(
        report.flexion_correlation_mean.unwrap() > 0.999,
        "{report:?}"
    );
    assert_eq!(report.flexion_lag_frames, Some(0));
    // Each middle joint mirrored about its mid-range: the robot opens as the human closes.
    let mirrored = |t: f64| {
        let q = trajectory(&model, t);
        (0..q.len())
            .map(|j| match middle[j] {
                true => limits[j].lower_rad + limits[j].upper_rad - q[j],
                false => q[j],
            })
            .collect()
    };
    let report = record(&model, |p| p, mirrored);
    let d = &report.per_digit[Finger::Middle.index()];
    assert!(d.flexion_correlation.unwrap() < 0.0, "{d:?}");
}

#[test]
fn push_at_needs_increasing_finite_times() {
    let model = HandModel::orca_v1_right();
    let q = trajectory(&model, 0.0);
    let points = robot_keypoints(&model, &q);
    let mut recorder = QualityRecorder::new(model.clone(), KeypointLayout::Lab22);
    recorder.push_at(1.0, &points, &q).unwrap();
    assert!(recorder.push_at(1.0, &points, &q).is_err());
    assert!(recorder.push_at(0.5, &points, &q).is_err());
    assert!(recorder.push_at(f64::NAN, &points, &q).is_err());
    recorder.push(&points, &q).unwrap();
    assert!(recorder.push_at(0.9, &points, &q).is_err());
    recorder.push_at(1.1, &points, &q).unwrap();
    assert_eq!(recorder.len(), 3);
    // One frame without a time: the lag has no seconds.
    let report = recorder.report();
    assert_eq!(report.flexion_lag_s, None);
}
