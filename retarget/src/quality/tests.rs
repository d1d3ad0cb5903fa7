use super::*;

fn model() -> HandModel {
    HandModel::orca_v1_right()
}

/// A pose with every joint at `fraction` of the way from its lower to its upper limit.
fn pose(model: &HandModel, fraction: f64) -> Vec<f64> {
    model
        .limits()
        .map(|l| l.lower_rad + fraction * (l.upper_rad - l.lower_rad))
        .collect()
}

fn keypoints(model: &HandModel, q: &[f64], layout: KeypointLayout) -> Vec<Point3<f64>> {
    model.synthetic_keypoints(&model.forward_new(q).unwrap(), layout)
}

#[test]
fn the_robot_as_its_own_human_has_no_tip_error() {
    let model = model();
    for layout in KeypointLayout::ALL {
        let mut recorder = QualityRecorder::new(model.clone(), layout);
        for k in 0..20 {
            let q = pose(&model, 0.2 + 0.03 * f64::from(k));
            recorder.push(&keypoints(&model, &q, layout), &q).unwrap();
        }
        let report = recorder.report();
        assert_eq!(report.frames, 20);
        assert!((report.tip_scale - 1.0).abs() < 1e-12, "{report:?}");
        assert!(report.tip_error_mean_mm < 1e-9, "{report:?}");
        assert!(report.tip_error_p95_mm < 1e-9, "{report:?}");
        assert_eq!(report.limit_violation_frames, 0);
    }
}

#[test]
fn the_global_scale_absorbs_a_smaller_human_hand() {
    let model = model();
    let layout = KeypointLayout::Lab22;
    let mut recorder = QualityRecorder::new(model.clone(), layout);
    for k in 0..5 {
        let q = pose(&model, 0.3 + 0.1 * f64::from(k));
        let human: Vec<Point3<f64>> = keypoints(&model, &q, layout)
            .into_iter()
            .map(|p| Point3::from(p.coords * 0.8))
            .collect();
        recorder.push(&human, &q).unwrap();
    }
    let report = recorder.report();
    assert!((report.tip_scale - 1.25).abs() < 1e-9, "{report:?}");
    assert!(report.tip_error_mean_mm < 1e-9, "{report:?}");
}

#[test]
fn tip_error_is_the_distance_left_after_the_scale() {
    // Human index tip moved 10 mm along the palm normal in one frame of two: the scale stays
    // 1 (the offset is orthogonal to every tip vector's fit only approximately, so compare
    // with the formula rather than with 10 mm).
    let model = model();
    let layout = KeypointLayout::Lab22;
    let q = pose(&model, 0.5);
    let exact = keypoints(&model, &q, layout);
    let mut moved = exact.clone();
    let palm = PalmFrame::from_landmarks(&layout.palm_landmarks(&exact)).unwrap();
    let normal = palm.rotation.matrix().column(2).into_owned();
    moved[layout.tip(Finger::Index)] += normal * 0.01;
    let mut recorder = QualityRecorder::new(model.clone(), layout);
    recorder.push(&exact, &q).unwrap();
    recorder.push(&moved, &q).unwrap();
    let report = recorder.report();
    let human =
        |points: &[Point3<f64>]| Finger::ALL.map(|f| palm.point_to_palm(&points[layout.tip(f)]));
    let robot = human(&exact);
    let (h1, h2) = (human(&exact), human(&moved));
    let (mut rh, mut hh) = (0.0, 0.0);
    for h in [&h1, &h2] {
        for (r, h) in robot.iter().zip(h.iter()) {
            rh += r.dot(h);
            hh += h.dot(h);
        }
    }
    let s = rh / hh;
    let mut errors: Vec<f64> = Vec::new();
    for h in [&h1, &h2] {
        for (r, h) in robot.iter().zip(h.iter()) {
            errors.push((r - h * s).norm() * 1e3);
        }
    }
    let expected = errors.iter().sum::<f64>() / errors.len() as f64;
    assert!((report.tip_scale - s).abs() < 1e-12);
    assert!(
        (report.tip_error_mean_mm - expected).abs() < 1e-9,
        "{report:?}"
    );
    assert!(
        report.tip_error_mean_mm > 0.5,
        "the moved tip shows: {report:?}"
    );
    let index = &report.per_digit[Finger::Index.index()];
    assert!(index.tip_error_mean_mm.unwrap() > 4.0, "{index:?}");
}

