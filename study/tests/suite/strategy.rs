//! The strategy analysis end to end on synthetic glove recordings: distinct task motions
//! cluster by task whatever the participants' hand sizes and the trials' placement; one
//! motion under three task labels does not.

use crate::common;

use common::{Motion, Participant, Rng, study_trials, trial};
use nalgebra::{Point3, Rotation3, Unit, Vector3};
use study::{
    ClusterStrength, SkipReason, StrategySettings, StudyError, analyse, report_markdown,
    strategy_figure, trial_segments,
};

const TASKS: [(&str, Motion); 3] = [
    ("power grasp", Motion::PowerGrasp),
    ("pinch", Motion::Pinch),
    ("spread", Motion::Spread),
];

#[test]
fn distinct_task_motions_cluster_by_task() {
    let trials = study_trials(&TASKS, 7);
    let a = analyse(&trials, &StrategySettings::default()).unwrap();
    println!(
        "separated tasks: silhouette {:.3}, {:?}",
        a.silhouette, a.per_task
    );
    println!("variance explained {:?}", a.variance_explained);
    assert_eq!(a.trials_used, 27);
    assert_eq!(
        a.segments.len(),
        27 * 4,
        "6 s at 60 Hz is four 1.5 s segments"
    );
    assert_eq!((a.components_kept, a.participants), (3, 3));
    assert!(a.skipped.is_empty() && a.collapsed_frames == 0 && a.dropped_windows == 0);
    assert!(a.silhouette > 0.5, "silhouette {}", a.silhouette);
    assert!(a.verdict().clusters(), "{:?}", a.verdict());
    for task in &a.per_task {
        assert_eq!((task.segments, task.trials, task.participants), (36, 9, 3));
        assert!(task.mean_silhouette > 0.3, "{task:?}");
    }
    let v = &a.variance_explained;
    assert!(
        v.windows(2).all(|w| w[0] >= w[1]) && v.iter().sum::<f64>() <= 1.0,
        "{v:?}"
    );
    assert!(
        a.sentence()
            .starts_with("Segments cluster by task: mean silhouette")
    );
}

#[test]
fn one_motion_under_three_labels_does_not_cluster() {
    let same = TASKS.map(|(task, _)| (task, Motion::PowerGrasp));
    let a = analyse(&study_trials(&same, 7), &StrategySettings::default()).unwrap();
    println!(
        "same motion: silhouette {:.3}, {:?}",
        a.silhouette, a.per_task
    );
    assert!(a.silhouette < 0.25, "silhouette {}", a.silhouette);
    assert_eq!(a.verdict(), ClusterStrength::NoSubstantialStructure);
    assert!(
        a.sentence().starts_with("Segments do not cluster by task"),
        "{}",
        a.sentence()
    );
}

#[test]
fn segment_features_ignore_the_hands_place_orientation_and_size() {
    let mut rng = Rng::new(3);
    let who = Participant::new("P1", 1.0, &mut rng);
    let original = trial(
        &who,
        Motion::Pinch,
        "pinch",
        "t1",
        (4.0, 100.0, 0.001),
        &mut rng,
    );
    let settings = StrategySettings::default();
    let reference = trial_segments(&original, &settings).unwrap();
    assert_eq!(reference.segments.len(), 2);
    let rotation =
        Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::new(0.3, -1.0, 0.4)), 2.2);
    let offset = Vector3::new(-1.2, 0.7, 3.0);
    for scale in [1.0, 1.3, 0.8] {
        let mut moved = original.clone();
        for frame in &mut moved.frames {
            for p in &mut frame.points {
                *p = Point3::from((rotation * p.coords) * scale + offset);
            }
        }
        let got = trial_segments(&moved, &settings).unwrap();
        assert!((got.hand_length_m / reference.hand_length_m - scale).abs() < 1e-12);
        for (a, b) in got.segments.iter().zip(&reference.segments) {
            assert_eq!(a.frames, b.frames);
            let worst = (a.features.iter().zip(&b.features))
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-9, "scale {scale}: features differ by {worst}");
        }
    }
}

