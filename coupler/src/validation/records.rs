//! The committed records (docs/validation/records/<id>.toml) and how freshly written ones
//! (out/validation/<id>.toml) join them.

use schemas::validation::{read, write, Record};
use std::path::Path;

/// Every `*.toml` record in `dir`, sorted by id; an unreadable or malformed file is an error
/// naming it, and so is a record whose id is not its file's name.
pub fn load(dir: &Path) -> Result<Vec<Record>, String> {
    let entries = std::fs::read_dir(dir).map_err(|e| format!("cannot read {}: {e}", dir.display()))?;
    let mut records = Vec::new();
    for entry in entries {
        let path = entry
            .map_err(|e| format!("cannot read {}: {e}", dir.display()))?
            .path();
        if path.extension().is_none_or(|ext| ext != "toml") {
            continue;
        }
        let record = read(&path)?;
        if path.file_stem().is_none_or(|stem| *stem != *record.id) {
            return Err(format!(
                "{}: the record's id is `{}`: name the file {}.toml",
                path.display(),
                record.id,
                record.id
            ));
        }
        records.push(record);
    }
    records.sort_by(|a, b| a.id.cmp(&b.id));
    Ok(records)
}

/// What [`collect`] did.
#[derive(Debug, Default, PartialEq)]
pub struct Collected {
    /// Ids that were not committed before.
    pub added: Vec<String>,
    /// Ids whose committed record was replaced by a fresh one.
    pub replaced: Vec<String>,
    /// Ids whose fresh record is older than the committed one (left as committed).
    pub kept: Vec<String>,
}

/// Copies every record of `fresh` into `committed`, replacing a committed record of the same id
/// unless that one is newer (a later `date`).
pub fn collect(fresh: &Path, committed: &Path) -> Result<Collected, String> {
    let mut done = Collected::default();
    for record in load(fresh)? {
        let path = committed.join(format!("{}.toml", record.id));
        let old = path.exists().then(|| read(&path)).transpose()?;
        match old {
            Some(old) if old.date > record.date => {
                done.kept.push(record.id);
                continue;
            }
            Some(_) => done.replaced.push(record.id.clone()),
            None => done.added.push(record.id.clone()),
        }
        write(committed, &record).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    }
    Ok(done)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(id: &str, date: &str, value: f64) -> Record {
        Record {
            id: id.into(),
            date: date.into(),
            value,
            ..Default::default()
        }
    }

    #[test]
    fn a_fresh_record_replaces_an_older_one_of_its_id_and_joins_the_others() {
        let dir = std::env::temp_dir().join(format!("validation-collect-{}", std::process::id()));
        let (fresh, committed) = (dir.join("fresh"), dir.join("committed"));
        let write_all = |dir: &Path, records: &[Record]| {
            for r in records {
                write(dir, r).unwrap_or_else(|e| panic!("{e}"));
            }
        };
        write_all(
            &committed,
            &[record("a", "2026-11-01", 1.0), record("c", "2026-12-01", 3.0)],
        );
        write_all(
            &fresh,
            &[
                record("a", "2026-11-28", 1.5),
                record("b", "2026-11-28", 2.0),
                record("c", "2026-11-28", 3.5),
            ],
        );
        let done = collect(&fresh, &committed).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            done,
            Collected {
                added: vec!["b".into()],
                replaced: vec!["a".into()],
                kept: vec!["c".into()],
            }
        );
        let values: Vec<f64> = load(&committed)
            .unwrap_or_else(|e| panic!("{e}"))
            .iter()
            .map(|r| r.value)
            .collect();
        assert_eq!(values, [1.5, 2.0, 3.0]);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
