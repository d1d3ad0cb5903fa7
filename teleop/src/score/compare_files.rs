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
use super::report_files::{WrittenReport, write_figures};

/// Draws the figures (their file names and remarks go into `comparison`), then writes every
/// file into `dir` (created if needed).
pub fn write_compare_files(
    dir: &Path,
    comparison: &mut Comparison,
) -> Result<WrittenReport, ScoreFileError> {
    let (figures, notes, errors) = render_compare_figures(comparison);
    comparison.notes.extend(notes);
    let (warnings, names) = (&mut comparison.warnings, &mut comparison.figures);
    let mut written = write_figures(dir, &figures, &errors, warnings, names)?;
    written.write(
        dir,
        "compare.md",
        render_compare_markdown(comparison).as_bytes(),
    )?;
    written.write(
        dir,
        "compare.csv",
        render_compare_csv(comparison).as_bytes(),
    )?;
    written.write(dir, "compare.json", comparison.to_json().as_bytes())?;
    Ok(written)
}
