//! `coupler validation`: docs/validation.md generated from data, never edited by hand.
//!
//! Validation tests write one [`schemas::validation::Record`] each to `out/validation/<id>.toml`;
//! `--collect` merges them into the committed `docs/validation/records/` ([`records`]). The page
//! is rendered from those records, grouped by capability as `docs/validation/groups.toml` says
//! ([`groups`]), with the latest `coupler report` fragments (`docs/validation/report-*.md`, written
//! by `coupler report --docs`) appended ([`page`]); the README's summary table between its marker
//! comments is rewritten too ([`summary`]). A test checks that the committed page is the rendered
//! one and that every test a row names exists ([`sources`]).

pub mod cells;
pub mod groups;
pub mod layout;
pub mod page;
pub mod records;
pub mod sources;
pub mod summary;

use crate::error::CouplerError;
use layout::Layout;
use std::path::{Path, PathBuf};

/// What `coupler validation` was asked to do.
pub struct ValidationOptions {
    /// The workspace root (docs/ and README.md under it).
    pub root: PathBuf,
    /// A folder of freshly written records to merge first (e.g. out/validation).
    pub collect: Option<PathBuf>,
}

/// Collects (when asked), renders docs/validation.md and rewrites the README's summary.
pub fn validation(opts: &ValidationOptions) -> Result<(), CouplerError> {
    let layout = Layout::new(&opts.root);
    let io = CouplerError::Io;
    if let Some(fresh) = &opts.collect {
        let done = records::collect(fresh, &layout.records()).map_err(io)?;
        crate::say!(
            "{}: {} added, {} replaced{}",
            layout.records().display(),
            done.added.len(),
            done.replaced.len(),
            match done.kept.is_empty() {
                true => String::new(),
                false => format!(
                    "; kept the committed, newer {} (the fresh ones are older)",
                    done.kept.join(", ")
                ),
            }
        );
    }
    let rendered = page::render(&layout).map_err(io)?;
    schemas::atomic_file::write(&layout.page(), &rendered.page)
        .map_err(|e| CouplerError::Io(format!("cannot write {}: {e}", layout.page().display())))?;
    let rows: usize = rendered.groups.iter().map(|(_, r)| r.len()).sum::<usize>() + rendered.orphans.len();
    crate::say!("{}: {rows} rows", layout.page().display());
    if !rendered.orphans.is_empty() {
        crate::say!(
            "warning: no group of {} names {}: they are shown under \"Other\"",
            layout.groups().display(),
            rendered.orphans.join(", ")
        );
    }
    let all = records::load(&layout.records()).map_err(io)?;
    for missing in sources::missing_tests(&layout.root, &all) {
        crate::say!("warning: the row's test is missing: {missing}");
    }
    update_readme(
        &layout.readme(),
        &summary::table(&rendered.groups, "docs/validation.md"),
    )
}

/// Puts `table` between the README's summary markers; a README without them is left alone.
fn update_readme(readme: &Path, table: &str) -> Result<(), CouplerError> {
    let text = std::fs::read_to_string(readme)
        .map_err(|e| CouplerError::Io(format!("cannot read {}: {e}", readme.display())))?;
    match summary::replace_between(&text, summary::MARKERS, table) {
        Some(new) if new == text => crate::say!("{}: summary unchanged", readme.display()),
        Some(new) => {
            schemas::atomic_file::write(readme, new)
                .map_err(|e| CouplerError::Io(format!("cannot write {}: {e}", readme.display())))?;
            crate::say!("{}: summary updated", readme.display());
        }
        None => crate::say!(
            "{} has no `{}` … `{}` markers: its summary was left alone (add them where the table goes)",
            readme.display(),
            summary::MARKERS.0,
            summary::MARKERS.1
        ),
    }
    Ok(())
}
