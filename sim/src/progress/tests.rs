//! Scripted reading sequences, their events run through `scoring::correctness`.

use scoring::{CorrectnessKind, Mark, correctness};

use super::*;

/// The lab's V marks (the shipped catalog's), m.
const V_MARKS: [f64; 6] = [0.03575, 0.06775, 0.09975, 0.13175, 0.16375, 0.19575];

/// Feeds `readings` (one per 5 ms) to a tracker; returns its marks and its total.
fn run(
    kind: &CorrectnessKind,
    mapping: &PhysicsMapping,
    readings: &[Reading],
) -> (Vec<(i64, Mark)>, f64) {
    let mut tracker = ProgressTracker::new(kind, mapping, readings[0]).unwrap();
    let mut marks = Vec::new();
    for (i, reading) in readings.iter().enumerate().skip(1) {
        let t_s = i as f64 * 0.005;
        for event in tracker.update(*reading, t_s) {
            marks.push(((t_s * 1e9) as i64, event.mark()));
        }
    }
    (marks, tracker.total())
}

fn value(kind: &CorrectnessKind, marks: &[(i64, Mark)]) -> f64 {
    correctness(kind, marks, None).unwrap().value
}

/// Joint readings moving linearly from `from` to `to` in `n` steps (excluding `from`).
fn ramp(from: f64, to: f64, n: usize) -> Vec<Reading> {
    (1..=n)
        .map(|i| Reading::Joint(from + (to - from) * i as f64 / n as f64))
        .collect()
}

/// Readings alternating `±amplitude` around `centre`.
fn jitter(centre: f64, amplitude: f64, n: usize) -> Vec<Reading> {
    (0..n)
        .map(|i| Reading::Joint(centre + if i % 2 == 0 { amplitude } else { -amplitude }))
        .collect()
}

fn v_mapping() -> PhysicsMapping {
    PhysicsMapping {
        marks: V_MARKS.to_vec(),
        ..PhysicsMapping::joint("disk_rod_slide_joint")
    }
}

#[test]
fn notches_count_once_through_noise_at_a_mark_and_come_off_going_back() {
    let kind = CorrectnessKind::Notches { count: 6 };
    let mut readings = vec![Reading::Joint(-0.01)];
    readings.extend(ramp(-0.01, V_MARKS[2] + 0.0012, 60));
    // Resting on the third platform with ±0.9 mm of noise: one +1, no stream.
    readings.extend(jitter(V_MARKS[2] + 0.0012, 0.0009, 200));
    readings.extend(jitter(V_MARKS[2], 0.0009, 200));
    let (marks, total) = run(&kind, &v_mapping(), &readings);
    assert_eq!(marks.len(), 3, "{marks:?}");
    assert_eq!(total, 3.0);
    assert_eq!(value(&kind, &marks), 0.5);

    // Back down below the second mark: −1 twice; then up through all six.
    readings.extend(ramp(V_MARKS[2], V_MARKS[1] - 0.002, 20));
    let (marks, total) = run(&kind, &v_mapping(), &readings);
    assert_eq!(total, 1.0);
    assert_eq!(value(&kind, &marks), 1.0 / 6.0);
    readings.extend(ramp(V_MARKS[1] - 0.002, 0.26, 100));
    let (marks, total) = run(&kind, &v_mapping(), &readings);
    assert_eq!(total, 6.0);
    assert_eq!(value(&kind, &marks), 1.0);
    let ones: Vec<f64> = marks
        .iter()
        .map(|(_, m)| match m {
            Mark::Progress(v) => *v,
            Mark::Drop => f64::NAN,
        })
        .collect();
    assert!(ones.iter().all(|v| v.abs() == 1.0), "{ones:?}");
}

#[test]
fn curves_run_the_other_way_with_a_decreasing_mapping() {
    let kind = CorrectnessKind::Curves { count: 4 };
    let mapping = PhysicsMapping {
        marks: vec![-0.02, -0.06, -0.10, -0.14],
        direction: Direction::Decreasing,
        ..PhysicsMapping::joint("rail_slide")
    };
    let mut readings = vec![Reading::Joint(0.0)];
    readings.extend(ramp(0.0, -0.11, 50));
    let (marks, _) = run(&kind, &mapping, &readings);
    assert_eq!(value(&kind, &marks), 0.75);
    readings.extend(ramp(-0.11, 0.05, 50));
    let (marks, total) = run(&kind, &mapping, &readings);
    assert_eq!((total, value(&kind, &marks)), (0.0, 0.0));
}

