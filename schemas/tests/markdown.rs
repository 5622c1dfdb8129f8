//! Tests of `schemas::markdown`.

use schemas::markdown::{github_anchor, table_cell};

#[test]
fn a_cell_is_one_line_with_its_bars_escaped() {
    assert_eq!(table_cell("a |b|\n  c"), "a \\|b\\| c");
}

#[test]
fn anchors_are_githubs() {
    assert_eq!(github_anchor("E-MPS fluid"), "e-mps-fluid");
    assert_eq!(github_anchor("Structure: rigid bodies"), "structure-rigid-bodies");
    assert_eq!(github_anchor("Frames (ASI-Gauss)"), "frames-asi-gauss");
    assert_eq!(github_anchor("`[[fluid.NAME.block]]`"), "fluidnameblock");
}
