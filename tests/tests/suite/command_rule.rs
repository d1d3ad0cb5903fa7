//! The command rule holds for `teleop/src/command/`: every file at most 250 lines, and no
//! command importing another (see `pomdar_tests::command_rule`); and the check itself catches
//! both in a made-up crate.

use pomdar_tests::command_rule::{
    COMMAND_FILE_LINES, command_cross_imports, oversized_command_files,
};
use pomdar_tests::{scratch_dir, workspace_root};

#[test]
fn every_command_file_is_short() {
    let dir = workspace_root().join("teleop").join("src").join("command");
    let files = pomdar_tests::files_with_extension(&dir, "rs").unwrap();
    assert!(files.len() > 20, "found only {} command files", files.len());
    let report = oversized_command_files(&dir).unwrap();
    assert!(
        report.is_empty(),
        "files under teleop/src/command/ over {COMMAND_FILE_LINES} lines (move the work into the module that owns it):\n{}",
        report.join("\n")
    );
}

#[test]
fn no_command_imports_another() {
    let root = workspace_root().join("teleop").join("src").join("lib.rs");
    let report = command_cross_imports(&root).unwrap();
    assert!(
        report.is_empty(),
        "commands importing each other (move what they share out of command/, or shared flags into command/shared_args.rs):\n{}",
        report.join("\n")
    );
}

#[test]
fn the_check_catches_a_long_file_and_a_command_importing_another() {
    let dir = scratch_dir("command-rule");
    let command = dir.join("command");
    std::fs::create_dir_all(&command).unwrap();
    let write = |name: &str, text: &str| std::fs::write(command.join(name), text).unwrap();
    std::fs::write(dir.join("lib.rs"), "pub mod command;\npub mod console;\n").unwrap();
    std::fs::write(dir.join("console.rs"), "pub fn run() {}\n").unwrap();
    write(
        "mod.rs",
        "pub mod cli;\npub mod shared_args;\npub mod study;\npub mod trial;\npub mod demo;\n",
    );
    write("cli.rs", "use crate::command::{study, trial};\n");
    write("shared_args.rs", "pub struct NodeArgs;\n");
    write(
        "trial.rs",
        "use super::shared_args::NodeArgs;\npub fn trial() { crate::console::run(); }\n",
    );
    write("study.rs", "use super::trial::trial;\n");
    write(
        "demo.rs",
        &format!(
            "pub fn demo() {{ crate::command::shared_args::NodeArgs; }}\n{}",
            "// a line\n".repeat(COMMAND_FILE_LINES)
        ),
    );
    let imports = command_cross_imports(&dir.join("lib.rs")).unwrap();
    assert_eq!(imports.len(), 1, "{imports:?}");
    assert!(imports[0].starts_with("command::study imports command::trial"));
    let long = oversized_command_files(&command).unwrap();
    assert_eq!(long.len(), 1, "{long:?}");
    assert!(long[0].contains("demo.rs: 251 lines"), "{long:?}");
}
