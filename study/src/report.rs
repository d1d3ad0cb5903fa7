//! The analysis in words: the report's sentence and its Markdown section.

use std::fmt::Write as _;

use crate::analysis::StrategyAnalysis;
use crate::cluster_strength::ClusterStrength;

impl StrategyAnalysis {
    /// One plain sentence for the report: whether the segments cluster by task, the mean
    /// silhouette, and its band.
    pub fn sentence(&self) -> String {
        let verdict = self.verdict();
        let claim = match verdict {
            ClusterStrength::Strong | ClusterStrength::Reasonable => "Segments cluster by task",
            ClusterStrength::Weak => "Segments cluster only weakly by task",
            ClusterStrength::NoSubstantialStructure => "Segments do not cluster by task",
        };
        format!(
            "{claim}: mean silhouette {:.2} over {} segments of {} tasks from {} participant{} \
             ({} by Kaufman & Rousseeuw's bands, {}).",
            self.silhouette,
            self.segments.len(),
            self.per_task.len(),
            self.participants,
            if self.participants == 1 { "" } else { "s" },
            verdict.describe(),
            verdict.range(),
        )
    }
}

/// The analysis as a Markdown section: the sentence, what was analysed, the variance
/// explained, the separation per task and the skipped trials.
pub fn report_markdown(analysis: &StrategyAnalysis) -> String {
    let a = analysis;
    let mut out = String::from("## Strategy per task (hand-motion PCA)\n\n");
    let _ = writeln!(out, "{}\n", a.sentence());
    let _ = writeln!(
        out,
        "{} segments of {} s from {} trials, keypoint layout {}; {} features (mean and standard \
         deviation of every keypoint coordinate in the palm frame, in hand lengths), {} of them \
         constant; {} principal components kept.\n",
        a.segments.len(),
        a.settings.segment_s,
        a.trials_used,
        a.layout,
        a.feature_names.len(),
        a.constant_features,
        a.components_kept,
    );
    out.push_str("| component | variance explained | cumulative |\n|---|---:|---:|\n");
    let mut cumulative = 0.0;
    for (i, v) in a.variance_explained.iter().enumerate() {
        cumulative += v;
        let _ = writeln!(
            out,
            "| PC{} | {:.1} % | {:.1} % |",
            i + 1,
            100.0 * v,
            100.0 * cumulative
        );
    }
    out.push_str(
        "\n| task | segments | trials | participants | mean silhouette |\n\
         |---|---:|---:|---:|---:|\n",
    );
    for t in &a.per_task {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {:.2} |",
            cell(&t.task),
            t.segments,
            t.trials,
            t.participants,
            t.mean_silhouette
        );
    }
    out.push('\n');
    write_left_out(&mut out, a);
    out
}

fn write_left_out(out: &mut String, a: &StrategyAnalysis) {
    if a.collapsed_frames > 0 || a.dropped_windows > 0 {
        let _ = writeln!(
            out,
            "Left out of analysed trials: {} frames with a collapsed palm frame, {} windows with \
             fewer than {} usable frames.\n",
            a.collapsed_frames, a.dropped_windows, a.settings.min_frames_per_segment
        );
    }
    if a.skipped.is_empty() {
        out.push_str("No trials were skipped.\n");
        return;
    }
    let _ = writeln!(out, "Skipped trials ({}):\n", a.skipped.len());
    out.push_str("| participant | task | trial | reason |\n|---|---|---|---|\n");
    for s in &a.skipped {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} |",
            cell(&s.participant),
            cell(&s.task),
            cell(&s.trial),
            cell(&s.reason.to_string())
        );
    }
}

/// `text` safe inside a Markdown table cell.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace(['\n', '\r'], " ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_cannot_break_the_table() {
        assert_eq!(cell("a|b\nc"), "a\\|b c");
    }
}
