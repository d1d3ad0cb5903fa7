//! Aggregation golden cases: the published Orca_full radar values give the paper's overall
//! score; practice trials stay out of the means; a missing or example baseline is flagged in
//! every report format.

use crate::common;

use std::collections::BTreeMap;

use common::*;
use scoring::{
    BaselineTable, CorrectnessKind, DEFAULT_RULES_ORIGIN, ReportInputs, ScoreReport, ScoringRules,
    TaskCatalog, TrialLog, TrialScore, render_markdown, render_overall_csv, render_scores_csv,
    render_terminal, render_trials_csv, score_trial,
};

/// Orca_full's per-task scores read off the paper's radar figure.
const ORCA_FULL: [(&str, f64); 18] = [
    ("V1", 0.74),
    ("V2", 0.54),
    ("V3", 0.67),
    ("H1", 0.94),
    ("H2", 0.81),
    ("H3", 0.86),
    ("H4", 0.86),
    ("H5", 0.89),
    ("C1", 0.81),
    ("C2", 0.20),
    ("C3", 0.05),
    ("C4", 0.83),
    ("G1", 0.87),
    ("G2", 0.85),
    ("G3", 0.85),
    ("G4", 0.64),
    ("G5", 0.80),
    ("G6", 0.78),
];

const BASELINE_S: f64 = 10.0;

fn dof() -> BTreeMap<String, u32> {
    [
        ("orca_full", 16),
        ("orca_5", 11),
        ("orca_3", 7),
        ("orca_2", 5),
    ]
    .into_iter()
    .map(|(n, d)| (n.to_string(), d))
    .collect()
}

/// A stopped trial of `task` whose score is exactly `target` (with a 10 s baseline): the
/// largest correctness the task's kind can reach below target / 0.8, the rest from speed.
fn trial_scoring(task: &str, embodiment: &str, target: f64, file: &str) -> TrialLog {
    let catalog = TaskCatalog::builtin();
    let kind = catalog.get(task).unwrap().correctness;
    let (progress, correctness): (Vec<f64>, f64) = match kind {
        CorrectnessKind::Notches { count } | CorrectnessKind::Curves { count } => {
            let n = f64::from(count);
            let mut steps = (target / 0.8 * n).floor().min(n);
            if (0.8 * steps / n - target).abs() < 1e-12 {
                steps -= 1.0;
            }
            (vec![1.0; steps as usize], steps / n)
        }
        CorrectnessKind::Rotation { full_deg: full }
        | CorrectnessKind::Distance { full_mm: full } => {
            let c = target / 1.6;
            (vec![c * full], c)
        }
        CorrectnessKind::Grasp {} => {
            let c = [1.0, 0.5, 0.0]
                .into_iter()
                .find(|c| 0.8 * c < target)
                .unwrap();
            (if c > 0.0 { vec![c] } else { vec![] }, c)
        }
    };
    let speed = (target - 0.8 * correctness) / 0.2;
    assert!(speed > 0.0, "{task}: {speed}");
    let time_s = BASELINE_S / speed;
    let mut events = vec![(0.0, start())];
    for (i, v) in progress.iter().enumerate() {
        events.push((
            time_s * (i + 1) as f64 / (progress.len() + 2) as f64,
            progress_event(*v),
        ));
    }
    events.push((time_s, stop()));
    trial(file, task, embodiment, false, &events)
}

fn progress_event(v: f64) -> serde_json::Value {
    progress(v)
}

fn score_all(logs: &[TrialLog], table: Option<&BaselineTable>) -> Vec<TrialScore> {
    let catalog = TaskCatalog::builtin();
    logs.iter()
        .map(|l| score_trial(l, &catalog, table, &ScoringRules::default()).unwrap())
        .collect()
}

fn report(scores: Vec<TrialScore>, table: Option<&BaselineTable>) -> ScoreReport {
    let catalog = TaskCatalog::builtin();
    let dof = dof();
    let rules = ScoringRules::default();
    ScoreReport::build(ReportInputs {
        catalog: &catalog,
        baseline: table,
        rules: &rules,
        rules_origin: DEFAULT_RULES_ORIGIN,
        dof: &dof,
        scores,
        rejected: Vec::new(),
        skipped: Vec::new(),
    })
}

