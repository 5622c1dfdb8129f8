//! Every row whose source names a test must point at a test that exists; a test CI skips
//! (`#[ignore]`) is named as one.

use super::cells::test_source;
use schemas::validation::Record;
use std::collections::HashSet;
use std::path::Path;

/// Where `text` defines `fn name` (the byte offset of `fn`).
fn definition(text: &str, name: &str) -> Option<usize> {
    text.match_indices(&format!("fn {name}")).find_map(|(i, m)| {
        let after = text[i + m.len()..].chars().next();
        after
            .is_some_and(|c| c == '(' || c == '<' || c.is_whitespace())
            .then_some(i)
    })
}

/// The records whose source names a test `file::name` where `root/file` is missing or holds no
/// `fn name`, each with why.
pub fn missing_tests(root: &Path, records: &[Record]) -> Vec<String> {
    records
        .iter()
        .filter_map(|r| {
            let (file, name) = test_source(&r.source)?;
            let text = match std::fs::read_to_string(root.join(file)) {
                Ok(text) => text,
                Err(e) => return Some(format!("{}: {file}: {e}", r.id)),
            };
            definition(&text, name)
                .is_none()
                .then(|| format!("{}: {file} has no `fn {name}`", r.id))
        })
        .collect()
}

/// The ids of the records whose source test carries `#[ignore]` among the attributes and doc
/// comments just above its `fn` (CI does not run it; `--ignored` does).
pub fn ignored_tests(root: &Path, records: &[Record]) -> HashSet<String> {
    records
        .iter()
        .filter(|r| {
            let Some((file, name)) = test_source(&r.source) else {
                return false;
            };
            let Ok(text) = std::fs::read_to_string(root.join(file)) else {
                return false;
            };
            definition(&text, name).is_some_and(|at| {
                text[..at]
                    .lines()
                    .rev()
                    .map(str::trim)
                    .take_while(|l| l.starts_with("#[") || l.starts_with("///") || l.starts_with("//"))
                    .any(|l| l.starts_with("#[ignore"))
            })
        })
        .map(|r| r.id.clone())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_renamed_test_is_found_missing() {
        let dir = std::env::temp_dir().join(format!("validation-sources-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("x/tests")).unwrap_or_else(|e| panic!("{e}"));
        std::fs::write(dir.join("x/tests/a.rs"), "#[test]\nfn front_follows() {}\n")
            .unwrap_or_else(|e| panic!("{e}"));
        let record = |id: &str, source: &str| Record {
            id: id.into(),
            source: source.into(),
            ..Default::default()
        };
        let records = [
            record("ok", "x/tests/a.rs::front_follows"),
            record("prefix", "x/tests/a.rs::front"),
            record("gone", "x/tests/b.rs::front_follows"),
            record("one-off", "fluid-solver run cases/x/case.toml"),
        ];
        let missing = missing_tests(&dir, &records);
        assert_eq!(missing.len(), 2, "{missing:?}");
        assert!(missing[0].starts_with("prefix: x/tests/a.rs has no `fn front`"));
        assert!(missing[1].starts_with("gone: x/tests/b.rs"));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_test_behind_ignore_is_known_as_one() {
        let dir = std::env::temp_dir().join(format!("validation-ignored-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("x/tests")).unwrap_or_else(|e| panic!("{e}"));
        let text =
            "#[test]\nfn runs() {}\n\n/// Long.\n#[test]\n#[ignore = \"long\"]\n/// More.\nfn skipped() {}\n";
        std::fs::write(dir.join("x/tests/a.rs"), text).unwrap_or_else(|e| panic!("{e}"));
        let record = |id: &str, source: &str| Record {
            id: id.into(),
            source: source.into(),
            ..Default::default()
        };
        let records = [
            record("ci", "x/tests/a.rs::runs"),
            record("ignored", "x/tests/a.rs::skipped"),
            record("one-off", "fluid-solver run cases/x/case.toml"),
        ];
        let ignored = ignored_tests(&dir, &records);
        assert_eq!(ignored, HashSet::from(["ignored".to_string()]));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
