//! Module cycles in a crate's sources: the module tree is read from the crate root by following
//! its `mod` declarations (`#[path]` included), every `crate::`, `super::` and `self::` path in
//! the sources (`use` trees and inline paths) becomes an edge between the two sibling modules
//! that contain its two ends, and the strongly connected components of each module's children
//! are the cycles. Comments, strings and character literals are skipped; inline `mod x { … }`
//! blocks are modules of their own. Test modules (`#[cfg(test)]`) are left out: test code may
//! reach anywhere, the layering is the library's.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A module path below the crate root (`["console", "view"]`); the root is empty.
pub type ModulePath = Vec<String>;

/// One reference from a module to another, where it was written.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct Reference {
    /// The module the path was written in.
    pub from: ModulePath,
    /// The absolute path it names (module part and possibly an item).
    pub to: ModulePath,
    /// The file it was written in.
    pub file: PathBuf,
}

/// A cycle among the children of one module.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ModuleCycle {
    /// The parent module (`crate` for the root).
    pub parent: String,
    /// The sibling modules that reach each other.
    pub members: Vec<String>,
    /// For each edge inside the cycle, one reference that makes it.
    pub evidence: Vec<String>,
}

/// Every module of the crate rooted at `root_file` with the file it is written in.
pub fn module_files(root_file: &Path) -> std::io::Result<BTreeMap<ModulePath, PathBuf>> {
    let mut modules = BTreeMap::new();
    let mut pending = vec![(ModulePath::new(), root_file.to_path_buf())];
    while let Some((path, file)) = pending.pop() {
        let text = strip_comments_and_literals(&std::fs::read_to_string(&file)?);
        for (name, explicit) in file_module_declarations(&text) {
            let child_file = child_module_file(&file, &name, explicit.as_deref());
            let mut child = path.clone();
            child.push(name);
            pending.push((child, child_file));
        }
        modules.insert(path, file);
    }
    Ok(modules)
}

/// Every reference in the crate's sources, from the module (inline modules included) it is
/// written in.
pub fn crate_references(
    modules: &BTreeMap<ModulePath, PathBuf>,
) -> std::io::Result<(BTreeSet<ModulePath>, Vec<Reference>)> {
    let mut known: BTreeSet<ModulePath> = modules.keys().cloned().collect();
    let mut references = Vec::new();
    for (path, file) in modules {
        let text = strip_comments_and_literals(&std::fs::read_to_string(file)?);
        let scan = scan_paths(&text, path);
        known.extend(scan.inline_modules);
        references.extend(scan.paths.into_iter().map(|(from, to)| Reference {
            from,
            to,
            file: file.clone(),
        }));
    }
    Ok((known, references))
}

/// The cycles among sibling modules that `references` make.
pub fn module_cycles(known: &BTreeSet<ModulePath>, references: &[Reference]) -> Vec<ModuleCycle> {
    let mut edges: BTreeMap<ModulePath, BTreeMap<(String, String), &Reference>> = BTreeMap::new();
    for reference in references {
        let target = module_part(known, &reference.to);
        if let Some((parent, from, to)) = sibling_edge(&reference.from, &target) {
            edges
                .entry(parent)
                .or_default()
                .entry((from, to))
                .or_insert(reference);
        }
    }
    let mut cycles = Vec::new();
    for (parent, parent_edges) in &edges {
        let graph: BTreeMap<&str, Vec<&str>> =
            parent_edges
                .keys()
                .fold(BTreeMap::new(), |mut graph, (from, to)| {
                    graph.entry(from.as_str()).or_insert_with(Vec::new).push(to);
                    graph.entry(to.as_str()).or_insert_with(Vec::new);
                    graph
                });
        for component in strongly_connected(&graph) {
            if component.len() < 2 {
                continue;
            }
            let members: BTreeSet<&str> = component.iter().copied().collect();
            let evidence = parent_edges
                .iter()
                .filter(|((f, t), _)| members.contains(f.as_str()) && members.contains(t.as_str()))
                .map(|((f, t), r)| {
                    format!("{f} → {t}: {} names {}", r.file.display(), r.to.join("::"))
                })
                .collect();
            cycles.push(ModuleCycle {
                parent: display_path(parent),
                members: members.iter().map(|m| (*m).to_string()).collect(),
                evidence,
            });
        }
    }
    cycles
}