#[test]
fn jerk_and_max_step_follow_their_definitions() {
    let model = model();
    let layout = KeypointLayout::Lab22;
    let j = model.dof_index("index_mcp").unwrap();
    let base = pose(&model, 0.3);
    let points = keypoints(&model, &base, layout);
    // A cubic in the frame index: third difference 6c every frame; a ramp would give 0.
    let c = 1e-3;
    let mut recorder = QualityRecorder::new(model.clone(), layout);
    for t in 0..8 {
        let mut q = base.clone();
        q[j] += c * f64::from(t).powi(3);
        recorder.push(&points, &q).unwrap();
    }
    let report = recorder.report();
    let dofs = model.dof() as f64;
    // 5 third differences per joint, only index_mcp's non-zero.
    assert!(
        (report.jerk_rad - 6.0 * c / dofs).abs() < 1e-12,
        "{report:?}"
    );
    assert!((report.max_step_rad - c * (343.0 - 216.0)).abs() < 1e-12);
    let index = &report.per_digit[Finger::Index.index()];
    let index_dofs = (0..model.dof())
        .filter(|&k| model.dofs()[k].name.starts_with("index_"))
        .count() as f64;
    assert!((index.jerk_rad.unwrap() - 6.0 * c / index_dofs).abs() < 1e-12);
    assert_eq!(
        report.per_digit[Finger::Middle.index()].max_step_rad,
        Some(0.0)
    );
    let wrist = report.per_digit.last().unwrap();
    assert_eq!(wrist.digit, "wrist");
    assert_eq!(wrist.jerk_rad, Some(0.0));
}

#[test]
fn every_degree_of_freedom_belongs_to_its_digit_or_the_wrist() {
    let model = model();
    let recorder = QualityRecorder::new(model.clone(), KeypointLayout::Lab22);
    for (dof, digit) in model.dofs().iter().zip(&recorder.dof_digit) {
        let expected = match dof.name.split('_').next().unwrap() {
            "thumb" => Some(Finger::Thumb),
            "index" => Some(Finger::Index),
            "middle" => Some(Finger::Middle),
            "ring" => Some(Finger::Ring),
            "pinky" => Some(Finger::Little),
            _ => None,
        };
        assert_eq!(*digit, expected, "{}", dof.name);
    }
}

#[test]
fn limit_violations_count_frames_beyond_the_tolerance_or_not_finite() {
    let model = model();
    let layout = KeypointLayout::Lab22;
    let q = pose(&model, 0.5);
    let points = keypoints(&model, &q, layout);
    let upper = model.dofs()[3].limits.upper_rad;
    let mut recorder = QualityRecorder::new(model.clone(), layout);
    let mut at_limit = q.clone();
    at_limit[3] = upper + 0.5e-9;
    recorder.push(&points, &at_limit).unwrap();
    let mut beyond = q.clone();
    beyond[3] = upper + 1e-6;
    recorder.push(&points, &beyond).unwrap();
    let mut nan = q.clone();
    nan[0] = f64::NAN;
    recorder.push(&points, &nan).unwrap();
    let report = recorder.report();
    assert_eq!(report.frames, 3);
    assert_eq!(report.limit_violation_frames, 2);
    assert!(report.tip_error_mean_mm.is_finite());
    assert!(report.max_step_rad.is_finite());
    assert!(recorder.push(&points, &q[1..]).is_err());
    assert!(recorder.push(&points[1..], &q).is_err());
    assert_eq!(recorder.len(), 3);
}

#[test]
fn a_human_pinch_is_judged_by_the_robot_gap() {
    let model = model();
    let layout = KeypointLayout::Lab22;
    let q = pose(&model, 0.5);
    let robot = keypoints(&model, &q, layout);
    let robot_gap = (robot[layout.tip(Finger::Middle)] - robot[layout.tip(Finger::Thumb)]).norm();
    assert!(robot_gap > PINCH_CLOSED_M, "the test pose is open");
    let mut recorder = QualityRecorder::new(model.clone(), layout);
    // Human thumb 1 cm from the middle tip along the palm normal (a pinch, the robot open),
    // then 3 cm (none).
    let palm = PalmFrame::from_landmarks(&layout.palm_landmarks(&robot)).unwrap();
    let normal = palm.rotation.matrix().column(2).into_owned();
    for offset in [0.01, 0.03] {
        let mut human = robot.clone();
        human[layout.tip(Finger::Thumb)] = human[layout.tip(Finger::Middle)] + normal * offset;
        recorder.push(&human, &q).unwrap();
    }
    // And a human thumb tip on the index tip.
    let mut human = robot.clone();
    human[layout.tip(Finger::Thumb)] = human[layout.tip(Finger::Index)];
    recorder.push(&human, &q).unwrap();
    let report = recorder.report();
    assert_eq!(report.pinch_frames, 2);
    assert_eq!(report.pinches_closed_pct, Some(0.0));
    let middle = &report.per_digit[Finger::Middle.index()];
    assert_eq!(middle.pinch_frames, 1);
    let index = &report.per_digit[Finger::Index.index()];
    assert_eq!(index.pinch_frames, 1);
    let index_gap = (robot[layout.tip(Finger::Index)] - robot[layout.tip(Finger::Thumb)]).norm();
    let expected = (robot_gap + index_gap) / 2.0 * 1e3;
    assert!((report.pinch_gap_mean_mm.unwrap() - expected).abs() < 1e-9);
}
