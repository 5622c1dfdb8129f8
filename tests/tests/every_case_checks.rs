//! Every case file shipped in `cases/` passes `coupler check` (the case check every run does
//! first), so a case folder that a README tells a user to run cannot rot unnoticed.

use stack_tests::{coupler, stderr, workspace};

#[test]
fn every_shipped_case_file_passes_the_check() {
    let mut checked = 0;
    let mut cases: Vec<_> = std::fs::read_dir(workspace().join("cases"))
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .collect();
    cases.sort();
    for folder in cases {
        let mut files: Vec<_> = std::fs::read_dir(&folder)
            .into_iter()
            .flatten()
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .collect();
        files.sort();
        for file in files {
            let run = coupler(&["check", file.to_str().unwrap_or_default()]);
            assert!(run.status.success(), "{}: {}", file.display(), stderr(&run));
            checked += 1;
        }
    }
    println!("{checked} case files checked");
    assert!(checked >= 15, "only {checked} case files found under cases/");
}
