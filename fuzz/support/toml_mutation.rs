//! Structure-aware mutation of TOML documents, for fuzzing every configuration loader on
//! stable Rust with proptest: a valid document (a shipped launch config, a built-in file, a
//! default serialised) is parsed, then keys are set to hostile values (zero, negative, huge,
//! NaN, infinities, empty and long strings, values of the wrong type, empty and long arrays),
//! removed, added (unknown keys), arrays resized, and the text itself is cut or has a byte
//! changed. The loader under test must return `Ok` or `Err` and never panic.
//!
//! Shared by the config fuzz tests of the crates (`*/tests/suite/fuzz_config.rs`, included with
//! `#[path]`); not part of any crate.

#![allow(dead_code)] // each test file uses what it needs

use proptest::prelude::*;
use proptest::sample::Index;
use toml::{Table, Value};

/// One step from a key path into a document.
#[derive(Debug, Clone, PartialEq)]
enum Step {
    Key(String),
    Item(usize),
}

/// One edit of a document.
#[derive(Debug, Clone)]
pub enum TomlEdit {
    /// Replace the value at a path (any node of the document) with another.
    Set(Index, Value),
    /// Multiply the number at a path (integers rounded): values of the right type, near and
    /// far from the valid range, so more documents get past parsing into validation and use.
    Scale(Index, f64),
    /// Remove the value at a path.
    Remove(Index),
    /// Add an unknown key to a table.
    AddKey(Index, String, Value),
    /// Resize an array: truncate it, or repeat its first element.
    ResizeArray(Index, usize),
    /// Change one byte of the document's text.
    TextByte(Index, u8),
    /// Cut the document's text.
    TextTruncate(Index),
}

/// Values that break ranges and types.
pub fn hostile_values() -> impl Strategy<Value = Value> {
    let scalars = prop_oneof![
        prop_oneof![
            Just(0i64),
            Just(-1),
            Just(1),
            Just(2),
            Just(i64::MAX),
            Just(i64::MIN),
            Just(1 << 40),
            -1000i64..1000,
        ]
        .prop_map(Value::Integer),
        prop_oneof![
            Just(0.0f64),
            Just(-0.0),
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(f64::NEG_INFINITY),
            Just(f64::MAX),
            Just(f64::MIN_POSITIVE),
            Just(1e-300),
            Just(-1e300),
            Just(0.5),
            Just(1e9),
            -10.0f64..10.0,
        ]
        .prop_map(Value::Float),
        prop_oneof![
            Just(String::new()),
            Just("x".to_string()),
            Just("/".to_string()),
            Just("a".repeat(5000)),
            "\\PC{0,20}",
            "[a-z_]{1,12}",
        ]
        .prop_map(Value::String),
        any::<bool>().prop_map(Value::Boolean),
    ];
    scalars.prop_recursive(2, 8, 4, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..4).prop_map(Value::Array),
            prop::collection::btree_map("[a-z_]{1,8}", inner, 0..3)
                .prop_map(|m| Value::Table(m.into_iter().collect())),
        ]
    })
}

/// Any edit.
pub fn edits() -> impl Strategy<Value = TomlEdit> {
    prop_oneof![
        6 => (any::<Index>(), hostile_values()).prop_map(|(i, v)| TomlEdit::Set(i, v)),
        6 => (
            any::<Index>(),
            prop_oneof![
                Just(0.0),
                Just(-1.0),
                Just(1e-3),
                Just(1e3),
                Just(1e12),
                0.5f64..2.0,
            ]
        )
            .prop_map(|(i, f)| TomlEdit::Scale(i, f)),
        2 => any::<Index>().prop_map(TomlEdit::Remove),
        1 => (any::<Index>(), "[a-z_]{1,12}", hostile_values())
            .prop_map(|(i, k, v)| TomlEdit::AddKey(i, k, v)),
        1 => (any::<Index>(), 0usize..40).prop_map(|(i, n)| TomlEdit::ResizeArray(i, n)),
        1 => (any::<Index>(), any::<u8>()).prop_map(|(i, b)| TomlEdit::TextByte(i, b)),
        1 => any::<Index>().prop_map(TomlEdit::TextTruncate),
    ]
}

