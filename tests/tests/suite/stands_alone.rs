//! The repository stands alone: no source file, script, configuration or document cites a
//! document outside it or a tracker's issue number. A fact the code needs is written into the
//! repository's own docs (`docs/LAB_CONVENTIONS.md` and the others), in its own words. Tests may
//! read the shared reference data beside the clone; that is data, not a citation, and is not
//! matched here.

use std::path::{Path, PathBuf};

use pomdar_tests::workspace_root;

/// Names of documents outside the repository (written in pieces so this file does not match).
const OUTSIDE_DOCUMENTS: [&str; 3] = [
    concat!("DOMAIN", ".md"),
    concat!("STYLE", ".md"),
    concat!("shared/", "docs"),
];

/// Extensions of the files a reader or a build reads.
const TEXT_EXTENSIONS: [&str; 8] = ["rs", "md", "toml", "py", "sh", "json", "yaml", "txt"];

/// Directories that hold no project text: build output, vendored libraries, virtual
/// environments, version control.
fn skipped(dir: &Path) -> bool {
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    matches!(
        name.as_str(),
        "target" | ".git" | ".mujoco" | "node_modules" | "__pycache__"
    ) || name.ends_with("venv")
}

fn project_text_files(root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut pending = vec![root.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() {
                if !skipped(&path) {
                    pending.push(path);
                }
            } else if path
                .extension()
                .is_some_and(|e| TEXT_EXTENSIONS.iter().any(|t| e == *t))
            {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// Where `text` names a tracker's issue by number: the word, singular or plural, then a number,
/// with only spaces, a `#`, a line break or a comment's leading slashes between. Byte offsets.
fn issue_numbers(text: &str) -> Vec<usize> {
    let lower = text.to_ascii_lowercase();
    let bytes = lower.as_bytes();
    let mut hits = Vec::new();
    let mut from = 0;
    while let Some(at) = lower[from..].find("issue") {
        let start = from + at;
        from = start + 5;
        let word_start = start == 0 || !bytes[start - 1].is_ascii_alphanumeric();
        let mut k = from;
        if bytes.get(k) == Some(&b's') {
            k += 1;
        }
        let gap = k;
        while bytes
            .get(k)
            .is_some_and(|b| b.is_ascii_whitespace() || matches!(b, b'/' | b'!' | b'#' | b'*'))
        {
            k += 1;
        }
        if word_start && k > gap && bytes.get(k).is_some_and(u8::is_ascii_digit) {
            hits.push(start);
        }
    }
    hits
}

fn line_of(text: &str, offset: usize) -> usize {
    text[..offset].matches('\n').count() + 1
}

#[test]
fn no_file_cites_an_outside_document_or_an_issue_number() {
    let root = workspace_root();
    let files = project_text_files(&root);
    assert!(files.len() > 300, "found only {} files", files.len());
    let mut report = Vec::new();
    for file in &files {
        let Ok(text) = std::fs::read_to_string(file) else {
            continue;
        };
        let shown = file
            .strip_prefix(&root)
            .unwrap_or(file)
            .display()
            .to_string();
        for needle in OUTSIDE_DOCUMENTS {
            for (offset, _) in text.match_indices(needle) {
                report.push(format!(
                    "{shown}:{}: names {needle}",
                    line_of(&text, offset)
                ));
            }
        }
        for offset in issue_numbers(&text) {
            report.push(format!(
                "{shown}:{}: an issue number",
                line_of(&text, offset)
            ));
        }
    }
    assert!(
        report.is_empty(),
        "citations outside the repository:\n{}",
        report.join("\n")
    );
}

#[test]
fn an_issue_number_is_found_across_a_line_break_and_not_in_other_words() {
    // Written in pieces, so that this file holds no citation itself.
    let word = concat!("iss", "ue");
    assert_eq!(issue_numbers(&format!("as {word} 12 asked")), vec![3]);
    assert_eq!(
        issue_numbers(&format!("{}S #4 and 5", word.to_uppercase())),
        vec![0]
    );
    assert_eq!(
        issue_numbers(&format!("smoothing of {word}\n/// 12, a frame")),
        vec![13]
    );
    let other_words = format!("{word}d 3 times; the {word}'s text; t{word} 4");
    assert!(issue_numbers(&other_words).is_empty());
    assert!(issue_numbers(&format!("an {word}, 2 lines")).is_empty());
}
