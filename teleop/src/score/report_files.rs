//! `pomdar score --out DIR`: the report's files, each written atomically (temp + rename).
//!
//! | file | content |
//! |---|---|
//! | `report.md` | the whole report in Markdown, figures linked |
//! | `scores.csv` | per task × embodiment |
//! | `overall.csv` | per embodiment |
//! | `trials.csv` | per trial |
//! | `scores.json` | everything, machine-readable |
//! | `radar_manipulation`, `radar_grasp`, `overall_vs_dof`, `overall_vs_dof_all_tasks` | `.svg` and `.png` figures |

use std::path::{Path, PathBuf};

use scoring::{
    ScoreReport, render_figures, render_markdown, render_overall_csv, render_scores_csv,
    render_trials_csv,
};

use super::ScoreFileError;
use crate::atomic_file::write_atomically;

/// What [`write_report_files`] did.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct WrittenReport {
    /// Files written.
    pub files: Vec<PathBuf>,
    /// Figures that could not be drawn, with the reason.
    pub figure_errors: Vec<String>,
}

/// Draws the figures (their file names and remarks go into `report`), then writes every file
/// into `dir` (created if needed).
pub fn write_report_files(
    dir: &Path,
    report: &mut ScoreReport,
) -> Result<WrittenReport, ScoreFileError> {
    let mut written = WrittenReport::default();
    let (figures, notes, errors) = render_figures(report);
    report.notes.extend(notes);
    for e in &errors {
        report
            .warnings
            .push(format!("a figure could not be drawn: {e}"));
        written.figure_errors.push(e.to_string());
    }
    let mut write = |name: &str, bytes: &[u8]| -> Result<(), ScoreFileError> {
        let path = dir.join(name);
        write_atomically(&path, bytes)?;
        written.files.push(path);
        Ok(())
    };
    for f in &figures {
        let svg = format!("{}.svg", f.stem);
        let png = format!("{}.png", f.stem);
        write(&svg, f.figure.svg.as_bytes())?;
        write(&png, &f.figure.png)?;
        report.figures.push(svg);
        report.figures.push(png);
    }
    write("report.md", render_markdown(report).as_bytes())?;
    write("scores.csv", render_scores_csv(report).as_bytes())?;
    write("overall.csv", render_overall_csv(report).as_bytes())?;
    write("trials.csv", render_trials_csv(report).as_bytes())?;
    write("scores.json", report.to_json().as_bytes())?;
    Ok(written)
}