/// Every path to a value in `value`, parents before children.
fn paths(value: &Value, prefix: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    match value {
        Value::Table(table) => {
            for (key, child) in table {
                prefix.push(Step::Key(key.clone()));
                out.push(prefix.clone());
                paths(child, prefix, out);
                prefix.pop();
            }
        }
        Value::Array(items) => {
            for (i, child) in items.iter().enumerate() {
                prefix.push(Step::Item(i));
                out.push(prefix.clone());
                paths(child, prefix, out);
                prefix.pop();
            }
        }
        _ => {}
    }
}

fn at<'a>(root: &'a mut Value, path: &[Step]) -> Option<&'a mut Value> {
    let mut node = root;
    for step in path {
        node = match (node, step) {
            (Value::Table(t), Step::Key(k)) => t.get_mut(k)?,
            (Value::Array(a), Step::Item(i)) => a.get_mut(*i)?,
            _ => return None,
        };
    }
    Some(node)
}

fn edit_tree(root: &mut Value, edit: &TomlEdit) {
    let mut all = Vec::new();
    paths(root, &mut Vec::new(), &mut all);
    let pick = |i: &Index| (!all.is_empty()).then(|| all[i.index(all.len())].clone());
    match edit {
        TomlEdit::Set(i, value) => {
            if let Some(node) = pick(i).and_then(|p| at(root, &p)) {
                *node = value.clone();
            }
        }
        TomlEdit::Scale(i, factor) => match pick(i).and_then(|p| at(root, &p)) {
            Some(Value::Float(x)) => *x *= factor,
            Some(Value::Integer(n)) => *n = (*n as f64 * factor).round() as i64,
            _ => {}
        },
        TomlEdit::Remove(i) => {
            if let Some(mut path) = pick(i) {
                let last = path.pop();
                match (at(root, &path), last) {
                    (Some(Value::Table(t)), Some(Step::Key(k))) => {
                        t.remove(&k);
                    }
                    (Some(Value::Array(a)), Some(Step::Item(n))) if n < a.len() => {
                        a.remove(n);
                    }
                    _ => {}
                }
            }
        }
        TomlEdit::AddKey(i, key, value) => {
            // Into the picked table, or the top level when the pick is not a table.
            let path = pick(i).filter(|p| matches!(at(root, p), Some(Value::Table(_))));
            if let Some(Value::Table(t)) = at(root, &path.unwrap_or_default()) {
                t.insert(key.clone(), value.clone());
            }
        }
        TomlEdit::ResizeArray(i, n) => {
            if let Some(Value::Array(a)) = pick(i).and_then(|p| at(root, &p)) {
                if *n <= a.len() {
                    a.truncate(*n);
                } else if let Some(first) = a.first().cloned() {
                    a.resize(*n, first);
                }
            }
        }
        TomlEdit::TextByte(..) | TomlEdit::TextTruncate(_) => {}
    }
}

/// `seed` (a valid TOML document) with `edits` applied, as text. Tree edits come first, in
/// order; then the text edits. A seed that does not parse is only edited as text.
pub fn mutate(seed: &str, edits: &[TomlEdit]) -> String {
    let mut text = match seed.parse::<Table>() {
        Ok(table) => {
            let mut root = Value::Table(table);
            for edit in edits {
                edit_tree(&mut root, edit);
            }
            match root {
                Value::Table(t) => toml::to_string(&t).unwrap_or_else(|_| seed.to_string()),
                _ => seed.to_string(),
            }
        }
        Err(_) => seed.to_string(),
    };
    let mut bytes = std::mem::take(&mut text).into_bytes();
    for edit in edits {
        match edit {
            TomlEdit::TextByte(i, b) if !bytes.is_empty() => {
                let at = i.index(bytes.len());
                bytes[at] = *b;
            }
            TomlEdit::TextTruncate(i) => bytes.truncate(i.index(bytes.len() + 1)),
            _ => {}
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

/// Cases per property in CI, unless `PROPTEST_CASES` asks for another number.
pub fn budget(ci_cases: u32) -> ProptestConfig {
    let mut config = ProptestConfig::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        config.cases = ci_cases;
    }
    config.failure_persistence = None;
    config
}
