//! Which files to score: `.mcap` files named on the command line, and those found by walking
//! the directories named (recursively, sorted, symlinked directories not followed so a link
//! loop cannot hang the walk). Interrupted recordings (`*.mcap.part`) are skipped with a note;
//! a path that does not exist is a problem named with its reason.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use scoring::FileProblem;

/// The files found.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct TrialFiles {
    /// `.mcap` files to score, in command-line order, each directory's files sorted; each
    /// file once.
    pub files: Vec<PathBuf>,
    /// Files skipped on purpose (unfinished `.part` recordings).
    pub skipped: Vec<FileProblem>,
    /// Paths that could not be read.
    pub problems: Vec<FileProblem>,
}

fn is_part(path: &Path) -> bool {
    path.to_string_lossy().ends_with(".mcap.part")
}

fn is_mcap(path: &Path) -> bool {
    path.extension().is_some_and(|e| e == "mcap")
}

fn part_note(path: &Path) -> FileProblem {
    FileProblem {
        file: path.display().to_string(),
        reason: format!(
            "an unfinished recording (.part), not scored: repair it with `pomdar recover {}`",
            path.display()
        ),
    }
}

/// Exit status of the commands that read many trial files (`pomdar score`, `baseline`,
/// `study-report`) when the run finished but some files were rejected.
pub const EXIT_SOME_REJECTED: u8 = 3;

/// Collects the trial files under `paths`.
pub fn collect_trial_files(paths: &[PathBuf]) -> TrialFiles {
    let mut out = TrialFiles::default();
    let mut seen = BTreeSet::new();
    let mut add = |out: &mut TrialFiles, path: PathBuf| {
        let key = std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone());
        if seen.insert(key) {
            out.files.push(path);
        }
    };
    for path in paths {
        let metadata = match std::fs::metadata(path) {
            Ok(m) => m,
            Err(e) => {
                out.problems.push(FileProblem {
                    file: path.display().to_string(),
                    reason: format!("cannot read: {e}"),
                });
                continue;
            }
        };
        if metadata.is_dir() {
            let mut found = Vec::new();
            walk(path, &mut found, &mut out);
            found.sort();
            for file in found {
                add(&mut out, file);
            }
        } else if is_part(path) {
            out.skipped.push(part_note(path));
        } else {
            // A file named explicitly is scored whatever its extension; the reader says if it
            // is not MCAP.
            add(&mut out, path.clone());
        }
    }
    out
}

fn walk(dir: &Path, found: &mut Vec<PathBuf>, out: &mut TrialFiles) {
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) => {
            out.problems.push(FileProblem {
                file: dir.display().to_string(),
                reason: format!("cannot list the directory: {e}"),
            });
            return;
        }
    };
    let mut parts = Vec::new();
    let mut dirs = Vec::new();
    for entry in entries {
        let entry = match entry {
            Ok(entry) => entry,
            Err(e) => {
                out.problems.push(FileProblem {
                    file: dir.display().to_string(),
                    reason: format!("cannot list the directory: {e}"),
                });
                continue;
            }
        };
        let path = entry.path();
        let kind = match entry.file_type() {
            Ok(kind) => kind,
            Err(e) => {
                out.problems.push(FileProblem {
                    file: path.display().to_string(),
                    reason: format!("cannot read: {e}"),
                });
                continue;
            }
        };
        if kind.is_dir() {
            dirs.push(path);
        } else if is_part(&path) {
            parts.push(path);
        } else if is_mcap(&path) {
            found.push(path);
        }
    }
    parts.sort();
    out.skipped.extend(parts.iter().map(|p| part_note(p)));
    dirs.sort();
    for d in dirs {
        walk(&d, found, out);
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn walks_directories_skips_parts_and_names_missing_paths() {
        let dir = std::env::temp_dir().join(format!("pomdar-trial-files-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        std::fs::create_dir_all(dir.join("b/c")).unwrap();
        for f in [
            "b/2.mcap",
            "b/1.mcap",
            "b/c/3.mcap",
            "b/c/4.mcap.part",
            "b/notes.txt",
        ] {
            std::fs::write(dir.join(f), b"x").unwrap();
        }
        let found =
            collect_trial_files(&[dir.join("b"), dir.join("b/1.mcap"), dir.join("nope.mcap")]);
        let names: Vec<String> = found
            .files
            .iter()
            .map(|p| p.strip_prefix(&dir).unwrap().display().to_string())
            .collect();
        assert_eq!(names, ["b/1.mcap", "b/2.mcap", "b/c/3.mcap"]);
        assert_eq!(found.skipped.len(), 1);
        assert!(found.skipped[0].reason.contains("pomdar recover"));
        assert_eq!(found.problems.len(), 1);
        assert!(found.problems[0].file.ends_with("nope.mcap"));
        std::fs::remove_dir_all(&dir).ok();
    }
}