#[test]
fn the_published_orca_full_values_give_the_papers_overall() {
    let table = baseline(BASELINE_S, &[]);
    let logs: Vec<TrialLog> = ORCA_FULL
        .iter()
        .map(|(task, v)| trial_scoring(task, "orca_full", *v, &format!("{task}.mcap")))
        .collect();
    let report = report(score_all(&logs, Some(&table)), Some(&table));
    for (task, v) in ORCA_FULL {
        let r = report.task_result(task, "orca_full").unwrap();
        assert_close(r.score.unwrap().mean, v, 1e-6, task);
    }
    let e = &report.embodiments[0];
    assert_eq!(
        (e.embodiment.as_str(), e.dof, e.tasks_attempted),
        ("orca_full", Some(16), 18)
    );
    let overall = e.overall_attempted.unwrap();
    // The mean of the 18 values is 0.7217; the paper's figure: 0.72 ± 0.01.
    assert_close(overall, 0.7217, 1e-4, "overall");
    assert_close(overall, 0.72, 0.01, "overall (acceptance)");
    assert_close(e.overall_all.unwrap(), overall, 1e-12, "all 18 attempted");
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
}

#[test]
fn a_reduced_hand_gets_both_overalls() {
    // Orca_2-like: H2–H4 not attempted (as in the paper), the other 15 at the Orca_full values.
    let table = baseline(BASELINE_S, &[]);
    let attempted: Vec<(&str, f64)> = ORCA_FULL
        .iter()
        .copied()
        .filter(|(t, _)| !["H2", "H3", "H4"].contains(t))
        .collect();
    let logs: Vec<TrialLog> = attempted
        .iter()
        .map(|(task, v)| trial_scoring(task, "orca_2", *v, &format!("{task}.mcap")))
        .collect();
    let report = report(score_all(&logs, Some(&table)), Some(&table));
    let e = &report.embodiments[0];
    let sum: f64 = attempted.iter().map(|(_, v)| v).sum();
    assert_eq!(e.tasks_attempted, 15);
    assert_close(e.overall_attempted.unwrap(), sum / 15.0, 1e-6, "attempted");
    assert_close(e.overall_all.unwrap(), sum / 18.0, 1e-6, "missing = 0");
}

#[test]
fn per_task_mean_and_sample_std_over_trials() {
    // V1, three trials: 6/6 in 10 s (1.0), 3/6 in 20 s (0.5), 0/6 in 40 s (0.05).
    let table = baseline(BASELINE_S, &[]);
    let logs = [
        stopped_trial("a.mcap", "V1", "orca_5", &[1.0; 6], 10.0),
        stopped_trial("b.mcap", "V1", "orca_5", &[1.0; 3], 20.0),
        stopped_trial("c.mcap", "V1", "orca_5", &[], 40.0),
    ];
    let report = report(score_all(&logs, Some(&table)), Some(&table));
    let r = report.task_result("V1", "orca_5").unwrap();
    let values = [0.8 + 0.2, 0.4 + 0.1, 0.05];
    let mean = values.iter().sum::<f64>() / 3.0;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / 2.0;
    let score = r.score.unwrap();
    assert_eq!(score.n, 3);
    assert_close(score.mean, mean, 1e-12, "mean");
    assert_close(score.std.unwrap(), var.sqrt(), 1e-12, "sample std");
}

#[test]
fn practice_trials_are_scored_but_never_averaged() {
    let table = baseline(BASELINE_S, &[]);
    let mut practice = stopped_trial("p.mcap", "V2", "orca_3", &[], 100.0);
    practice.metadata.insert("practice".into(), "true".into());
    let logs = [
        practice,
        stopped_trial("r1.mcap", "V2", "orca_3", &[1.0; 6], 10.0),
        stopped_trial("r2.mcap", "V2", "orca_3", &[1.0; 6], 20.0),
    ];
    let report = report(score_all(&logs, Some(&table)), Some(&table));
    let p = &report.trials[0];
    assert!(p.practice && !p.counted && p.score.is_some());
    let r = report.task_result("V2", "orca_3").unwrap();
    assert_eq!((r.counted, r.practice), (2, 1));
    assert_close(
        r.score.unwrap().mean,
        (1.0 + 0.9) / 2.0,
        1e-12,
        "mean without practice",
    );
    assert_eq!(report.embodiments[0].trials, 2);
    // Only practice trials: listed, not attempted.
    let mut only = stopped_trial("p2.mcap", "V3", "orca_3", &[1.0], 5.0);
    only.metadata.insert("practice".into(), "true".into());
    let report = self::report(score_all(&[only], Some(&table)), Some(&table));
    assert_eq!(report.embodiments[0].tasks_attempted, 0);
    assert_eq!(report.embodiments[0].overall_attempted, None);
    assert!(render_terminal(&report).contains("practice (1)"));
}

