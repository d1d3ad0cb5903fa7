//! The two pinch definitions on timed frames: a one-frame dip, runs at 30 fps and 100 Hz, a
//! run that changes finger, and the per-pair figures.

use super::*;

fn model() -> HandModel {
    HandModel::orca_v1_right()
}

/// The robot's open pose (every joint a fifth of the way up), its keypoints, and the palm normal.
fn open_robot(
    model: &HandModel,
    layout: KeypointLayout,
) -> (Vec<f64>, Vec<Point3<f64>>, Vector3<f64>) {
    let q: Vec<f64> = model
        .limits()
        .map(|l| l.lower_rad + 0.2 * (l.upper_rad - l.lower_rad))
        .collect();
    let points = model.synthetic_keypoints(&model.forward_new(&q).unwrap(), layout);
    let palm = PalmFrame::from_landmarks(&layout.palm_landmarks(&points)).unwrap();
    let normal = palm.rotation.matrix().column(2).into_owned();
    (q, points, normal)
}

/// A recorder fed the open robot as the command for every frame, at `rate_hz`, where the
/// human's thumb tip sits `gaps_m[k]` off `fingers[k]`'s tip (along the palm normal), or
/// 5 cm off the index tip where `fingers[k]` is None.
fn record(rate_hz: f64, fingers: &[Option<Finger>], gaps_m: &[f64]) -> QualityReport {
    let model = model();
    let layout = KeypointLayout::Lab22;
    let (q, robot, normal) = open_robot(&model, layout);
    let mut recorder = QualityRecorder::new(model, layout);
    for (k, (finger, gap)) in fingers.iter().zip(gaps_m).enumerate() {
        let mut human = robot.clone();
        let (target, offset) = finger.map_or((Finger::Index, 0.05), |f| (f, *gap));
        human[layout.tip(Finger::Thumb)] = human[layout.tip(target)] + normal * offset;
        recorder.push_at(k as f64 / rate_hz, &human, &q).unwrap();
    }
    recorder.report()
}

const I: Option<Finger> = Some(Finger::Index);
const M: Option<Finger> = Some(Finger::Middle);

fn pair<'a>(report: &'a QualityReport, finger: &str) -> &'a PinchPair {
    report
        .pinch_pairs
        .iter()
        .find(|p| p.finger == finger)
        .unwrap()
}

#[test]
fn a_one_frame_dip_is_a_pinch_only_under_the_first_definition() {
    let report = record(30.0, &[None, None, I, None, None], &[0.01; 5]);
    assert_eq!(report.pinch_frames, 1);
    assert_eq!(report.sustained_pinch_frames, 0);
    assert_eq!(report.sustained_pinches_closed_pct, None);
    assert_eq!(pair(&report, "index").frames, 1);
    assert_eq!(pair(&report, "index").sustained_frames, 0);
}

#[test]
fn two_frames_at_30_fps_are_a_sustained_pinch() {
    let report = record(30.0, &[None, I, I, None], &[0.01; 4]);
    assert_eq!(report.pinch_frames, 2);
    assert_eq!(report.sustained_pinch_frames, 2);
}

#[test]
fn at_100_hz_a_pinch_needs_40_ms() {
    let three = record(100.0, &[None, I, I, I, None], &[0.01; 5]);
    assert_eq!((three.pinch_frames, three.sustained_pinch_frames), (3, 0));
    let four = record(100.0, &[None, I, I, I, I, None], &[0.01; 6]);
    assert_eq!((four.pinch_frames, four.sustained_pinch_frames), (4, 4));
}

#[test]
fn a_run_that_changes_finger_is_two_runs() {
    // Index for one frame, then middle for two: only the middle's run holds.
    let report = record(30.0, &[I, M, M, None], &[0.01; 4]);
    assert_eq!(report.pinch_frames, 3);
    assert_eq!(report.sustained_pinch_frames, 2);
    assert_eq!(pair(&report, "index").sustained_frames, 0);
    assert_eq!(pair(&report, "middle").sustained_frames, 2);
}

#[test]
fn each_pair_reports_the_robot_and_human_distances_of_its_sustained_frames() {
    let report = record(
        30.0,
        &[I, I, I, None, I],
        &[0.010, 0.012, 0.014, 0.0, 0.004],
    );
    let index = pair(&report, "index");
    assert_eq!((index.frames, index.sustained_frames), (4, 3));
    let human = index.human_gap_mean_mm.unwrap();
    assert!((human - 12.0).abs() < 1e-6, "{human}");
    // The robot stays open: the same distance every frame, none closed.
    let model = model();
    let layout = KeypointLayout::Lab22;
    let (_, robot, _) = open_robot(&model, layout);
    let open_mm =
        (robot[layout.tip(Finger::Index)] - robot[layout.tip(Finger::Thumb)]).norm() * 1e3;
    assert!(open_mm > PINCH_CLOSED_M * 1e3, "the test pose is open");
    for figure in [index.robot_gap_mean_mm, index.robot_gap_p95_mm] {
        assert!(
            (figure.unwrap() - open_mm).abs() < 1e-6,
            "{figure:?} vs {open_mm}"
        );
    }
    assert_eq!((index.closed_frames, index.sustained_closed_frames), (0, 0));
    assert_eq!(report.sustained_pinches_closed_pct, Some(0.0));
    let ring = pair(&report, "ring");
    assert_eq!((ring.frames, ring.robot_gap_mean_mm), (0, None));
}
