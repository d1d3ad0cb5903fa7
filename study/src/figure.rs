//! The strategy figures: segments' scores on two principal components, coloured by task.

use scoring::plot::{Figure, PcaChart, PcaSeries, pca_scatter};

use crate::analysis::StrategyAnalysis;
use crate::error::StudyError;

/// The scatter of every segment's scores on components `x_pc` and `y_pc` (1-based: PC1 is
/// 1), one series per task in the order of [`StrategyAnalysis::per_task`].
pub fn strategy_figure(
    analysis: &StrategyAnalysis,
    x_pc: usize,
    y_pc: usize,
) -> Result<Figure, StudyError> {
    Ok(pca_scatter(&strategy_chart(analysis, x_pc, y_pc)?)?)
}

/// The chart behind [`strategy_figure`].
pub fn strategy_chart(
    analysis: &StrategyAnalysis,
    x_pc: usize,
    y_pc: usize,
) -> Result<PcaChart, StudyError> {
    let kept = analysis.components_kept;
    for requested in [x_pc, y_pc] {
        if requested == 0 || requested > kept {
            return Err(StudyError::BadComponent { requested, kept });
        }
    }
    if x_pc == y_pc {
        return Err(StudyError::SameComponent { component: x_pc });
    }
    let (xi, yi) = (x_pc - 1, y_pc - 1);
    let series = (analysis.per_task.iter())
        .map(|task| PcaSeries {
            label: task.task.clone(),
            points: (analysis.segments.iter())
                .filter(|s| s.task == task.task)
                .map(|s| (s.scores[xi], s.scores[yi]))
                .collect(),
        })
        .collect();
    let percent = |i: usize| 100.0 * analysis.variance_explained[i];
    let axis = |i: usize| format!("PC{} ({:.0} % of variance)", i + 1, percent(i));
    let note = format!(
        "variance explained {:.0} % / {:.0} %; silhouette {:.2} ({}); {} segments of {} s, {} \
         participant{}",
        percent(xi),
        percent(yi),
        analysis.silhouette,
        analysis.verdict().describe(),
        analysis.segments.len(),
        analysis.settings.segment_s,
        analysis.participants,
        if analysis.participants == 1 { "" } else { "s" },
    );
    Ok(PcaChart {
        title: format!("Hand-motion segments by task: PC{x_pc} vs PC{y_pc}"),
        x_label: axis(xi),
        y_label: axis(yi),
        series,
        note: Some(note),
    })
}
