//! `compare`'s tests: grouping, the missing group, the reference, the statistics and the
//! differences against values worked out by hand from the trials below.

use std::collections::BTreeMap;

use super::*;
use crate::catalog::TaskCatalog;
use crate::report::ReportInputs;
use crate::rules::ScoringRules;
use crate::trial_score::Outcome;
use crate::welch::DifferenceInterval;

/// A scored trial of `task` on `embodiment` with `keypoint_source = source` (none: `None`).
fn trial(
    task: &str,
    embodiment: &str,
    source: Option<&str>,
    time_s: f64,
    correctness: f64,
    score: Option<f64>,
) -> TrialScore {
    let mut metadata = BTreeMap::from([
        ("task".to_string(), task.to_string()),
        ("embodiment".to_string(), embodiment.to_string()),
    ]);
    if let Some(s) = source {
        metadata.insert("keypoint_source".to_string(), s.to_string());
    }
    TrialScore {
        file: format!("{task}-{embodiment}-{time_s}.mcap"),
        task: task.into(),
        embodiment: embodiment.into(),
        user: None,
        operator: None,
        trial_index: None,
        metadata,
        practice: false,
        outcome: Outcome::Completed,
        time_s,
        progress: 0.0,
        correctness,
        speed: score.map(|_| 1.0),
        score,
        counted: true,
        notes: Vec::new(),
    }
}

pub(crate) fn report(scores: Vec<TrialScore>) -> ScoreReport {
    let catalog = TaskCatalog::builtin();
    ScoreReport::build(ReportInputs {
        catalog: &catalog,
        baseline: None,
        rules: &ScoringRules::default(),
        rules_origin: "default rules",
        dof: &BTreeMap::new(),
        scores,
        rejected: Vec::new(),
        skipped: Vec::new(),
    })
}

/// V1 on orca_full: rokoko in 10, 12, 14 s; avp in 13, 15, 17 s; one trial without the
/// entry; a practice trial (left out) with a third value. H2 (scored without score) on
/// orca_5: one rokoko, two avp.
pub(crate) fn trials() -> Vec<TrialScore> {
    let mut practice = trial("V1", "orca_full", Some("simulated"), 5.0, 1.0, Some(1.0));
    practice.practice = true;
    practice.counted = false;
    vec![
        trial("V1", "orca_full", Some("rokoko"), 10.0, 1.0, Some(0.9)),
        trial("V1", "orca_full", Some("rokoko"), 12.0, 0.5, Some(0.6)),
        trial("V1", "orca_full", Some(" rokoko "), 14.0, 1.0, Some(0.9)),
        trial("V1", "orca_full", Some("avp"), 13.0, 0.5, Some(0.5)),
        trial("V1", "orca_full", Some("avp"), 15.0, 0.5, Some(0.5)),
        trial("V1", "orca_full", Some("avp"), 17.0, 1.0, Some(0.8)),
        trial("V1", "orca_full", None, 20.0, 0.0, Some(0.0)),
        trial("V1", "orca_full", Some(""), 21.0, 0.0, Some(0.0)),
        practice,
        trial("H2", "orca_5", Some("rokoko"), 8.0, 1.0, None),
        trial("H2", "orca_5", Some("avp"), 9.0, 2.0 / 3.0, None),
        trial("H2", "orca_5", Some("avp"), 11.0, 1.0 / 3.0, None),
    ]
}

fn close(a: f64, b: f64, what: &str) {
    assert!((a - b).abs() < 1e-9, "{what}: {a} != {b}");
}

#[test]
fn groups_are_sorted_with_the_missing_group_last_and_practice_left_out() {
    let c = compare_by(&report(trials()), "keypoint_source", None).unwrap();
    let names: Vec<(&str, usize, bool)> = (c.groups.iter())
        .map(|g| (g.name.as_str(), g.trials, g.reference))
        .collect();
    assert_eq!(
        names,
        [
            ("avp", 5, true),
            ("rokoko", 4, false),
            (MISSING_GROUP, 2, false)
        ]
    );
    assert_eq!((c.reference.as_str(), c.missing_trials), ("avp", 2));
    assert!(
        c.notes
            .iter()
            .any(|n| n.contains("2 recorded trial(s) have no"))
    );
    assert!(
        c.notes
            .iter()
            .any(|n| n.starts_with("1 practice and 0 excluded"))
    );
    let order: Vec<(&str, &str)> = (c.rows.iter())
        .map(|r| (r.task.as_str(), r.embodiment.as_str()))
        .collect();
    // The report's order: embodiments by DoF (unknown here), then name.
    assert_eq!(order, [("H2", "orca_5"), ("V1", "orca_full")]);
}

