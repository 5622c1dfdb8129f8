//! Settings that change the answer without a word (issue 41, item 3) get a warning saying what
//! they do: sub-members longer than the fluid's spacing, a `section_axis` along the member, and a
//! frame that nothing holds. The shipped prism case gets none.

use schemas::case::Case;
use std::path::PathBuf;

fn prism(edit: impl Fn(String) -> String) -> Vec<String> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../cases/prism-dam-break/case.toml");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let case = Case::parse(&path, edit(text)).unwrap_or_else(|e| panic!("{e}"));
    case.warnings()
}

#[test]
fn the_shipped_prism_case_runs_without_a_warning() {
    let warnings = prism(|t| t);
    assert!(warnings.is_empty(), "{warnings:?}");
}

#[test]
fn long_sub_members_a_section_axis_along_the_member_and_a_free_frame_are_named() {
    let long = prism(|t| {
        t.replace(
            "section_axis = [1.0, 0.0, 0.0]",
            "section_axis = [1.0, 0.0, 0.0]\nsub_member_length = 0.04",
        )
    });
    assert!(
        long.iter().any(
            |w| w.starts_with("coupling.drag[0]: `sub_member_length` = 0.04 m") && w.contains("loses drag")
        ),
        "{long:?}"
    );
    // the default (the spacing) and one spacing and a half are quiet
    assert!(prism(|t| t.replace(
        "section_axis = [1.0, 0.0, 0.0]",
        "section_axis = [1.0, 0.0, 0.0]\nsub_member_length = 0.0075"
    ))
    .is_empty());

    let along = prism(|t| {
        t.replace(
            "section_axis = [1.0, 0.0, 0.0]",
            "section_axis = [0.0, 0.02, 1.0]",
        )
    });
    assert!(
        along
            .iter()
            .any(|w| w.contains("`section_axis`") && w.contains("member(s) [0]") && w.contains("taken as 0")),
        "{along:?}"
    );

    let free = prism(|t| {
        t.replace("[[structure.prism.frame.support]]\nnode = 1\nfixed = [\"x\", \"y\", \"z\", \"rx\", \"ry\", \"rz\"]\n", "")
    });
    assert!(
        free.iter()
            .any(|w| w.starts_with("structure.prism.frame: no [[support]]") && w.contains("falls freely")),
        "{free:?}"
    );
    for w in long.iter().chain(&along).chain(&free) {
        println!("warning: {w}");
    }
}