/// The cycles of the crate whose root file is `root_file` (`src/lib.rs`).
pub fn crate_module_cycles(root_file: &Path) -> std::io::Result<Vec<ModuleCycle>> {
    let modules = module_files(root_file)?;
    let (known, references) = crate_references(&modules)?;
    Ok(module_cycles(&known, &references))
}

fn display_path(path: &[String]) -> String {
    if path.is_empty() {
        "crate".into()
    } else {
        format!("crate::{}", path.join("::"))
    }
}

/// The longest prefix of `path` that is a known module.
fn module_part(known: &BTreeSet<ModulePath>, path: &[String]) -> ModulePath {
    (0..=path.len())
        .rev()
        .map(|n| path[..n].to_vec())
        .find(|prefix| known.contains(prefix))
        .unwrap_or_default()
}

/// The edge between siblings that a reference from module `from` to module `to` makes: their
/// common parent and the two children of it that contain each end. None when one contains the
/// other.
fn sibling_edge(from: &[String], to: &[String]) -> Option<(ModulePath, String, String)> {
    let common = from.iter().zip(to).take_while(|(a, b)| a == b).count();
    if common == from.len() || common == to.len() {
        return None;
    }
    Some((
        from[..common].to_vec(),
        from[common].clone(),
        to[common].clone(),
    ))
}

/// Tarjan's strongly connected components.
fn strongly_connected<'a>(graph: &BTreeMap<&'a str, Vec<&'a str>>) -> Vec<Vec<&'a str>> {
    struct Tarjan<'g, 'a> {
        graph: &'g BTreeMap<&'a str, Vec<&'a str>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        components: Vec<Vec<&'a str>>,
    }
    impl<'a> Tarjan<'_, 'a> {
        fn visit(&mut self, node: &'a str) {
            let index = self.index.len();
            self.index.insert(node, index);
            self.low.insert(node, index);
            self.stack.push(node);
            self.on_stack.insert(node);
            for &next in self.graph.get(node).into_iter().flatten() {
                if !self.index.contains_key(next) {
                    self.visit(next);
                    let low = self.low[node].min(self.low[next]);
                    self.low.insert(node, low);
                } else if self.on_stack.contains(next) {
                    let low = self.low[node].min(self.index[next]);
                    self.low.insert(node, low);
                }
            }
            if self.low[node] == self.index[node] {
                let mut component = Vec::new();
                while let Some(member) = self.stack.pop() {
                    self.on_stack.remove(member);
                    component.push(member);
                    if member == node {
                        break;
                    }
                }
                self.components.push(component);
            }
        }
    }
    let mut tarjan = Tarjan {
        graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        components: Vec::new(),
    };
    for &node in graph.keys() {
        if !tarjan.index.contains_key(node) {
            tarjan.visit(node);
        }
    }
    tarjan.components
}

/// `mod name;` declarations (not inline blocks) with their `#[path = "…"]`, if any, in a
/// text stripped by [`strip_comments_and_literals`] (which keeps a path attribute's string).
fn file_module_declarations(text: &str) -> Vec<(String, Option<String>)> {
    let tokens = tokenize(text);
    let mut out = Vec::new();
    for (i, token) in tokens.iter().enumerate() {
        if token != "mod" {
            continue;
        }
        let (Some(name), Some(end)) = (tokens.get(i + 1), tokens.get(i + 2)) else {
            continue;
        };
        if end != ";" || !is_ident(name) {
            continue;
        }
        let attributes = attributes_before(&tokens, i);
        if attributes.iter().any(|a| is_cfg_test(a)) {
            continue;
        }
        let path = attributes.iter().find_map(|a| match a.as_slice() {
            [key, eq, value] if key == "path" && eq == "=" => {
                Some(value.trim_matches('"').to_string())
            }
            _ => None,
        });
        out.push((name.clone(), path));
    }
    out
}

