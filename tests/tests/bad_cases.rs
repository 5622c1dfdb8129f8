//! Wrong case files: each is refused with its own message naming the file, the key and what is
//! allowed, with exit code 2, and no participant process is started.

use stack_tests::{coupler, coupler_run, out_dir, stderr, workspace};

/// (name, text to find in the oscillator case, replacement, fragments the error must contain).
const BAD: &[(&str, &str, &str, &[&str])] = &[
    (
        "missing-key",
        "end_time = 1.0\n",
        "",
        &["missing field `end_time`"],
    ),
    (
        "unknown-key",
        "end_time = 1.0\n",
        "end_time = 1.0\ncolour = \"red\"\n",
        &["unknown field `colour`", "case"],
    ),
    (
        "negative-mass",
        "mass = 1.0\nposition = [0.0",
        "mass = -1.0\nposition = [0.0",
        &["structure.mass-left", "mass", "-1"],
    ),
    (
        "zero-max-step",
        "max_step = 2.5e-4\n\n[[structure.mass-left",
        "max_step = 0.0\n\n[[structure.mass-left",
        &["structure.mass-left.max_step", "> 0"],
    ),
    (
        "window-longer-than-run",
        "window = 0.01",
        "window = 2.0",
        &["coupling.window", "longer than case.end_time"],
    ),
    (
        "unknown-participant-in-order",
        "order = [\"mass-left\", \"mass-right\"]",
        "order = [\"mass-left\", \"mass-middle\"]",
        &["coupling.order[1]", "`mass-middle` is not a participant"],
    ),
    (
        "unknown-point",
        "a = \"mass-left/m1\"",
        "a = \"mass-left/m9\"",
        &["coupling.spring[0].a", "no point mass `m9`"],
    ),
    (
        "zero-stiffness",
        "stiffness = 157.91367041742973",
        "stiffness = 0.0",
        &["coupling.spring[0].stiffness", "> 0"],
    ),
    (
        "unknown-scheme",
        "scheme = \"implicit\"",
        "scheme = \"sideways\"",
        &["coupling", "unknown variant `sideways`"],
    ),
    (
        "zero-samples",
        "samples = 4 ",
        "samples = 0 ",
        &["coupling.samples", "1 … 64"],
    ),
    (
        "tolerance-too-large",
        "tolerance = 1e-10",
        "tolerance = 2.0",
        &["coupling.tolerance", "[1e-15, 0.5]"],
    ),
    (
        "bad-participant-name",
        "[coupling]\n",
        "[structure.Mass_Left]\nmax_step = 1e-3\n\n[coupling]\n",
        &["structure.Mass_Left", "a–z, 0–9 and `-`"],
    ),
    (
        "executable-for-nobody",
        "end_time = 1.0\n",
        "end_time = 1.0\nexecutables = { mass-middle = \"x\" }\n",
        &["case.executables.mass-middle", "names no participant"],
    ),
    (
        "spring-within-one-participant",
        "b = \"mass-right/m2\"",
        "b = \"mass-left/m1\"",
        &["coupling.spring[0]", "both ends are in participant `mass-left`"],
    ),
    ("not-toml", "[case]\n", "[case\n", &["case.toml"]),
];

#[test]
fn each_bad_case_gets_its_own_clear_error_and_starts_nothing() {
    let template =
        std::fs::read_to_string(workspace().join("cases/oscillator/case.toml")).unwrap_or_default();
    let root = out_dir("bad-cases");
    let mut messages = Vec::new();
    for (name, find, replace, fragments) in BAD {
        assert!(template.contains(find), "{name}: the template has no `{find}`");
        let dir = root.join(name);
        std::fs::create_dir_all(&dir).unwrap_or_default();
        let case = dir.join("case.toml");
        std::fs::write(&case, template.replacen(find, replace, 1)).unwrap_or_default();
        let out = dir.join("out");
        let run = coupler_run(&case, &out);
        let err = stderr(&run);
        assert_eq!(
            run.status.code(),
            Some(2),
            "{name}: exit code 2 for a bad case, got {:?}: {err}",
            run.status
        );
        assert!(
            err.contains(case.to_str().unwrap_or_default()),
            "{name}: the error names the file: {err}"
        );
        for f in *fragments {
            assert!(err.contains(f), "{name}: the error should contain `{f}`: {err}");
        }
        assert!(
            !err.contains("started"),
            "{name}: no participant may start: {err}"
        );
        assert!(!out.exists(), "{name}: nothing may be written");
        messages.push(err.trim().to_string());
    }
    let mut unique = messages.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), messages.len(), "every bad case has its own message");
    println!("{}", messages.join("\n"));
}

#[test]
fn check_lists_participants_without_starting_them() {
    let case = workspace().join("cases/oscillator/case.toml");
    let run = coupler(&["check", case.to_str().unwrap_or_default()]);
    assert!(run.status.success(), "{}", stderr(&run));
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(text.contains("participant mass-left: structure-solver"), "{text}");
    assert!(
        text.contains("participant mass-right: structure-solver"),
        "{text}"
    );
}
