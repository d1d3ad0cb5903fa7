//! `pomdar score --compare FIELD --out DIR`: the comparison's files, each written atomically
//! (temp + rename).
//!
//! | file | content |
//! |---|---|
//! | `compare.md` | the comparison in Markdown, figures linked |
//! | `compare.csv` | per task × embodiment × group, with the differences and their intervals |
//! | `compare.json` | everything, machine-readable |
//! | `compare_score`, `compare_correctness` | `.svg` and `.png`: grouped bars per task × embodiment, one bar per group |

use std::path::Path;

use scoring::{Comparison, render_compare_csv, render_compare_figures, render_compare_markdown};

use super::ScoreFileError;
use super::report_files::WrittenReport;
use crate::atomic_file::write_atomically;

/// Draws the figures (their file names and remarks go into `comparison`), then writes every
/// file into `dir` (created if needed).
pub fn write_compare_files(
    dir: &Path,
    comparison: &mut Comparison,
) -> Result<WrittenReport, ScoreFileError> {
    let mut written = WrittenReport::default();
    let (figures, notes, errors) = render_compare_figures(comparison);
    comparison.notes.extend(notes);
    for e in &errors {
        comparison
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
        comparison.figures.push(svg);
        comparison.figures.push(png);
    }
    write("compare.md", render_compare_markdown(comparison).as_bytes())?;
    write("compare.csv", render_compare_csv(comparison).as_bytes())?;
    write("compare.json", comparison.to_json().as_bytes())?;
    Ok(written)
}
