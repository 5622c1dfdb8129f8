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

/// `coupler check CASE | head -1`: the reader closes the pipe before the check has written its
/// lines; the check still succeeds and says nothing of a panic.
#[test]
fn a_check_piped_into_a_reader_that_quits_early_does_not_panic() {
    use std::process::{Command, Stdio};
    let case = workspace().join("cases/oscillator/case.toml");
    let mut child = Command::new(stack_tests::binary("coupler"))
        .args(["check", case.to_str().unwrap_or_default()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    drop(child.stdout.take());
    let run = child
        .wait_with_output()
        .unwrap_or_else(|e| panic!("coupler check did not end: {e}"));
    assert!(run.status.success(), "{}", stderr(&run));
    assert!(!stderr(&run).contains("panicked"), "{}", stderr(&run));
}

/// A case written for E-MPS switched to ISPH by `method = "isph"` alone passes the check, which
/// names its sound speed as unused and the longest time step ISPH would take instead (issue 12:
/// one key selects the method); `run` prints the same line before it starts.
#[test]
fn an_emps_case_switched_by_one_key_passes_the_check_and_names_its_unused_sound_speed() {
    let text = std::fs::read_to_string(workspace().join("cases/dam-break-tank/case.toml"))
        .unwrap_or_else(|e| panic!("{e}"))
        .replace("[fluid.tank]\n", "[fluid.tank]\nmethod = \"isph\"\n");
    assert!(text.contains("method = \"isph\"") && text.contains("sound_speed = 12.1"));
    let dir = std::env::temp_dir().join(format!("switched-case-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let case = dir.join("case.toml");
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let run = coupler(&["check", case.to_str().unwrap_or_default()]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    println!("{stdout}");
    assert!(run.status.success(), "{}", stderr(&run));
    assert!(
        stdout.contains("warning: fluid.tank: `sound_speed` = 12.1 m/s is not used: ISPH has no sound speed"),
        "{stdout}"
    );
    // The longest step ISPH accepts there: advective Courant 0.4 at u = 2√(gH), the dam-break
    // front's speed (Ritter 1892) for the 0.3 m column: 0.4 · 0.01 / (2√(9.8 · 0.3)) = 1.166e-3 s,
    // 2.3 times the case's acoustic 5e-4 s (the viscous term is off).
    assert!(
        stdout.contains("they allow time_step up to 1.166e-3 s, 2.3× the case's 0.0005 s"),
        "{stdout}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
