//! Properties over generated trials: correctness stays in [0, 1] for every kind, the score is
//! the paper's formula, a slower trial never scores higher, and the "missing = 0" overall
//! never exceeds the "attempted" one.

use crate::common;

use common::*;
use proptest::prelude::*;
use scoring::{ScoringRules, TaskCatalog, overall_means, score_trial};

fn task_and_values() -> impl Strategy<Value = (String, Vec<f64>)> {
    prop_oneof![
        (
            prop::sample::select(vec!["V1", "V2", "V3", "H1", "H2", "H3"]),
            prop::collection::vec(0..3i32, 0..12)
        )
            .prop_map(|(t, v)| (t.to_string(), v.into_iter().map(f64::from).collect())),
        (
            prop::sample::select(vec!["C1", "C2", "C3", "C4", "H4", "H5"]),
            prop::collection::vec(-400.0..400.0f64, 0..8)
        )
            .prop_map(|(t, v)| (t.to_string(), v)),
        (
            prop::sample::select(vec!["G1", "G2", "G3", "G4", "G5", "G6"]),
            prop::collection::vec(prop::sample::select(vec![0.0, 0.5, 1.0]), 0..4)
        )
            .prop_map(|(t, v)| (t.to_string(), v)),
    ]
}

proptest! {
    #[test]
    fn scores_follow_the_formula_and_slower_is_never_better(
        (task, values) in task_and_values(),
        stop_s in 20.0..200.0f64,
        extra_s in 0.001..100.0f64,
        baseline_s in 1.0..60.0f64,
    ) {
        let catalog = TaskCatalog::builtin();
        let table = baseline(baseline_s, &[]);
        let rules = ScoringRules::default();
        let fast = stopped_trial("f.mcap", &task, "orca_full", &values, stop_s);
        let slow = stopped_trial("s.mcap", &task, "orca_full", &values, stop_s + extra_s);
        let f = score_trial(&fast, &catalog, Some(&table), &rules).unwrap();
        let s = score_trial(&slow, &catalog, Some(&table), &rules).unwrap();
        prop_assert!((0.0..=1.0).contains(&f.correctness));
        prop_assert_eq!(f.correctness, s.correctness);
        let expected = 0.8 * f.correctness + 0.2 * baseline_s / f.time_s;
        prop_assert!((f.score.unwrap() - expected).abs() < 1e-9);
        prop_assert!(s.score.unwrap() <= f.score.unwrap());
        prop_assert!(s.score.unwrap() >= 0.0);
    }

    #[test]
    fn missing_tasks_only_lower_the_overall(
        values in prop::collection::vec(0.0..3.0f64, 1..18),
    ) {
        let (attempted, all) = overall_means(&values, 18).unwrap();
        prop_assert!(all <= attempted + 1e-12);
        if values.len() == 18 {
            prop_assert!((all - attempted).abs() < 1e-12);
        }
    }
}