#[test]
fn marks_passed_before_the_start_are_not_progress_and_never_undo_below_zero() {
    let kind = CorrectnessKind::Notches { count: 6 };
    let start = V_MARKS[3] + 0.005;
    let mut readings = vec![Reading::Joint(start)];
    readings.extend(ramp(start, 0.0, 40));
    readings.extend(ramp(0.0, V_MARKS[4] + 0.002, 40));
    let (marks, total) = run(&kind, &v_mapping(), &readings);
    assert_eq!(total, 1.0);
    assert_eq!(value(&kind, &marks), 1.0 / 6.0);
}

#[test]
fn rotation_counts_whole_degrees_on_the_best_angle() {
    let kind = CorrectnessKind::Rotation { full_deg: 360.0 };
    let mapping = PhysicsMapping::joint("rotor_hinge");
    let deg = f64::to_radians;
    let mut readings = vec![Reading::Joint(0.5)];
    readings.extend(ramp(0.5, 0.5 + deg(200.4), 300));
    readings.extend(ramp(0.5 + deg(200.4), 0.5 + deg(90.0), 100)); // turned back: no change
    let (marks, total) = run(&kind, &mapping, &readings);
    assert_eq!(total, 200.0);
    assert!(
        marks
            .iter()
            .all(|(_, m)| matches!(m, Mark::Progress(v) if *v >= 1.0))
    );
    assert_eq!(value(&kind, &marks), 200.0 / 360.0);
    // Forward again, a full turn from the start: exactly 360, not 359.
    readings.extend(ramp(0.5 + deg(90.0), 0.5 + std::f64::consts::TAU, 300));
    let (marks, total) = run(&kind, &mapping, &readings);
    assert_eq!(total, 360.0);
    assert_eq!(value(&kind, &marks), 1.0);
}

#[test]
fn a_decreasing_hinge_turns_forward_when_its_angle_falls() {
    let kind = CorrectnessKind::Rotation { full_deg: 360.0 };
    let mapping = PhysicsMapping {
        direction: Direction::Decreasing,
        ..PhysicsMapping::joint("bolt_hinge")
    };
    let mut readings = vec![Reading::Joint(0.0)];
    readings.extend(ramp(0.0, -std::f64::consts::PI, 100));
    let (marks, total) = run(&kind, &mapping, &readings);
    assert_eq!((total, value(&kind, &marks)), (180.0, 0.5));
    let mut backwards = vec![Reading::Joint(0.0)];
    backwards.extend(ramp(0.0, 3.0, 100));
    assert_eq!(run(&kind, &mapping, &backwards).1, 0.0);
}

#[test]
fn distance_counts_whole_millimetres_through_noise() {
    let kind = CorrectnessKind::Distance { full_mm: 200.0 };
    let mapping = PhysicsMapping::joint("rod_slide");
    let mut readings = vec![Reading::Joint(0.0)];
    readings.extend(ramp(0.0, 0.1004, 100));
    readings.extend(jitter(0.1, 0.0003, 100));
    readings.extend(ramp(0.1, 0.05, 20));
    let (marks, total) = run(&kind, &mapping, &readings);
    assert_eq!(total, 100.0);
    assert_eq!(value(&kind, &marks), 0.5);
    readings.extend(ramp(0.05, 0.2, 100));
    let (marks, total) = run(&kind, &mapping, &readings);
    assert_eq!(total, 200.0);
    assert_eq!(value(&kind, &marks), 1.0);
}

fn body(x: f64, y: f64, z: f64, speed_m_s: f64) -> Reading {
    Reading::Body {
        position_m: [x, y, z],
        speed_m_s,
    }
}

fn grasp_mapping() -> PhysicsMapping {
    PhysicsMapping {
        grasp: Some(GraspMapping::with_target(
            [0.45, 0.10, 0.0],
            [0.55, 0.20, 0.04],
        )),
        ..PhysicsMapping::joint("g_free")
    }
}

const START: (f64, f64, f64) = (0.5, -0.1, 0.03);

/// Readings carrying the object from `a` to `b` in `n` steps at 0.2 m/s.
fn carry(a: (f64, f64, f64), b: (f64, f64, f64), n: usize) -> Vec<Reading> {
    (1..=n)
        .map(|i| {
            let s = i as f64 / n as f64;
            let at = |p: f64, q: f64| p + (q - p) * s;
            body(at(a.0, b.0), at(a.1, b.1), at(a.2, b.2), 0.2)
        })
        .collect()
}

