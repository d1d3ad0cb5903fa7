//! The dependency rule holds for the real workspace: checked on `cargo metadata` and on the
//! core crates' sources.

use std::process::Command;

use pomdar_tests::dependency_rule::{
    CORE_CRATES, banned_dependencies, banned_source_lines, crate_dir,
};
use pomdar_tests::{files_with_extension, workspace_root};

#[test]
fn core_crates_never_reach_ros2_client_rustdds_or_tokio() {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let output = Command::new(cargo)
        .args(["metadata", "--format-version", "1", "--locked"])
        .current_dir(workspace_root())
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "cargo metadata failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let metadata: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let members = metadata["workspace_members"].as_array().unwrap().len();
    assert!(
        members >= 6,
        "expected the whole workspace, got {members} members"
    );
    let violations = banned_dependencies(&metadata);
    assert!(
        violations.is_empty(),
        "dependency rule broken:\n{}",
        violations.join("\n")
    );
}

#[test]
fn core_crate_sources_do_no_io_and_read_no_clock() {
    let mut report = Vec::new();
    let mut files = Vec::new();
    for core in CORE_CRATES {
        files.extend(
            files_with_extension(&workspace_root().join(crate_dir(core)).join("src"), "rs")
                .unwrap(),
        );
    }
    assert!(files.len() >= 4, "found only {} source files", files.len());
    for file in files {
        let source = std::fs::read_to_string(&file).unwrap();
        for line in banned_source_lines(&source) {
            report.push(format!("{}: {line}", file.display()));
        }
    }
    assert!(
        report.is_empty(),
        "I/O or clock use in a core crate:\n{}",
        report.join("\n")
    );
}

#[test]
fn no_crate_has_a_module_cycle() {
    let mut report = Vec::new();
    let mut crates = 0;
    let members = workspace_members();
    assert!(
        members.len() >= 12,
        "the workspace's members, read from Cargo.toml: {members:?}"
    );
    for member in &members {
        let root = workspace_root().join(member).join("src").join("lib.rs");
        let modules = pomdar_tests::module_graph::module_files(&root).unwrap();
        assert!(
            modules.len() > 1,
            "{member}: found no modules below {}",
            root.display()
        );
        crates += 1;
        for cycle in pomdar_tests::module_graph::crate_module_cycles(&root).unwrap() {
            report.push(format!(
                "{member}: {} ↔ among {}:\n  {}",
                cycle.members.join(" ↔ "),
                cycle.parent,
                cycle.evidence.join("\n  ")
            ));
        }
    }
    assert_eq!(crates, members.len());
    assert!(report.is_empty(), "module cycles:\n{}", report.join("\n"));
}

#[test]
fn anyhow_is_only_in_the_binary_wiring() {
    let src = workspace_root().join("teleop").join("src");
    let files = files_with_extension(&src, "rs").unwrap();
    assert!(
        files.len() > 50,
        "found only {} teleop sources",
        files.len()
    );
    let wiring = |path: &std::path::Path| {
        path.starts_with(src.join("command")) || path == src.join("main.rs")
    };
    let offenders: Vec<String> = files
        .iter()
        .filter(|path| !wiring(path))
        .filter(|path| std::fs::read_to_string(path).unwrap().contains("anyhow"))
        .map(|path| path.display().to_string())
        .collect();
    assert!(
        offenders.is_empty(),
        "anyhow outside teleop/src/command/ and main.rs (each module has its own typed error):\n{}",
        offenders.join("\n")
    );
}

/// teleop's modules import only from their own layer and the layers below it, as the table in
/// `teleop/src/lib.rs` ranks them, and the table names every top-level module.
#[test]
fn teleop_imports_only_from_its_own_layer_and_below() {
    use pomdar_tests::layer_rule::{inner_doc, layer_ranks, layer_violations};
    let root = workspace_root().join("teleop/src/lib.rs");
    let doc = inner_doc(&std::fs::read_to_string(&root).unwrap());
    let ranks = layer_ranks(&doc).unwrap();
    assert!(ranks.len() >= 20, "the table names {} modules", ranks.len());
    let report = layer_violations(&root, &ranks).unwrap();
    assert!(
        report.is_empty(),
        "layer rule broken:\n{}",
        report.join("\n")
    );
}

/// The layer check fails where it should: a fixture crate whose infrastructure module names
/// its sessions module, and a module its table leaves out.
#[test]
fn the_layer_check_reports_an_upward_import_and_an_unlisted_module() {
    use pomdar_tests::layer_rule::{layer_ranks, layer_violations};
    let fixture = workspace_root().join("tests/fixtures/layer_rule");
    let doc = std::fs::read_to_string(fixture.join("ARCHITECTURE.md")).unwrap();
    let ranks = layer_ranks(&doc).unwrap();
    let report = layer_violations(&fixture.join("src/lib.rs"), &ranks).unwrap();
    assert_eq!(report.len(), 2, "{report:#?}");
    assert!(
        report
            .iter()
            .any(|l| l.starts_with("`clock` (infrastructure) imports `console` (sessions)")),
        "{report:#?}"
    );
    assert!(
        report
            .iter()
            .any(|l| l.contains("`unlisted` is in no layer")),
        "{report:#?}"
    );
}

/// Every crate of the workspace, as the root `Cargo.toml` lists its members: a crate added
/// later is checked without being named here.
fn workspace_members() -> Vec<String> {
    let path = workspace_root().join("Cargo.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let manifest: toml::Table = toml::from_str(&text).unwrap();
    let members = manifest["workspace"]["members"].as_array().unwrap();
    members
        .iter()
        .map(|m| m.as_str().unwrap().to_string())
        .collect()
}
