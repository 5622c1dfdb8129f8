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

/// ISPH steps landing on times closer than its step are all short steps, each removing only its
/// share of the divergence (`isph_landing_warning`): probes, outputs and coupling exchanges
/// closer than ISPH's time_step are named; at or beyond it, and with E-MPS, nothing is said.
#[test]
fn intervals_shorter_than_isphs_step_are_named() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../cases/dam-break-obstacle/case-ci.toml");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let warnings = |edit: &dyn Fn(&str) -> String| {
        let case = Case::parse(&path, edit(&text)).unwrap_or_else(|e| panic!("{e}"));
        case.warnings()
    };
    let isph_at = |dt: &str| {
        let dt = dt.to_string();
        move |t: &str| {
            t.replace(
                "time_step = 0.0012",
                &format!("method = \"isph\"\ntime_step = {dt}"),
            )
        }
    };
    let long = warnings(&isph_at("0.0034"));
    assert!(
        long.iter().any(|w| w.starts_with(
            "fluid.tank: `probe_interval` = 0.0012 s is shorter than ISPH's time_step = 0.0034 s"
        ) && w.contains("set time_step ≤ 0.0012 s")),
        "{long:?}"
    );
    assert!(!long.iter().any(|w| w.contains("`output_interval`")), "{long:?}");
    let quiet = |w: &[String]| !w.iter().any(|w| w.contains("shorter than ISPH's time_step"));
    assert!(quiet(&warnings(&isph_at("0.0012"))));
    assert!(
        quiet(&warnings(&|t: &str| t.to_string())),
        "E-MPS lands on probes at no cost"
    );

    // the prism's coupling exchanges every 2e-4 s, its fluid switched to ISPH at 4e-4 s
    let coupled = prism(|t| t.replacen("time_step = 2.0e-4", "method = \"isph\"\ntime_step = 4.0e-4", 1));
    assert!(
        coupled.iter().any(|w| w.starts_with(
            "fluid.water: `coupling.window` = 0.0002 s is shorter than ISPH's time_step = 0.0004 s"
        )),
        "{coupled:?}"
    );
}
