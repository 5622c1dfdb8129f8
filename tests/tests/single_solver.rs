//! A case with one participant and no coupling: `coupler run` starts only that solver, in its
//! standalone mode, and no coupling traffic happens (no recording, no ledger).

use stack_tests::{coupler_run, out_dir, stderr, workspace};
use std::path::Path;

/// Copies `cases/NAME/case.toml` into a test folder with `end_time` replaced.
fn short_case(name: &str, end_time: &str, dir: &Path) -> std::path::PathBuf {
    let text =
        std::fs::read_to_string(workspace().join("cases").join(name).join("case.toml")).unwrap_or_default();
    let start = text
        .find("\nend_time =")
        .unwrap_or_else(|| panic!("{name} has no end_time"));
    let end = text[start + 1..]
        .find('\n')
        .map(|i| start + 1 + i)
        .unwrap_or(text.len());
    let mut text = text;
    text.replace_range(start + 1..end, &format!("end_time = {end_time}"));
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap_or_default();
    // Relative paths in the case (load tables) are taken from its folder: copy its CSV files.
    for entry in std::fs::read_dir(workspace().join("cases").join(name))
        .into_iter()
        .flatten()
        .flatten()
    {
        if entry.path().extension().is_some_and(|e| e == "csv") {
            std::fs::copy(entry.path(), dir.join(entry.file_name())).unwrap_or_default();
        }
    }
    path
}

fn run_alone(name: &str, end_time: &str, solver: &str) -> std::path::PathBuf {
    let dir = out_dir(&format!("alone-{name}"));
    let case = short_case(name, end_time, &dir);
    let out = dir.join("out");
    let run = coupler_run(&case, &out);
    let err = stderr(&run);
    println!("{err}");
    assert!(run.status.success(), "{err}");
    assert!(err.contains(&format!("{solver} solver alone")), "{err}");
    assert!(
        !err.contains("started"),
        "no coupled participant is started: {err}"
    );
    assert!(
        !out.join("recording.rec").exists() && !out.join("ledger.csv").exists(),
        "no coupling traffic"
    );
    out
}

#[test]
fn a_structure_only_case_starts_only_the_structure_solver() {
    let out = run_alone("rigid-washout", "3.0", "structure-solver");
    let files: Vec<_> = walk(&out);
    assert!(
        files.iter().any(|f| f.ends_with(".csv")),
        "the solver's history is written: {files:?}"
    );
}

#[test]
fn a_fluid_only_case_starts_only_the_fluid_solver() {
    let out = run_alone("hydrostatic-tank", "0.02", "fluid-solver");
    let files: Vec<_> = walk(&out);
    assert!(
        files.iter().any(|f| f.ends_with(".vtu")),
        "the solver's frames are written: {files:?}"
    );
}

/// A fluid-only case's warning (here ISPH's unused sound speed) reaches the terminal once: the
/// solver running alone prints it, the coupler does not repeat it (it did until session 19).
#[test]
fn a_fluid_only_case_warns_once() {
    let dir = out_dir("alone-warns-once");
    let case = short_case("hydrostatic-tank", "0.005", &dir);
    let text = std::fs::read_to_string(&case).unwrap_or_default().replace(
        "[fluid.water]\n",
        "[fluid.water]\nmethod = \"isph\"\nsound_speed = 20.0\n",
    );
    assert!(text.contains("sound_speed = 20.0"));
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let run = coupler_run(&case, &dir.join("out"));
    let err = stderr(&run);
    println!("{err}");
    assert!(run.status.success(), "{err}");
    assert_eq!(
        err.matches("`sound_speed` = 20 m/s is not used").count(),
        1,
        "{err}"
    );
}

fn walk(dir: &Path) -> Vec<String> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let p = entry.path();
        if p.is_dir() {
            found.extend(walk(&p));
        } else {
            found.push(p.display().to_string());
        }
    }
    found
}
