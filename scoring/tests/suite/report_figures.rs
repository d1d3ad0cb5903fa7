//! The report's figures from scored trials: the two radars and the two overall-vs-DoF charts
//! are drawn, decode, are not blank; a report without baselines draws correctness radars.

use crate::common;

use std::collections::BTreeMap;

use common::*;
use scoring::{
    DEFAULT_RULES_ORIGIN, ReportInputs, ScoreReport, ScoringRules, TaskCatalog, render_figures,
    score_trial,
};

fn report(with_baseline: bool) -> ScoreReport {
    let catalog = TaskCatalog::builtin();
    let table = baseline(10.0, &[]);
    let table = with_baseline.then_some(&table);
    let rules = ScoringRules::default();
    let dof: BTreeMap<String, u32> =
        [("orca_full".to_string(), 16), ("orca_2".to_string(), 5)].into();
    let mut scores = Vec::new();
    for (e, stop_s) in [("orca_full", 12.0), ("orca_2", 25.0), ("human", 10.0)] {
        for t in &catalog.tasks {
            if e == "orca_2" && ["H2", "H3", "H4"].contains(&t.id.as_str()) {
                continue;
            }
            let progress: &[f64] = match t.id.as_bytes()[0] {
                b'C' => &[200.0],
                b'G' => &[1.0],
                b'H' if ["H4", "H5"].contains(&t.id.as_str()) => &[150.0],
                _ => &[1.0, 1.0],
            };
            let log = stopped_trial(&format!("{e}/{}.mcap", t.id), &t.id, e, progress, stop_s);
            scores.push(score_trial(&log, &catalog, table, &rules).unwrap());
        }
    }
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
fn the_four_figures_render_and_are_not_blank() {
    let (figures, notes, errors) = render_figures(&report(true));
    assert!(errors.is_empty(), "{errors:?}");
    assert!(notes.is_empty(), "{notes:?}");
    let stems: Vec<&str> = figures.iter().map(|f| f.stem.as_str()).collect();
    assert_eq!(
        stems,
        [
            "radar_manipulation",
            "radar_grasp",
            "overall_vs_dof",
            "overall_vs_dof_all_tasks"
        ]
    );
    for f in &figures {
        let pixmap = tiny_skia::Pixmap::decode_png(&f.figure.png).unwrap();
        assert_eq!(
            (pixmap.width(), pixmap.height()),
            (f.figure.width_px, f.figure.height_px)
        );
        assert!(
            pixmap.width() >= 400 && pixmap.height() >= 300,
            "{}",
            f.stem
        );
        let first = pixmap.pixels()[0];
        let differing = pixmap.pixels().iter().filter(|p| **p != first).count();
        assert!(
            differing > pixmap.pixels().len() / 100,
            "{} is nearly blank",
            f.stem
        );
        let svg = roxmltree::Document::parse(&f.figure.svg).unwrap();
        assert_eq!(svg.root_element().tag_name().name(), "svg");
    }
    // The radars carry the embodiments; the DoF charts only those with a known DoF.
    let manipulation = &figures[0].figure.svg;
    assert!(manipulation.contains("orca_full") && manipulation.contains("human"));
    let dof = &figures[2].figure.svg;
    assert!(dof.contains("orca_2") && !dof.contains("human"));
}

#[test]
fn without_a_baseline_the_radars_show_correctness_and_say_so() {
    let (figures, notes, errors) = render_figures(&report(false));
    assert!(errors.is_empty(), "{errors:?}");
    let stems: Vec<&str> = figures.iter().map(|f| f.stem.as_str()).collect();
    assert_eq!(stems, ["radar_manipulation", "radar_grasp"]);
    assert!(
        figures[0]
            .figure
            .svg
            .contains("mean correctness (no baseline: no scores)")
    );
    assert_eq!(notes.len(), 2, "{notes:?}");
    assert!(
        notes[0].starts_with("overall_vs_dof: no embodiment with a known DoF and an overall score")
    );
}