#[test]
fn a_missing_baseline_shows_correctness_only_with_a_warning_in_every_format() {
    let table = baseline(BASELINE_S, &["C1"]);
    let logs = [
        stopped_trial("v1.mcap", "V1", "orca_full", &[1.0; 6], 10.0),
        stopped_trial("c1.mcap", "C1", "orca_full", &[270.0], 30.0),
    ];
    let report = report(score_all(&logs, Some(&table)), Some(&table));
    let c1 = report.task_result("C1", "orca_full").unwrap();
    assert!(!c1.has_baseline);
    assert_eq!(c1.score, None);
    assert_close(c1.correctness.unwrap().mean, 0.75, 1e-12, "correctness");
    let e = &report.embodiments[0];
    assert_eq!(
        e.overall_attempted, None,
        "no overall score mixing in correctness"
    );
    assert_eq!(e.tasks_without_baseline, ["C1"]);
    assert_close(
        e.correctness_attempted.unwrap(),
        (1.0 + 0.75) / 2.0,
        1e-12,
        "correctness",
    );
    assert_eq!(report.warnings.len(), 1, "{:?}", report.warnings);
    assert!(report.warnings[0].starts_with("NO BASELINE for C1 in test_baseline.toml"));

    let terminal = render_terminal(&report);
    assert!(
        terminal.contains("WARNING: NO BASELINE for C1"),
        "{terminal}"
    );
    assert!(terminal.contains("0.75±–    (1)*"), "{terminal}");
    let markdown = render_markdown(&report);
    assert!(
        markdown.contains("> **WARNING:** NO BASELINE for C1"),
        "{markdown}"
    );
    let csv = render_scores_csv(&report);
    let c1_row = csv.lines().find(|l| l.starts_with("C1,")).unwrap();
    assert!(
        c1_row.ends_with(",no baseline: correctness only"),
        "{c1_row}"
    );
    assert!(render_trials_csv(&report).contains("c1.mcap,C1"));
    assert!(render_overall_csv(&report).contains("(C1): overall score not computed"));
    let json: serde_json::Value = serde_json::from_str(&report.to_json()).unwrap();
    assert!(
        json["warnings"][0]
            .as_str()
            .unwrap()
            .contains("NO BASELINE for C1")
    );
    assert!(json["tasks"][1]["score"].is_null());

    // No table at all: every task correctness only, one warning saying so.
    let report = self::report(score_all(&logs, None), None);
    assert!(report.warnings[0].starts_with("NO BASELINE: no baseline table was given"));
    assert!(report.tasks.iter().all(|t| t.score.is_none()));
    assert!(render_terminal(&report).contains("baseline  none (correctness only)"));
}

#[test]
fn an_example_baseline_is_flagged_in_every_format() {
    let catalog = TaskCatalog::builtin();
    let table = BaselineTable::from_toml_str(
        "[baseline]\nexample = true\nsource = \"illustration\"\n\n[[task]]\nid = \"V1\"\nmean_s = 10.0\nn = 1\n",
        "example.toml",
        &catalog,
    )
    .unwrap();
    let logs = [stopped_trial("v1.mcap", "V1", "orca_full", &[1.0; 6], 10.0)];
    let report = report(score_all(&logs, Some(&table)), Some(&table));
    assert!(report.warnings[0].starts_with("EXAMPLE BASELINE: example.toml says example = true"));
    assert!(render_terminal(&report).contains("WARNING: EXAMPLE BASELINE"));
    assert!(render_terminal(&report).contains("baseline  EXAMPLE example.toml"));
    assert!(render_markdown(&report).contains("**EXAMPLE**"));
    assert!(render_scores_csv(&report).contains("EXAMPLE baseline: not real scores"));
    assert!(report.to_json().contains("EXAMPLE BASELINE"));
    assert!(table.to_toml().contains("# EXAMPLE"));
}

#[test]
fn the_terminal_report_fits_100_columns() {
    let table = baseline(BASELINE_S, &[]);
    let mut logs = Vec::new();
    for e in ["orca_full", "orca_5", "orca_3", "orca_2", "human"] {
        for (task, v) in ORCA_FULL {
            logs.push(trial_scoring(task, e, v, &format!("{e}/{task}.mcap")));
        }
    }
    let report = report(score_all(&logs, Some(&table)), Some(&table));
    let text = render_terminal(&report);
    for line in text.lines() {
        assert!(
            line.chars().count() <= 100,
            "{} columns: {line}",
            line.chars().count()
        );
    }
    // DoF ascending, unknown DoF last; five embodiments split over two per-task blocks.
    let order: Vec<&str> = report
        .embodiments
        .iter()
        .map(|e| e.embodiment.as_str())
        .collect();
    assert_eq!(order, ["orca_2", "orca_3", "orca_5", "orca_full", "human"]);
    assert_eq!(text.matches("Per task:").count(), 2);
    assert!(
        report
            .notes
            .iter()
            .any(|n| n.contains("human: DoF unknown"))
    );
}
