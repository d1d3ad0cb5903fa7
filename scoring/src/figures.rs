//! The report's figures, in the style of the paper: a radar of the 12 manipulation tasks and
//! one of the 6 grasping tasks (one polygon per embodiment), and overall score against DoF.
//!
//! A radar shows mean scores. Where the tasks of a radar have no baseline at all it shows
//! mean correctness instead, and says so in its title; where only some lack one, those axes
//! are drawn as not available and the title names them.

use crate::error::ScoringError;
use crate::plot::{self, DofChart, DofPoint, Figure, RadarChart, RadarSeries};
use crate::report::ScoreReport;

/// Most series a radar draws (the palette's distinct colours).
const MAX_SERIES: usize = 8;

/// A figure with the file stem it is saved under (`radar_manipulation` → `.svg`, `.png`).
#[derive(Debug, Clone, PartialEq)]
pub struct NamedFigure {
    /// File stem.
    pub stem: String,
    /// The rendered figure.
    pub figure: Figure,
}

/// The figures of `report`, and remarks about figures not drawn or incomplete. A figure
/// that fails to draw is an error naming it; the others are still returned.
pub fn render_figures(report: &ScoreReport) -> (Vec<NamedFigure>, Vec<String>, Vec<ScoringError>) {
    let mut figures = Vec::new();
    let mut notes = Vec::new();
    let mut errors = Vec::new();
    let mut keep = |stem: &str, result: Result<Figure, plot::PlotError>| match result {
        Ok(figure) => figures.push(NamedFigure {
            stem: stem.to_string(),
            figure,
        }),
        Err(e) => errors.push(ScoringError::Figure {
            figure: stem.to_string(),
            reason: e.to_string(),
        }),
    };
    for (stem, grasp, title) in [
        ("radar_manipulation", false, "Manipulation tasks"),
        ("radar_grasp", true, "Grasping tasks"),
    ] {
        match radar_chart(report, grasp, title, &mut notes) {
            Some(chart) => keep(stem, plot::radar(&chart)),
            None => notes.push(format!("{stem}: no trials of these tasks, not drawn")),
        }
    }
    let total = report.catalog_tasks.len();
    for (stem, all, y_label) in [
        (
            "overall_vs_dof",
            false,
            "Overall score (mean over attempted tasks)".to_string(),
        ),
        (
            "overall_vs_dof_all_tasks",
            true,
            format!("Overall score (mean over all {total} tasks, missing = 0)"),
        ),
    ] {
        let points: Vec<DofPoint> = report
            .embodiments
            .iter()
            .filter_map(|e| {
                let overall = if all {
                    e.overall_all
                } else {
                    e.overall_attempted
                };
                Some(DofPoint {
                    label: e.embodiment.clone(),
                    dof: e.dof?,
                    overall: overall?,
                    std: if all { None } else { e.overall_spread },
                })
            })
            .collect();
        if points.is_empty() {
            notes.push(format!(
                "{stem}: no embodiment with a known DoF and an overall score, not drawn"
            ));
            continue;
        }
        let chart = DofChart {
            title: format!(
                "Overall score vs DoF{}",
                if all { "" } else { " (± spread across tasks)" }
            ),
            y_label,
            points,
        };
        keep(stem, plot::dof_scatter(&chart));
    }
    (figures, notes, errors)
}

fn radar_chart(
    report: &ScoreReport,
    grasp: bool,
    title: &str,
    notes: &mut Vec<String>,
) -> Option<RadarChart> {
    let tasks: Vec<&str> = report
        .catalog_tasks
        .iter()
        .filter(|t| t.grasp == grasp)
        .map(|t| t.id.as_str())
        .collect();
    let results: Vec<_> = report
        .tasks
        .iter()
        .filter(|r| tasks.contains(&r.task.as_str()) && r.counted > 0)
        .collect();
    if results.is_empty() {
        return None;
    }
    let without: Vec<&str> = tasks
        .iter()
        .copied()
        .filter(|t| results.iter().any(|r| r.task == *t && !r.has_baseline))
        .collect();
    let correctness_only = results.iter().all(|r| !r.has_baseline);
    let mut embodiments: Vec<&str> = report
        .embodiments
        .iter()
        .map(|e| e.embodiment.as_str())
        .filter(|e| results.iter().any(|r| r.embodiment == *e))
        .collect();
    if embodiments.len() > MAX_SERIES {
        notes.push(format!(
            "{title}: {} embodiments, the radar draws the first {MAX_SERIES} ({})",
            embodiments.len(),
            embodiments[..MAX_SERIES].join(", ")
        ));
        embodiments.truncate(MAX_SERIES);
    }
    let series = embodiments
        .iter()
        .map(|e| RadarSeries {
            label: (*e).to_string(),
            values: tasks
                .iter()
                .map(|t| {
                    let r = report.task_result(t, e)?;
                    if correctness_only {
                        r.correctness.map(|c| c.mean)
                    } else {
                        r.score.map(|s| s.mean)
                    }
                })
                .collect(),
        })
        .collect();
    let title = if correctness_only {
        format!("{title}: mean correctness (no baseline: no scores)")
    } else if without.is_empty() {
        format!("{title}: mean score")
    } else {
        format!(
            "{title}: mean score (no baseline for {}: not drawn)",
            without.join(", ")
        )
    };
    let example = report.baseline.as_ref().is_some_and(|b| b.example);
    Some(RadarChart {
        title: if example && !correctness_only {
            format!("{title}, EXAMPLE baseline")
        } else {
            title
        },
        axes: tasks.iter().map(|t| (*t).to_string()).collect(),
        series,
    })
}
