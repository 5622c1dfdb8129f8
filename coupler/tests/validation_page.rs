//! docs/validation.md is generated: the committed page must be what `coupler validation` renders
//! from the committed records, every record must sit in a capability group, and every test a row
//! names must exist. The README's summary, once it has its markers, must be the rendered one too.

use coupler::validation::layout::Layout;
use coupler::validation::{page, records, sources, summary};
use std::path::Path;

fn layout() -> Layout {
    Layout::new(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .parent()
            .unwrap_or(Path::new("..")),
    )
}

#[test]
fn the_committed_page_is_the_rendered_one() {
    let layout = layout();
    let rendered = page::render(&layout).unwrap_or_else(|e| panic!("{e}"));
    let committed = std::fs::read_to_string(layout.page()).unwrap_or_default();
    assert!(
        committed == rendered.page,
        "docs/validation.md is not what the committed data renders: run `coupler validation` \
         (`cargo run --release -p coupler -- validation`) and commit the page; never edit it by hand"
    );
    assert!(
        rendered.orphans.is_empty(),
        "no group of docs/validation/groups.toml names {:?}: add them to a group",
        rendered.orphans
    );
}

#[test]
fn every_test_a_row_names_exists() {
    let layout = layout();
    let records = records::load(&layout.records()).unwrap_or_else(|e| panic!("{e}"));
    let missing = sources::missing_tests(&layout.root, &records);
    assert!(
        missing.is_empty(),
        "rows whose test is gone (rename the record's source, or remove its file from \
         docs/validation/records/):\n{}",
        missing.join("\n")
    );
}

#[test]
fn the_readme_summary_is_the_rendered_one_where_it_has_its_markers() {
    let layout = layout();
    let readme = std::fs::read_to_string(layout.readme()).unwrap_or_default();
    let rendered = page::render(&layout).unwrap_or_else(|e| panic!("{e}"));
    let table = summary::table(&rendered.groups, "docs/validation.md");
    if let Some(expected) = summary::replace_between(&readme, summary::MARKERS, &table) {
        assert!(
            expected == readme,
            "README.md's validation summary is out of date: run `coupler validation`"
        );
    }
}