#[test]
fn statistics_and_welch_differences_per_task_and_embodiment() {
    let c = compare_by(&report(trials()), "keypoint_source", Some("rokoko")).unwrap();
    assert_eq!(c.reference, "rokoko");
    let v1 = c.row("V1", "orca_full").unwrap();
    let rokoko = v1.group("rokoko").unwrap();
    let avp = v1.group("avp").unwrap();
    assert_eq!(
        (rokoko.n, avp.n, v1.group(MISSING_GROUP).unwrap().n),
        (3, 3, 2)
    );
    // Times: rokoko 12 ± 2, avp 15 ± 2 (sample std of 10, 12, 14 and 13, 15, 17).
    close(rokoko.time_s.unwrap().mean, 12.0, "rokoko time");
    close(rokoko.time_s.unwrap().std.unwrap(), 2.0, "rokoko std");
    close(avp.time_s.unwrap().mean, 15.0, "avp time");
    assert!(rokoko.versus_reference.is_none(), "the reference has none");
    // avp − rokoko = 3 s; SE² = 4/3 + 4/3, ν = (8/3)² / ((4/3)²/2 · 2) = 4, and
    // t(0.975, 4) = 2.7764451051977987 (SciPy 1.17.1; tables: 2.776).
    let time = avp.versus_reference.unwrap().time_s;
    close(time.estimate, 3.0, "time difference");
    let DifferenceInterval::Defined { low, high, df, .. } = time.ci else {
        panic!("{time:?}");
    };
    close(df, 4.0, "df");
    let half = 2.776_445_105_197_798_7 * (8.0_f64 / 3.0).sqrt();
    close(low, 3.0 - half, "low");
    close(high, 3.0 + half, "high");
    // Correctness: rokoko 1, .5, 1 (mean 5/6); avp .5, .5, 1 (mean 2/3).
    let correctness = avp.versus_reference.unwrap().correctness;
    close(
        correctness.estimate,
        2.0 / 3.0 - 5.0 / 6.0,
        "correctness difference",
    );
    // Scores: rokoko .9, .6, .9 (mean .8); avp .5, .5, .8 (mean .6).
    let score = avp.versus_reference.unwrap().score.unwrap();
    close(score.estimate, 0.6 - 0.8, "score difference");
}

#[test]
fn without_a_baseline_there_is_no_score_and_one_trial_has_no_interval() {
    let c = compare_by(&report(trials()), "keypoint_source", Some("rokoko")).unwrap();
    let h2 = c.row("H2", "orca_5").unwrap();
    assert!(!h2.has_baseline);
    assert!(h2.groups.iter().all(|g| g.score.is_none()));
    let avp = h2.group("avp").unwrap();
    let versus = avp.versus_reference.unwrap();
    assert!(versus.score.is_none());
    close(versus.time_s.estimate, 10.0 - 8.0, "H2 time difference");
    assert_eq!(
        versus.time_s.ci,
        DifferenceInterval::TooFewTrials {
            n: 2,
            reference_n: 1
        }
    );
    // The missing group has no H2 trial: n = 0, nothing to compare.
    let missing = h2.group(MISSING_GROUP).unwrap();
    assert_eq!((missing.n, missing.correctness), (0, None));
    assert!(missing.versus_reference.is_none());
    assert!(
        c.notes
            .iter()
            .any(|n| n.contains("no baseline for H2 (orca_5)"))
    );
}

#[test]
fn group_counts_add_up_to_the_reports_counted_trials() {
    let report = report(trials());
    let c = compare_by(&report, "keypoint_source", None).unwrap();
    for row in &c.rows {
        let result = report.task_result(&row.task, &row.embodiment).unwrap();
        let n: usize = row.groups.iter().map(|g| g.n).sum();
        assert_eq!(n, result.counted, "{} {}", row.task, row.embodiment);
    }
    let total: usize = c.groups.iter().map(|g| g.trials).sum();
    assert_eq!(total, report.counted_trials());
}

#[test]
fn one_group_a_missing_field_or_an_unknown_reference_is_an_error() {
    let same: Vec<TrialScore> = (trials().into_iter())
        .filter(|t| group_of(t, "keypoint_source") == "rokoko")
        .collect();
    let err = compare_by(&report(same), "keypoint_source", None).unwrap_err();
    assert!(
        err.to_string()
            .contains("all 4 recorded trials have the value \"rokoko\""),
        "{err}"
    );
    let err = compare_by(&report(trials()), "station_version", None).unwrap_err();
    assert_eq!(
        err.to_string(),
        "comparison by \"station_version\": none of the 11 recorded trials has this metadata \
         entry: nothing to compare"
    );
    let err = compare_by(&report(trials()), "keypoint_source", Some("simulated")).unwrap_err();
    assert!(
        err.to_string().contains(
            "reference group \"simulated\" has no recorded trial (groups: avp, rokoko, (missing))"
        ),
        "{err}"
    );
    let err = compare_by(&report(Vec::new()), "keypoint_source", None).unwrap_err();
    assert!(err.to_string().contains("no recorded trial to compare"));
}

#[test]
fn any_metadata_entry_groups_and_the_missing_group_can_be_the_reference() {
    let c = compare_by(&report(trials()), "keypoint_source", Some(MISSING_GROUP)).unwrap();
    assert_eq!(c.reference, MISSING_GROUP);
    let rokoko = c.row("V1", "orca_full").unwrap().group("rokoko").unwrap();
    // rokoko − missing: 12 − 20.5 s.
    close(
        rokoko.versus_reference.unwrap().time_s.estimate,
        12.0 - 20.5,
        "versus missing",
    );
    // Grouping by the task itself: one group per row, differences only where both exist.
    let by_task = compare_by(&report(trials()), "task", None).unwrap();
    assert_eq!(by_task.reference, "H2");
    let v1 = by_task.row("V1", "orca_full").unwrap();
    assert!(v1.groups.iter().all(|g| g.versus_reference.is_none()));
}
