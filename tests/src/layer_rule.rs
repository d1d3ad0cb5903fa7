//! The layers inside a crate, as the table in its root's doc comment ranks them, held against
//! its imports: a module may name modules of its own layer or of the layers below it, never one
//! above. The table is the one readers see (`| layer | module | what |`, a module named in
//! backticks with a trailing `/` or `.rs`), so the document and the check cannot drift apart: a
//! top-level module the table does not name is reported too. The imports are the module graph's
//! ([`crate::module_graph`]: every `crate::`/`super::`/`self::` path, test modules left out).

use std::collections::BTreeMap;
use std::path::Path;

use crate::module_graph::{crate_references, module_files};

/// The layers from the bottom up: a layer may import from its own and every earlier one.
pub const LAYERS: [&str; 4] = ["infrastructure", "nodes and logs", "sessions", "wiring"];

/// The header row that starts the layer table.
pub const TABLE_HEADER: &str = "| layer | module | what |";

/// The inner doc comment (`//!` lines) of a Rust source file, as the Markdown it is.
pub fn inner_doc(source: &str) -> String {
    source
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("//!"))
        .map(|l| l.strip_prefix(' ').unwrap_or(l))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Each module the layer table of `markdown` names, with its layer's rank in [`LAYERS`].
/// An unknown layer name is an error naming the row.
pub fn layer_ranks(markdown: &str) -> Result<BTreeMap<String, usize>, String> {
    let mut lines = markdown.lines().skip_while(|l| l.trim() != TABLE_HEADER);
    if lines.next().is_none() {
        return Err(format!("no layer table (a row `{TABLE_HEADER}`)"));
    }
    let mut ranks = BTreeMap::new();
    for row in lines.skip(1).take_while(|l| l.starts_with('|')) {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        let (layer, modules) = (cells.get(1).copied(), cells.get(2).copied());
        let (Some(layer), Some(modules)) = (layer, modules) else {
            return Err(format!("a layer row without a module cell: {row}"));
        };
        let rank = LAYERS
            .iter()
            .position(|l| *l == layer)
            .ok_or_else(|| format!("unknown layer `{layer}` (allowed: {LAYERS:?}) in: {row}"))?;
        for module in named_modules(modules) {
            ranks.insert(module, rank);
        }
    }
    Ok(ranks)
}

/// The modules a table cell names: backticked words ending in `/` or `.rs`, without them.
fn named_modules(cell: &str) -> Vec<String> {
    cell.split('`')
        .skip(1)
        .step_by(2)
        .filter_map(|word| {
            word.strip_suffix('/')
                .or_else(|| word.strip_suffix(".rs"))
                .map(str::to_string)
        })
        .collect()
}

/// Every import of the crate rooted at `root_file` that reaches a layer above its own, and
/// every top-level module `ranks` does not name, as readable lines.
pub fn layer_violations(
    root_file: &Path,
    ranks: &BTreeMap<String, usize>,
) -> std::io::Result<Vec<String>> {
    let modules = module_files(root_file)?;
    let (known, references) = crate_references(&modules)?;
    let mut report = Vec::new();
    for top in known.iter().filter(|p| p.len() == 1) {
        if !ranks.contains_key(&top[0]) {
            report.push(format!("module `{}` is in no layer of the table", top[0]));
        }
    }
    for reference in &references {
        let (Some(from), Some(to)) = (reference.from.first(), reference.to.first()) else {
            continue;
        };
        if from == to || !known.contains(std::slice::from_ref(to)) {
            continue;
        }
        let (Some(&low), Some(&high)) = (ranks.get(from), ranks.get(to)) else {
            continue;
        };
        if high > low {
            report.push(format!(
                "`{from}` ({}) imports `{to}` ({}), a layer above: {} names {}",
                LAYERS[low],
                LAYERS[high],
                reference.file.display(),
                reference.to.join("::")
            ));
        }
    }
    report.sort();
    report.dedup();
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_gives_each_named_module_its_layer() {
        let doc = "intro\n\n| layer | module | what |\n|---|---|---|\n\
                   | wiring | `main.rs`, `command/` | the commands |\n\
                   | sessions | `sim_bench/` (feature `physics`) | runs |\n\
                   | infrastructure | `clock.rs`, `ros/` | below |\n\nafter | not a row |\n";
        let ranks = layer_ranks(doc).unwrap();
        assert_eq!(ranks["command"], 3);
        assert_eq!(ranks["sim_bench"], 2);
        assert_eq!(ranks["clock"], 0);
        assert!(
            !ranks.contains_key("physics"),
            "a feature name is no module"
        );
        assert_eq!(ranks.len(), 5);
        let wrong = doc.replace("| sessions |", "| session |");
        assert!(
            layer_ranks(&wrong)
                .unwrap_err()
                .contains("unknown layer `session`")
        );
        assert!(layer_ranks("no table").is_err());
    }
}