/// Readings of the object resting at `p` for `seconds`.
fn rest(p: (f64, f64, f64), seconds: f64) -> Vec<Reading> {
    let n = (seconds / 0.005).round() as usize;
    vec![body(p.0, p.1, p.2, 0.001); n]
}

/// The object resting at [`START`], then `segments`.
fn grasp_run(segments: &[Vec<Reading>]) -> (Vec<(i64, Mark)>, f64) {
    let mut readings = vec![body(START.0, START.1, START.2, 0.0)];
    readings.extend(segments.iter().flatten());
    run(&CorrectnessKind::Grasp {}, &grasp_mapping(), &readings)
}

#[test]
fn grasp_levels_follow_lift_rest_in_the_target_and_leaving_it() {
    let kind = CorrectnessKind::Grasp {};
    let (up, over, down) = ((0.5, -0.1, 0.10), (0.5, 0.15, 0.10), (0.5, 0.15, 0.031));
    let mut segments = vec![
        carry(START, up, 20),
        carry(up, over, 40),
        carry(over, down, 20),
    ];
    segments.push(rest(down, 0.15));
    let (marks, total) = grasp_run(&segments);
    assert_eq!((total, value(&kind, &marks)), (0.5, 0.5), "not yet at rest");
    segments.push(rest(down, 0.15));
    let (marks, total) = grasp_run(&segments);
    assert_eq!(marks.len(), 2, "{marks:?}");
    assert_eq!((total, value(&kind, &marks)), (1.0, 1.0));
    // Pushed out of the target afterwards: 0.5 again, and no drop (it was not lifted).
    segments.push(carry(down, (0.5, 0.3, 0.031), 20));
    segments.push(rest((0.5, 0.3, 0.031), 0.5));
    let (marks, total) = grasp_run(&segments);
    assert_eq!(marks.len(), 3, "{marks:?}");
    assert_eq!((total, value(&kind, &marks)), (0.5, 0.5));
}

#[test]
fn grasp_a_drop_outside_the_target_is_half_and_a_push_is_nothing() {
    let kind = CorrectnessKind::Grasp {};
    let high = (0.5, -0.1, 0.12);
    let dropped = (0.5, 0.0, 0.03);
    let (marks, _) = grasp_run(&[
        carry(START, high, 20),
        carry(high, dropped, 10),
        rest(dropped, 0.3),
    ]);
    assert_eq!(marks.last().map(|m| m.1), Some(Mark::Drop));
    assert_eq!(value(&kind, &marks), 0.5);
    // Held still in the air outside the target: no drop.
    let (marks, _) = grasp_run(&[carry(START, high, 20), rest(high, 0.5)]);
    assert_eq!(marks.len(), 1, "{marks:?}");
    // Slid along the table into the target, never lifted: 0.
    let inside = (0.5, 0.15, 0.03);
    let (marks, total) = grasp_run(&[carry(START, inside, 40), rest(inside, 0.5)]);
    assert!(marks.is_empty());
    assert_eq!((total, value(&kind, &marks)), (0.0, 0.0));
}

#[test]
fn a_tracker_refuses_a_mapping_or_first_reading_that_does_not_fit() {
    let kind = CorrectnessKind::Notches { count: 6 };
    let body_first = ProgressTracker::new(&kind, &v_mapping(), body(0.0, 0.0, 0.0, 0.0));
    let message = body_first.unwrap_err().to_string();
    assert!(message.contains("a joint position"), "{message}");
    let short = PhysicsMapping {
        marks: V_MARKS[..5].to_vec(),
        ..v_mapping()
    };
    let error = ProgressTracker::new(&kind, &short, Reading::Joint(0.0)).unwrap_err();
    assert!(error.to_string().contains("physics.marks = ["), "{error}");
    let nan = ProgressTracker::new(&kind, &v_mapping(), Reading::Joint(f64::NAN));
    assert!(nan.is_err());
}

#[test]
fn readings_of_the_wrong_shape_are_skipped_and_counted() {
    let kind = CorrectnessKind::Distance { full_mm: 200.0 };
    let mut tracker =
        ProgressTracker::new(&kind, &PhysicsMapping::joint("s"), Reading::Joint(0.0)).unwrap();
    assert!(tracker.update(body(0.0, 0.0, 1.0, 0.0), 0.1).is_empty());
    assert!(
        tracker
            .update(Reading::Joint(f64::INFINITY), 0.2)
            .is_empty()
    );
    assert_eq!(tracker.skipped_readings(), 2);
    assert_eq!(
        tracker.update(Reading::Joint(0.0025), 0.3),
        vec![ProgressEvent::Progress(2.0)]
    );
}
