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
    NamedFigure, ScoreReport, ScoringError, render_figures, render_markdown, render_overall_csv,
    render_scores_csv, render_trials_csv,
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
    let (figures, notes, errors) = render_figures(report);
    report.notes.extend(notes);
    let mut written = write_figures(
        dir,
        &figures,
        &errors,
        &mut report.warnings,
        &mut report.figures,
    )?;
    written.write(dir, "report.md", render_markdown(report).as_bytes())?;
    written.write(dir, "scores.csv", render_scores_csv(report).as_bytes())?;
    written.write(dir, "overall.csv", render_overall_csv(report).as_bytes())?;
    written.write(dir, "trials.csv", render_trials_csv(report).as_bytes())?;
    written.write(dir, "scores.json", report.to_json().as_bytes())?;
    Ok(written)
}

impl WrittenReport {
    /// Write `dir/name` atomically and list it.
    pub fn write(&mut self, dir: &Path, name: &str, bytes: &[u8]) -> Result<(), ScoreFileError> {
        let path = dir.join(name);
        write_atomically(&path, bytes)?;
        self.files.push(path);
        Ok(())
    }
}

/// Write each figure as `STEM.svg` and `STEM.png` into `dir` (the names pushed onto `names`);
/// a figure that could not be drawn becomes a warning and a figure error.
pub fn write_figures(
    dir: &Path,
    figures: &[NamedFigure],
    errors: &[ScoringError],
    warnings: &mut Vec<String>,
    names: &mut Vec<String>,
) -> Result<WrittenReport, ScoreFileError> {
    let mut written = WrittenReport::default();
    for e in errors {
        warnings.push(format!("a figure could not be drawn: {e}"));
        written.figure_errors.push(e.to_string());
    }
    for f in figures {
        let svg = format!("{}.svg", f.stem);
        let png = format!("{}.png", f.stem);
        written.write(dir, &svg, f.figure.svg.as_bytes())?;
        written.write(dir, &png, &f.figure.png)?;
        names.push(svg);
        names.push(png);
    }
    Ok(written)
}