/// The attributes (`#[…]` contents as tokens) right before token `i`, past a visibility.
fn attributes_before(tokens: &[String], i: usize) -> Vec<Vec<String>> {
    let mut attributes = Vec::new();
    let mut j = i;
    while j > 0
        && matches!(
            tokens[j - 1].as_str(),
            "pub" | ")" | "crate" | "(" | "super"
        )
    {
        j -= 1;
    }
    while j > 1 && tokens[j - 1] == "]" {
        let close = j - 1;
        let Some(open) = (0..close).rev().find(|&k| tokens[k] == "[") else {
            break;
        };
        attributes.push(tokens[open + 1..close].to_vec());
        if open == 0 || tokens[open - 1] != "#" {
            break;
        }
        j = open - 1;
    }
    attributes
}

fn is_cfg_test(attribute: &[String]) -> bool {
    attribute == ["cfg", "(", "test", ")"]
}

/// The file of child module `name` declared in `parent_file`.
fn child_module_file(parent_file: &Path, name: &str, explicit: Option<&str>) -> PathBuf {
    let dir = parent_file.parent().unwrap_or(Path::new(""));
    if let Some(explicit) = explicit {
        return dir.join(explicit);
    }
    let stem = parent_file
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("");
    let base = if matches!(stem, "lib" | "main" | "mod") {
        dir.to_path_buf()
    } else {
        dir.join(stem)
    };
    let flat = base.join(format!("{name}.rs"));
    if flat.exists() {
        flat
    } else {
        base.join(name).join("mod.rs")
    }
}

/// What one file's text names.
struct PathScan {
    /// (module written in, absolute path named).
    paths: Vec<(ModulePath, ModulePath)>,
    /// Inline modules (`mod x { … }`) found.
    inline_modules: Vec<ModulePath>,
}

/// Every `crate::`/`super::`/`self::` path in `text`, written in module `file_module` (or an
/// inline module inside it); paths inside `#[cfg(test)]` inline modules are left out.
fn scan_paths(text: &str, file_module: &[String]) -> PathScan {
    let tokens = tokenize(text);
    let mut scan = PathScan {
        paths: Vec::new(),
        inline_modules: Vec::new(),
    };
    let mut open = OpenModules {
        file_module: file_module.to_vec(),
        inline: Vec::new(),
        depth: 0,
    };
    let mut i = 0;
    while i < tokens.len() {
        i = match tokens[i].as_str() {
            "mod" if tokens.get(i + 2).is_some_and(|t| t == "{") => {
                let is_test = attributes_before(&tokens, i).iter().any(|a| is_cfg_test(a));
                scan.inline_modules
                    .push(open.enter(&tokens[i + 1], is_test));
                i + 3
            }
            "{" => {
                open.depth += 1;
                i + 1
            }
            "}" => {
                open.close_brace();
                i + 1
            }
            "crate" | "super" | "self"
                if tokens.get(i + 1).is_some_and(|t| t == "::")
                    && (i == 0 || tokens[i - 1] != "::") =>
            {
                let current = open.current();
                let (base, next) = path_base(&tokens, i, &current);
                let (paths, after) = use_tree(&tokens, next, &base);
                if !open.in_test() {
                    scan.paths
                        .extend(paths.into_iter().map(|p| (current.clone(), p)));
                }
                after
            }
            _ => i + 1,
        };
    }
    scan
}

/// The inline modules open at a point of a file.
struct OpenModules {
    file_module: ModulePath,
    /// (module path, brace depth at its `{`, whether it is a test module).
    inline: Vec<(ModulePath, usize, bool)>,
    depth: usize,
}

impl OpenModules {
    fn current(&self) -> ModulePath {
        self.inline
            .last()
            .map_or_else(|| self.file_module.clone(), |(p, _, _)| p.clone())
    }

    fn in_test(&self) -> bool {
        self.inline.iter().any(|(_, _, test)| *test)
    }

    fn enter(&mut self, name: &str, is_test: bool) -> ModulePath {
        let mut path = self.current();
        path.push(name.to_string());
        self.depth += 1;
        self.inline.push((path.clone(), self.depth, is_test));
        path
    }

    fn close_brace(&mut self) {
        if self.inline.last().is_some_and(|(_, d, _)| *d == self.depth) {
            self.inline.pop();
        }
        self.depth = self.depth.saturating_sub(1);
    }
}

