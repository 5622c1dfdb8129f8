//! Tests of `schemas::case::inputs`.

use schemas::case::inputs::*;
use schemas::case::Case;
use std::path::Path;

const CASE: &str = "[case]\nname = \"m\"\nend_time = 1.0\n\n[structure.s]\nmax_step = 0.01\n\n\
                    [[structure.s.point_mass]]\nname = \"m\"\nmass = 2.0\nposition = [0, 0, 0]\n";

fn hashes(text: &str) -> Vec<(String, u64)> {
    Case::parse(Path::new("case.toml"), text.to_string())
        .unwrap_or_else(|e| panic!("{e}"))
        .input_hashes()
}

#[test]
fn comments_layout_and_the_end_time_leave_the_settings_hash_alone() {
    let before = hashes(CASE);
    let commented = format!(
        "# a note\n{}",
        CASE.replace("mass = 2.0", "mass   =   2.0   # kg")
    );
    assert_eq!(hashes(&commented), before, "comments and layout");
    let reordered = CASE.replace("name = \"m\"\nmass = 2.0", "mass = 2.0\nname = \"m\"");
    assert_ne!(reordered, CASE);
    assert_eq!(hashes(&reordered), before, "the order of keys in a table");
    assert_eq!(
        hashes(&CASE.replace("end_time = 1.0", "end_time = 3.5")),
        before,
        "case.end_time"
    );
}

#[test]
fn a_changed_value_changes_the_settings_hash() {
    let before = hashes(CASE);
    let heavier = hashes(&CASE.replace("mass = 2.0", "mass = 2.5"));
    assert_eq!(heavier[0].0, SETTINGS);
    assert_ne!(heavier[0].1, before[0].1);
    let renamed = hashes(&CASE.replace("name = \"m\"\nend", "name = \"n\"\nend"));
    assert_ne!(renamed[0].1, before[0].1, "the rest of [case] still counts");
}
