//! The rule for `teleop/src/command/`: each file there holds one command's flags, their checks
//! and one call into the module that does the work, so it stays short ([`COMMAND_FILE_LINES`]
//! at most), and no command imports another: what two commands share lives outside
//! `command/`, or in its one shared file of flag structs ([`SHARED_FILE`]). The dispatcher
//! (`cli.rs`, which names every command) and `mod.rs` are not commands.
//!
//! The imports are read with [`crate::module_graph`]: every `crate::`, `super::` and `self::`
//! path (in `use` trees and inline), test modules left out.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::module_graph::{crate_references, module_files};

/// The most lines a file under `command/` may have.
pub const COMMAND_FILE_LINES: usize = 250;

/// The file every command may import: the shared flag structs.
pub const SHARED_FILE: &str = "shared_args";

/// The module that names every command to dispatch to: not a command.
pub const DISPATCHER: &str = "cli";

/// Every `.rs` file below `command_dir` longer than [`COMMAND_FILE_LINES`], with its length.
pub fn oversized_command_files(command_dir: &Path) -> std::io::Result<Vec<String>> {
    let mut report = Vec::new();
    for file in crate::files_with_extension(command_dir, "rs")? {
        let lines = std::fs::read_to_string(&file)?.lines().count();
        if lines > COMMAND_FILE_LINES {
            report.push(format!(
                "{}: {lines} lines (at most {COMMAND_FILE_LINES})",
                file.display()
            ));
        }
    }
    Ok(report)
}

/// Every command module (or a module below it) that writes a path naming another command's
/// module, with the first file it does so in, for the crate rooted at `root_file` (its commands
/// under `crate::command`). The dispatcher may name every command; every command may name the
/// shared file.
pub fn command_cross_imports(root_file: &Path) -> std::io::Result<Vec<String>> {
    let modules = module_files(root_file)?;
    let (_, references) = crate_references(&modules)?;
    let mut found: BTreeMap<(String, String), PathBuf> = BTreeMap::new();
    for reference in references {
        let (Some(from), Some(to)) = (command_of(&reference.from), command_of(&reference.to))
        else {
            continue;
        };
        if from != to && from != DISPATCHER && to != SHARED_FILE {
            found.entry((from, to)).or_insert(reference.file);
        }
    }
    Ok(found
        .into_iter()
        .map(|((from, to), file)| {
            format!(
                "command::{from} imports command::{to} (in {})",
                file.display()
            )
        })
        .collect())
}

/// The command a module path lies in (`["command", "trial", ...]` → `trial`); `None` outside
/// `command/` and for `command` itself and its `mod.rs`.
fn command_of(path: &[String]) -> Option<String> {
    match path {
        [first, name, ..] if first == "command" => Some(name.clone()),
        _ => None,
    }
}