/// The module a path starting at token `i` (`crate`, `self` or `super`, then `super`s) is
/// relative to, and the index of the token after its last `::`.
fn path_base(tokens: &[String], mut i: usize, current: &[String]) -> (ModulePath, usize) {
    let mut base = match tokens[i].as_str() {
        "crate" => ModulePath::new(),
        _ => current.to_vec(),
    };
    if tokens[i] == "super" {
        base.pop();
    }
    i += 2;
    while tokens.get(i).is_some_and(|t| t == "super")
        && tokens.get(i + 1).is_some_and(|t| t == "::")
    {
        base.pop();
        i += 2;
    }
    (base, i)
}

/// The paths of a use tree (or a plain path) starting at token `i` below `base`, and the index
/// after it.
fn use_tree(tokens: &[String], mut i: usize, base: &[String]) -> (Vec<ModulePath>, usize) {
    let mut path = base.to_vec();
    loop {
        match tokens.get(i).map(String::as_str) {
            Some("{") => {
                let mut out = Vec::new();
                i += 1;
                while tokens.get(i).is_some_and(|t| t != "}") {
                    let before = i;
                    let (paths, after) = use_tree(tokens, i, &path);
                    out.extend(paths);
                    i = after;
                    let separator = tokens.get(i).is_some_and(|t| t == ",");
                    let stuck = i == before && tokens.get(i).is_some_and(|t| t != "}");
                    if separator || stuck {
                        i += 1;
                    }
                }
                return (out, i + 1);
            }
            Some("self") => return (vec![path], i + 1),
            Some(t) if is_ident(t) => {
                path.push(t.to_string());
                i += 1;
                if tokens.get(i).is_some_and(|t| t == "::") {
                    i += 1;
                    continue;
                }
                return (vec![path], i);
            }
            _ => return (vec![path], i),
        }
    }
}

fn is_ident(token: &str) -> bool {
    token
        .chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
        && token.chars().all(|c| c.is_alphanumeric() || c == '_')
}

/// Identifiers, `::`, and single punctuation characters; string literals stay one token.
fn tokenize(text: &str) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let mut tokens = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c.is_alphanumeric() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            tokens.push(chars[start..i].iter().collect());
        } else if c == '"' {
            let start = i;
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                i += 1;
            }
            i += 1;
            tokens.push(chars[start..i.min(chars.len())].iter().collect());
        } else if c == ':' && chars.get(i + 1) == Some(&':') {
            tokens.push("::".into());
            i += 2;
        } else {
            tokens.push(c.to_string());
            i += 1;
        }
    }
    tokens
}

/// `text` without comments; string and character literals keep their quotes but lose their
/// contents, except a string right after `path =` (a `#[path]` attribute), which is kept.
fn strip_comments_and_literals(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            i = skip_block_comment(&chars, i);
        } else if c == '"'
            || (c == 'r' && matches!(next, Some('"' | '#')) && !ident_before(&chars, i))
        {
            let (end, content) = string_literal(&chars, i);
            let keep = out.trim_end().ends_with("path =") || out.trim_end().ends_with("path=");
            out.push('"');
            if keep {
                out.push_str(&content);
            }
            out.push('"');
            i = end;
        } else if c == '\'' {
            i = char_literal_end(&chars, i, &mut out);
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

fn ident_before(chars: &[char], i: usize) -> bool {
    i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_')
}

fn skip_block_comment(chars: &[char], mut i: usize) -> usize {
    let mut depth = 0;
    while i < chars.len() {
        if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
            depth += 1;
            i += 2;
        } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
            depth -= 1;
            i += 2;
            if depth == 0 {
                break;
            }
        } else {
            i += 1;
        }
    }
    i
}

/// The end of the string literal (plain or raw) starting at `i`, and its contents.
fn string_literal(chars: &[char], mut i: usize) -> (usize, String) {
    let mut hashes = 0;
    let raw = chars[i] == 'r';
    if raw {
        i += 1;
        while chars.get(i) == Some(&'#') {
            hashes += 1;
            i += 1;
        }
    }
    i += 1; // the opening quote
    let mut content = String::new();
    while i < chars.len() {
        if !raw && chars[i] == '\\' {
            i += 2;
            continue;
        }
        if chars[i] == '"' && (0..hashes).all(|k| chars.get(i + 1 + k) == Some(&'#')) {
            return (i + 1 + hashes, content);
        }
        content.push(chars[i]);
        i += 1;
    }
    (i, content)
}