#[test]
fn one_task_is_an_error_that_names_it() {
    let trials = study_trials(&TASKS[..1], 1);
    let err = analyse(&trials, &StrategySettings::default()).unwrap_err();
    assert!(
        matches!(&err, StudyError::TooFewTasks { tasks, segments: 36 } if tasks == &["power grasp"])
    );
    assert_eq!(
        err.to_string(),
        "strategy analysis needs segments from at least 2 tasks; found 1 (power grasp) over 36 segments"
    );
}

#[test]
fn trials_shorter_than_a_segment_leave_nothing() {
    let mut rng = Rng::new(5);
    let who = Participant::new("P1", 1.0, &mut rng);
    let trials: Vec<_> = TASKS
        .iter()
        .map(|&(task, motion)| trial(&who, motion, task, "short", (1.2, 100.0, 0.001), &mut rng))
        .collect();
    let err = analyse(&trials, &StrategySettings::default()).unwrap_err();
    let StudyError::NoSegments { trials: 3, skipped } = &err else {
        panic!("{err:?}");
    };
    assert!(
        skipped
            .iter()
            .all(|s| matches!(s.reason, SkipReason::TooShort { .. }))
    );
    assert!(
        err.to_string().contains(
            "participant 'P1', task 'pinch', trial 'short' skipped: it lasts 1.200 s, shorter than one 1.5 s segment"
        ),
        "{err}"
    );
}

#[test]
fn bad_trials_are_skipped_and_reported_and_bad_frames_counted() {
    let mut trials = study_trials(&TASKS[..2], 11);
    // A frame short of a point, a non-finite point, and collapsed palms in a usable trial.
    trials[0].frames[10].points.pop();
    trials[4].frames[3].points[9].x = f64::NAN;
    for frame in &mut trials[7].frames[..20] {
        let wrist = frame.points[1];
        frame.points.iter_mut().for_each(|p| *p = wrist);
    }
    let a = analyse(&trials, &StrategySettings::default()).unwrap();
    assert_eq!(a.skipped.len(), 2);
    assert_eq!(a.skipped[0].trial, trials[0].trial);
    assert_eq!(
        a.skipped[1].reason.to_string(),
        "frame 3, point 9 (index_tip) is not finite"
    );
    assert_eq!(a.collapsed_frames, 20);
    assert_eq!(a.trials_used, trials.len() - 2);
    let report = report_markdown(&a);
    assert!(
        report.contains("frame 10 has 21 points but layout lab22 has 22"),
        "{report}"
    );
    assert!(
        report.contains("| PC1 |") && report.contains("| pinch |"),
        "{report}"
    );
    assert!(report.contains(&a.sentence()), "{report}");
    let json = serde_json::to_value(&a).unwrap();
    assert_eq!(json["skipped"][1]["reason"]["kind"], "non_finite_point");
    assert_eq!(json["segments"].as_array().unwrap().len(), a.segments.len());
}

#[test]
fn figures_show_every_segment_and_refuse_missing_components() {
    let a = analyse(&study_trials(&TASKS, 7), &StrategySettings::default()).unwrap();
    for (x, y) in [(1, 2), (1, 3)] {
        let figure = strategy_figure(&a, x, y).unwrap();
        let points = figure.svg.matches(r#"<circle class="point""#).count();
        assert_eq!(points, a.segments.len(), "PC{x}–PC{y}");
        assert!(figure.svg.contains(&format!("PC{y} (")), "PC{x}–PC{y}");
        assert!(!figure.png.is_empty());
    }
    assert_eq!(
        strategy_figure(&a, 1, 4).unwrap_err().to_string(),
        "the figure asks for PC4 but the analysis kept 3 components (PC1 to PC3); pick two \
         different components in that range"
    );
    assert_eq!(
        strategy_figure(&a, 2, 2).unwrap_err(),
        StudyError::SameComponent { component: 2 }
    );
}
