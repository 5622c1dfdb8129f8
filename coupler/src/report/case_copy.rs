//! A case with changed settings, written as a user would write it: a folder holding the changed
//! `case.toml` and links to everything else in the case's folder (data files, load tables,
//! solver executables named by relative paths), so relative paths keep working.

use schemas::case::report::{apply_settings, Settings};
use schemas::case::Case;
use std::path::{Path, PathBuf};

/// Writes `case` with `settings` applied to `dir/case.toml` and links the case folder's other
/// entries into `dir`; returns the new case file.
pub fn write_changed_case(case: &Case, settings: &Settings, dir: &Path) -> Result<PathBuf, String> {
    let text = apply_settings(&case.text, settings).map_err(|m| format!("{}: {m}", case.path.display()))?;
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let folder = match case.dir() {
        d if d.as_os_str().is_empty() => PathBuf::from("."),
        d => d,
    };
    let source = std::fs::canonicalize(&folder)
        .map_err(|e| format!("cannot resolve the folder of {}: {e}", case.path.display()))?;
    let own = case.path.file_name().map(|n| n.to_os_string());
    if let Ok(entries) = std::fs::read_dir(&source) {
        for entry in entries.flatten() {
            let name = entry.file_name();
            if Some(&name) == own.as_ref() || name == "case.toml" {
                continue;
            }
            std::os::unix::fs::symlink(entry.path(), dir.join(&name)).map_err(|e| {
                format!(
                    "cannot link {} into {}: {e}",
                    entry.path().display(),
                    dir.display()
                )
            })?;
        }
    }
    let path = dir.join("case.toml");
    std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok(path)
}