/// Past a character literal (`'x'`, `'\n'`) or a lifetime (`'a`, kept in `out`).
fn char_literal_end(chars: &[char], i: usize, out: &mut String) -> usize {
    if chars.get(i + 1) == Some(&'\\') {
        let mut j = i + 2;
        while j < chars.len() && chars[j] != '\'' {
            j += 1;
        }
        out.push_str("' '");
        return j + 1;
    }
    if chars.get(i + 2) == Some(&'\'') {
        out.push_str("' '");
        return i + 3;
    }
    out.push('\'');
    i + 1
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path(text: &str) -> ModulePath {
        text.split("::")
            .filter(|s| !s.is_empty())
            .map(str::to_string)
            .collect()
    }

    fn scanned(text: &str, module: &str) -> Vec<String> {
        scan_paths(&strip_comments_and_literals(text), &path(module))
            .paths
            .into_iter()
            .map(|(from, to)| format!("{} -> {}", from.join("::"), to.join("::")))
            .collect()
    }

    #[test]
    fn use_trees_super_and_inline_paths_are_resolved() {
        let text = r#"
            use crate::{mcap_log::{TrialReader, self}, samples::Samples};
            use super::health::Gate; // crate::nothing::here
            fn f() { let _ = crate::clock::now(); let s = "crate::fake::x"; }
            mod tests { use super::*; use super::super::view::View; }
            #[cfg(test)]
            mod more_tests { use crate::calibrate::Anything; }
        "#;
        assert_eq!(
            scanned(text, "console::trial_flow"),
            vec![
                "console::trial_flow -> mcap_log::TrialReader",
                "console::trial_flow -> mcap_log",
                "console::trial_flow -> samples::Samples",
                "console::trial_flow -> console::health::Gate",
                "console::trial_flow -> clock::now",
                "console::trial_flow::tests -> console::trial_flow",
                "console::trial_flow::tests -> console::view::View",
            ]
        );
    }

    #[test]
    fn a_cycle_between_siblings_is_found_and_a_parent_child_pair_is_not() {
        let known: BTreeSet<ModulePath> = ["", "a", "a::x", "a::y", "b", "c"]
            .iter()
            .map(|p| path(p))
            .collect();
        let reference = |from: &str, to: &str| Reference {
            from: path(from),
            to: path(to),
            file: PathBuf::from(format!("{from}.rs")),
        };
        let mut references = vec![
            reference("a::x", "a::y::Thing"),
            reference("a::y", "a::Helper"),
            reference("a", "a::x::Item"),
            reference("b", "c::f"),
        ];
        assert!(module_cycles(&known, &references).is_empty());
        references.push(reference("c", "a::x::Item"));
        references.push(reference("a::y", "b::g"));
        let cycles = module_cycles(&known, &references);
        assert_eq!(cycles.len(), 1, "{cycles:?}");
        assert_eq!(cycles[0].parent, "crate");
        assert_eq!(cycles[0].members, vec!["a", "b", "c"]);
        references.push(reference("a::y", "a::x::Item"));
        let cycles = module_cycles(&known, &references);
        assert_eq!(cycles.len(), 2, "{cycles:?}");
        assert!(
            cycles
                .iter()
                .any(|c| c.parent == "crate::a" && c.members == ["x", "y"])
        );
    }

    #[test]
    fn path_attributes_and_lifetimes_survive_stripping_and_test_modules_are_left_out() {
        let text = "#[cfg(test)]\n#[path = \"clutch_tests.rs\"]\nmod tests;\n#[path = \"other.rs\"]\nmod clutch;\nfn f<'a>(x: &'a str) -> char { 'x' }\npub(crate) mod inner;";
        let stripped = strip_comments_and_literals(text);
        assert_eq!(
            file_module_declarations(&stripped),
            vec![
                ("clutch".to_string(), Some("other.rs".to_string())),
                ("inner".to_string(), None)
            ]
        );
    }
}
