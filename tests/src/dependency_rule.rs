//! The dependency rule (ARCHITECTURE.md): the core crates `msgs`, `retarget`, `calibration`,
//! `scoring`, `study`, `review`, `station`, `simulation`, `practice` and `consoles` never depend, directly or transitively, on
//! ros2-client, rustdds, tokio or MuJoCo (mujoco-rs), and their sources do no I/O and read no
//! clock. Only `teleop` does.

use std::collections::{BTreeSet, HashMap};

use serde_json::Value;

/// The pure crates.
pub const CORE_CRATES: [&str; 10] = [
    "msgs",
    "retarget",
    "calibration",
    "scoring",
    "study",
    "review",
    "station",
    "simulation",
    "practice",
    "consoles",
];

/// The directory of a workspace crate (its package name, but `simulation` lives in `sim/`).
pub fn crate_dir(package: &str) -> &str {
    match package {
        "simulation" => "sim",
        other => other,
    }
}

/// Packages a core crate must never pull in.
pub const BANNED_PACKAGES: [&str; 4] = ["ros2-client", "rustdds", "tokio", "mujoco-rs"];

/// Source patterns a core crate must not use: file/network/process I/O and wall clocks.
pub const BANNED_SOURCE_PATTERNS: [&str; 7] = [
    "std::fs",
    "std::net",
    "std::process",
    "std::thread",
    "Instant::now",
    "SystemTime",
    "std::env::var",
];

/// Every `(core crate, banned package, path)` where `cargo metadata` output shows a core
/// crate reaching a banned package, through any kind of dependency.
pub fn banned_dependencies(metadata: &Value) -> Vec<String> {
    let name_of: HashMap<&str, &str> = metadata["packages"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|p| Some((p["id"].as_str()?, p["name"].as_str()?)))
        .collect();
    let deps: HashMap<&str, Vec<&str>> = metadata["resolve"]["nodes"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|n| {
            let id = n["id"].as_str()?;
            let deps = n["deps"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(|d| d["pkg"].as_str())
                .collect();
            Some((id, deps))
        })
        .collect();

    let mut violations = Vec::new();
    for core in CORE_CRATES {
        let Some((&root, _)) = name_of.iter().find(|(_, n)| **n == core) else {
            continue;
        };
        // Depth-first walk keeping the path, so the report shows how a ban is reached.
        let mut stack = vec![vec![root]];
        let mut seen = BTreeSet::from([root]);
        while let Some(path) = stack.pop() {
            let last = path[path.len() - 1];
            for &dep in deps.get(last).map(Vec::as_slice).unwrap_or(&[]) {
                let mut next = path.clone();
                next.push(dep);
                let name = name_of.get(dep).copied().unwrap_or(dep);
                if BANNED_PACKAGES.contains(&name) {
                    let chain: Vec<&str> = next
                        .iter()
                        .map(|id| name_of.get(id).copied().unwrap_or(id))
                        .collect();
                    violations.push(format!("{core} reaches {name}: {}", chain.join(" -> ")));
                } else if seen.insert(dep) {
                    stack.push(next);
                }
            }
        }
    }
    violations
}

/// Lines of `source` (not comments) that use a banned pattern, as `line N: text`.
pub fn banned_source_lines(source: &str) -> Vec<String> {
    source
        .lines()
        .enumerate()
        .filter(|(_, line)| !line.trim_start().starts_with("//"))
        .filter(|(_, line)| BANNED_SOURCE_PATTERNS.iter().any(|p| line.contains(p)))
        .map(|(i, line)| format!("line {}: {}", i + 1, line.trim()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn metadata(edges: &[(&str, &str)]) -> Value {
        let mut names: BTreeSet<&str> = BTreeSet::new();
        for (a, b) in edges {
            names.insert(a);
            names.insert(b);
        }
        json!({
            "packages": names.iter().map(|n| json!({"id": format!("id:{n}"), "name": n})).collect::<Vec<_>>(),
            "resolve": {"nodes": names.iter().map(|n| json!({
                "id": format!("id:{n}"),
                "deps": edges.iter().filter(|(a, _)| a == n)
                    .map(|(_, b)| json!({"pkg": format!("id:{b}")})).collect::<Vec<_>>(),
            })).collect::<Vec<_>>()},
        })
    }

    #[test]
    fn a_transitive_ban_is_reported_with_its_path() {
        let m = metadata(&[
            ("retarget", "helper"),
            ("helper", "tokio"),
            ("teleop", "rustdds"),
        ]);
        let v = banned_dependencies(&m);
        assert_eq!(v, ["retarget reaches tokio: retarget -> helper -> tokio"]);
    }

    #[test]
    fn a_clean_graph_has_no_violations() {
        let m = metadata(&[
            ("retarget", "nalgebra"),
            ("teleop", "tokio"),
            ("teleop", "retarget"),
        ]);
        assert!(banned_dependencies(&m).is_empty());
    }

    #[test]
    fn clock_and_io_uses_are_found_but_comments_are_not() {
        let src = "// Instant::now is banned\nlet t = std::time::Instant::now();\nuse std::fs;\n";
        assert_eq!(
            banned_source_lines(src),
            [
                "line 2: let t = std::time::Instant::now();",
                "line 3: use std::fs;"
            ]
        );
    }
}
