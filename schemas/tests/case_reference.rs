//! The case-file reference (`docs/guide/case-reference.md`) against the parser: it is what the
//! case types generate, it names every key the shipped cases use, every key it names is accepted,
//! and every number says its unit.

use schemas::case::key_reference::{markdown, tables, Table, NAME};
use schemas::case::Case;
use std::path::{Path, PathBuf};

const REFERENCE: &str = "docs/guide/case-reference.md";

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

#[test]
fn the_committed_reference_is_the_generated_one() {
    let committed = std::fs::read_to_string(repo().join(REFERENCE)).unwrap_or_default();
    let generated = markdown();
    if committed != generated {
        let line = committed
            .lines()
            .zip(generated.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| committed.lines().count().min(generated.lines().count()));
        panic!(
            "{REFERENCE} differs from what the case types generate (first at line {}: {:?} against {:?}); \
             run `coupler reference > {REFERENCE}` (e.g. `cargo run --release -p coupler -- reference > {REFERENCE}`) \
             and commit it",
            line + 1,
            committed.lines().nth(line).unwrap_or("<end>"),
            generated.lines().nth(line).unwrap_or("<end>"),
        );
    }
}

/// The table at `path` (`fluid.NAME.isph`).
fn table<'a>(tables: &'a [Table], path: &str) -> &'a Table {
    tables
        .iter()
        .find(|t| t.path == path)
        .unwrap_or_else(|| panic!("the reference has no table `{path}`"))
}

fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// Collects the keys of `value` (the table at `path`) that the reference lacks, as `path.key`.
fn missing_keys(tables: &[Table], path: &str, value: &toml::Table, missing: &mut Vec<String>) {
    let t = table(tables, path);
    for (name, v) in value {
        let Some(key) = t.keys.iter().find(|k| &k.name == name) else {
            missing.push(join(path, name));
            continue;
        };
        let Some(sub) = &key.table else { continue };
        let named = *sub != join(path, name);
        match v {
            toml::Value::Table(entries) if named => {
                for entry in entries.values() {
                    if let toml::Value::Table(e) = entry {
                        missing_keys(tables, sub, e, missing);
                    }
                }
            }
            toml::Value::Table(e) => missing_keys(tables, sub, e, missing),
            toml::Value::Array(items) => {
                for item in items {
                    if let toml::Value::Table(e) = item {
                        missing_keys(tables, sub, e, missing);
                    }
                }
            }
            _ => {}
        }
    }
}

#[test]
fn every_key_of_every_shipped_case_is_in_the_reference() {
    let tables = tables();
    let mut files: Vec<PathBuf> = std::fs::read_dir(repo().join("cases"))
        .expect("cases/")
        .flatten()
        .flat_map(|d| std::fs::read_dir(d.path()).into_iter().flatten().flatten())
        .map(|f| f.path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 10, "too few case files found: {files:?}");
    let mut missing = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).expect("readable case file");
        let value: toml::Table = toml::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        let mut keys = Vec::new();
        missing_keys(&tables, "", &value, &mut keys);
        missing.extend(keys.into_iter().map(|k| format!("{}: {k}", file.display())));
    }
    assert!(
        missing.is_empty(),
        "keys of shipped cases that {REFERENCE} does not name:\n{}",
        missing.join("\n")
    );
}

/// A case text holding `key = 1` in the table at `path` (names as `x`, one table per array),
/// and nothing else.
fn case_with(tables: &[Table], path: &str, key: &str) -> String {
    let mut value = toml::Table::new();
    value.insert(key.to_string(), toml::Value::Integer(1));
    let mut value = toml::Value::Table(value);
    let mut at = path.to_string();
    while !at.is_empty() {
        let (parent, last) = at.rsplit_once('.').unwrap_or(("", &at));
        if tables.iter().any(|t| t.path == at && t.array) {
            value = toml::Value::Array(vec![value]);
        }
        let mut t = toml::Table::new();
        t.insert(if last == NAME { "x".into() } else { last.into() }, value);
        value = toml::Value::Table(t);
        at = parent.to_string();
    }
    toml::to_string(&value).expect("a TOML table")
}

fn parse_error(text: String) -> String {
    match Case::parse(Path::new("reference-test.toml"), text.clone()) {
        Ok(_) => String::new(),
        Err(e) => format!("{e}\n--- case:\n{text}"),
    }
}

#[test]
fn every_key_the_reference_names_is_accepted_and_a_made_up_one_is_refused() {
    let tables = tables();
    let keys: usize = tables.iter().map(|t| t.keys.len()).sum();
    assert!(keys > 150, "only {keys} keys in the reference");
    for t in &tables {
        for k in &t.keys {
            let error = parse_error(case_with(&tables, &t.path, &k.name));
            assert!(
                !error.contains("unknown field"),
                "{REFERENCE} names `{}` but the parser refuses it: {error}",
                join(&t.path, &k.name)
            );
        }
        let error = parse_error(case_with(&tables, &t.path, "made_up_key"));
        assert!(
            error.contains("unknown field `made_up_key`"),
            "a made-up key in `{}` is not refused as unknown: {error}",
            t.path
        );
    }
}

#[test]
fn every_number_says_its_unit() {
    let unitless: Vec<String> = tables()
        .iter()
        .flat_map(|t| {
            t.keys
                .iter()
                .filter(|k| k.is_number() && k.unit.is_empty())
                .map(|k| join(&t.path, &k.name))
        })
        .collect();
    assert!(
        unitless.is_empty(),
        "keys that hold numbers but whose doc comment names no unit (`[m]`, `[s]`, `[–]` … of \
         schemas::case::key_reference::UNITS): {unitless:?}"
    );
}
