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
        "participant-twice-in-order",
        "order = [\"mass-left\", \"mass-right\"]",
        "order = [\"mass-left\", \"mass-left\"]",
        &["coupling.order[1]", "`mass-left` is listed twice"],
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

/// `check` and `run` of `case`: both exit 2 with every fragment in the message, and `run`
/// starts nothing and writes nothing.
fn refused_by_check_and_run(case: &std::path::Path, fragments: &[&str]) -> String {
    let check = coupler(&["check", case.to_str().unwrap_or_default()]);
    let out = case.with_file_name("out");
    let run = coupler_run(case, &out);
    for (what, result) in [("check", &check), ("run", &run)] {
        let err = stderr(result);
        assert_eq!(
            result.status.code(),
            Some(2),
            "{what}: exit 2, got {:?}: {err}",
            result.status
        );
        for f in fragments {
            assert!(err.contains(f), "{what}: the error should contain `{f}`: {err}");
        }
        assert!(!err.contains("started"), "{what}: nothing may start: {err}");
    }
    assert!(!out.exists(), "run must write nothing");
    stderr(&run)
}

/// The rigid-washout case (a load from `lift.csv`) in `dir`, with `lift` as its table.
fn washout_with_table(dir: &std::path::Path, table_name: &str, lift: Option<&str>) -> std::path::PathBuf {
    let text = std::fs::read_to_string(workspace().join("cases/rigid-washout/case.toml")).unwrap_or_default();
    std::fs::create_dir_all(dir).unwrap_or_default();
    let case = dir.join("case.toml");
    std::fs::write(
        &case,
        text.replace("table = \"lift.csv\"", &format!("table = \"{table_name}\"")),
    )
    .unwrap_or_default();
    if let Some(lift) = lift {
        std::fs::write(dir.join(table_name), lift).unwrap_or_default();
    }
    case
}

#[test]
fn a_missing_or_malformed_load_table_is_refused_by_check_and_run_with_its_line() {
    let root = out_dir("bad-tables");
    let missing = washout_with_table(&root.join("missing"), "no-such-lift.csv", None);
    refused_by_check_and_run(
        &missing,
        &[
            "structure.bridge.load[0].table",
            "no-such-lift.csv",
            "cannot read the load table",
        ],
    );
    let good = std::fs::read_to_string(workspace().join("cases/rigid-washout/lift.csv")).unwrap_or_default();
    let short_row = good.replacen(
        "2.0,4.0e8,0.0,8.0e8,0.0,0.0,0.0",
        "2.0,4.0e8,0.0,8.0e8,0.0,0.0",
        1,
    );
    assert_ne!(short_row, good);
    let line = good
        .lines()
        .position(|l| l.starts_with("2.0,"))
        .map(|i| i + 1)
        .unwrap_or_default();
    let malformed = washout_with_table(&root.join("short-row"), "lift.csv", Some(&short_row));
    refused_by_check_and_run(
        &malformed,
        &["lift.csv", &format!("line {line}"), "expected 7 columns", "got 6"],
    );
}

#[test]
fn toml_errors_give_line_column_and_the_line_and_an_empty_file_says_it_is_empty() {
    let root = out_dir("bad-toml");
    let template =
        std::fs::read_to_string(workspace().join("cases/oscillator/case.toml")).unwrap_or_default();
    let write = |name: &str, text: &str| {
        let dir = root.join(name);
        std::fs::create_dir_all(&dir).unwrap_or_default();
        let case = dir.join("case.toml");
        std::fs::write(&case, text).unwrap_or_default();
        case
    };
    let line_of = |text: &str, needle: &str| {
        text.lines()
            .position(|l| l.contains(needle))
            .map(|i| i + 1)
            .unwrap_or(0)
    };

    let text = template.replacen("end_time = 1.0", "end_time = 1.0.0", 1);
    let err = refused_by_check_and_run(
        &write("float", &text),
        &["invalid float", "column 15", "| end_time = 1.0.0"],
    );
    assert!(
        err.contains(&format!("line {}, column", line_of(&text, "end_time = 1.0.0"))),
        "{err}"
    );

    let text = template.replacen("end_time = 1.0", "end_time", 1);
    let err = refused_by_check_and_run(
        &write("no-value", &text),
        &["`case.end_time`", "expected `=`", "| end_time"],
    );
    assert!(
        err.contains(&format!("line {}, column 9", line_of(&text, "end_time"))),
        "{err}"
    );

    let text = format!("{template}\n[case]\nname = \"again\"\n");
    let err = refused_by_check_and_run(&write("twice", &text), &["duplicate key", "| [case]"]);
    assert!(
        err.contains(&format!("line {}, column 2", text.lines().count() - 1)),
        "{err}"
    );

    refused_by_check_and_run(&write("empty", "\n  \n"), &["the case file is empty"]);
}

#[test]
fn absurd_sizes_are_refused_before_the_run_with_the_estimate() {
    let root = out_dir("bad-sizes");
    let dir = root.join("tiny-window");
    std::fs::create_dir_all(&dir).unwrap_or_default();
    let case = stack_tests::oscillator_case(&dir, &[("window", "1e-12")]);
    refused_by_check_and_run(
        &case,
        &["1.0e12 windows", "PB of output", "above --max-output 20.0 GB"],
    );

    let dir = root.join("end-1e300");
    std::fs::create_dir_all(&dir).unwrap_or_default();
    let case = stack_tests::oscillator_case(&dir, &[("end_time", "1e300")]);
    let err = refused_by_check_and_run(&case, &["1.0e302 windows", "e305 B of output"]);
    assert!(!err.contains("000000000000"), "no 300-digit numbers: {err}");

    // A run that fits is told its estimate; a limit below it refuses it, with the estimate.
    let dir = root.join("limit");
    std::fs::create_dir_all(&dir).unwrap_or_default();
    let case = stack_tests::oscillator_case(&dir, &[]);
    let out = dir.join("out");
    let run = coupler(&[
        "run",
        case.to_str().unwrap_or_default(),
        "--out",
        out.to_str().unwrap_or_default(),
        "--max-output",
        "10k",
    ]);
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(
        err.contains("100 windows; about") && err.contains("above --max-output 10.0 kB"),
        "{err}"
    );
    assert!(!out.exists());
    let run = coupler_run(&case, &out);
    let err = stderr(&run);
    assert!(run.status.success(), "{err}");
    assert!(err.contains("estimate: 100 windows; about"), "{err}");
    assert!(
        err.contains(&format!("output: {}, ", out.display())) && err.contains(" kB ("),
        "the size written: {err}"
    );
}

#[test]
fn an_output_folder_in_use_or_holding_an_earlier_run_is_refused_and_overwrite_clears_it() {
    let dir = out_dir("out-folder");
    let case = stack_tests::oscillator_case(&dir, &[]);
    let out = dir.join("out");
    let first = coupler_run(&case, &out);
    assert!(first.status.success(), "{}", stderr(&first));
    std::fs::write(out.join("stale-frame.vtu"), "from an older run").unwrap_or_default();

    let again = coupler_run(&case, &out);
    let err = stderr(&again);
    assert_eq!(again.status.code(), Some(2), "{err}");
    assert!(
        err.contains("already holds") && err.contains("--overwrite"),
        "{err}"
    );
    assert!(
        out.join("stale-frame.vtu").exists(),
        "a refused run deletes nothing"
    );

    // A run still going on holds the folder: simulated by holding its lock as a run does.
    let lock = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .open(out.join(".coupler.lock"))
        .unwrap_or_else(|e| panic!("{e}"));
    // SAFETY: flock(2) on a file this test opened.
    assert_eq!(
        unsafe {
            libc::flock(
                std::os::unix::io::AsRawFd::as_raw_fd(&lock),
                libc::LOCK_EX | libc::LOCK_NB,
            )
        },
        0
    );
    std::fs::write(out.join(".coupler.lock"), "4242\n").unwrap_or_default();
    let busy = coupler(&[
        "run",
        case.to_str().unwrap_or_default(),
        "--out",
        out.to_str().unwrap_or_default(),
        "--overwrite",
    ]);
    let err = stderr(&busy);
    assert_eq!(busy.status.code(), Some(2), "{err}");
    assert!(err.contains("a run still going on (coupler pid 4242)"), "{err}");
    drop(lock);

    let overwritten = coupler(&[
        "run",
        case.to_str().unwrap_or_default(),
        "--out",
        out.to_str().unwrap_or_default(),
        "--overwrite",
    ]);
    assert!(overwritten.status.success(), "{}", stderr(&overwritten));
    assert!(
        !out.join("stale-frame.vtu").exists(),
        "--overwrite deletes the earlier run's files"
    );
    assert!(stack_tests::oscillator_error(&out.join("recording.rec")) < 1e-4);
}

#[test]
fn a_missing_executable_is_refused_by_check_as_by_run() {
    let dir = out_dir("bad-executable");
    let case = stack_tests::oscillator_case(
        &dir,
        &[(
            "end_time",
            "1.0\nexecutables = { mass-left = \"no-such-solver\" }",
        )],
    );
    refused_by_check_and_run(
        &case,
        &["participant `mass-left`: no executable at", "no-such-solver"],
    );
}

#[test]
fn an_executable_that_cannot_run_is_refused_by_check_as_by_run() {
    use std::os::unix::fs::PermissionsExt;
    let dir = out_dir("unrunnable-executable");
    std::fs::create_dir_all(&dir).unwrap_or_default();
    let text = dir.join("notes.txt");
    std::fs::write(&text, "not a program\n").unwrap_or_default();
    std::fs::set_permissions(&text, std::fs::Permissions::from_mode(0o755)).unwrap_or_default();
    let plain = dir.join("solver-without-x");
    std::fs::write(&plain, "#!/bin/sh\nexit 0\n").unwrap_or_default();
    std::fs::set_permissions(&plain, std::fs::Permissions::from_mode(0o644)).unwrap_or_default();
    for (file, why) in [
        ("notes.txt", "neither a program (ELF) nor a script"),
        ("solver-without-x", "no execute permission"),
    ] {
        let case_dir = dir.join(format!("case-{}", file.replace('.', "-")));
        std::fs::create_dir_all(&case_dir).unwrap_or_default();
        let case = stack_tests::oscillator_case(
            &case_dir,
            &[(
                "end_time",
                &format!(
                    "1.0\nexecutables = {{ mass-left = \"{}\" }}",
                    dir.join(file).display()
                ),
            )],
        );
        refused_by_check_and_run(
            &case,
            &[
                "participant `mass-left`",
                file,
                "is not a program the system can run",
                why,
            ],
        );
    }
}

#[test]
fn an_output_folder_through_a_file_or_on_proc_is_refused_as_such() {
    let dir = out_dir("bad-out-place");
    std::fs::create_dir_all(&dir).unwrap_or_default();
    let case = stack_tests::oscillator_case(&dir, &[]);
    let file = dir.join("results.csv");
    std::fs::write(&file, "t\n").unwrap_or_default();
    for (out, fragments) in [
        (file.clone(), vec!["cannot be made", "is a file, not a folder"]),
        (
            file.join("run"),
            vec!["cannot be made", "is a file, not a folder"],
        ),
        (
            std::path::PathBuf::from("/proc/nope"),
            vec!["cannot be made", "holds no files"],
        ),
    ] {
        for command in ["check", "run"] {
            let run = coupler(&[
                command,
                case.to_str().unwrap_or_default(),
                "--out",
                out.to_str().unwrap_or_default(),
            ]);
            let err = stderr(&run);
            assert_eq!(
                run.status.code(),
                Some(2),
                "{command} --out {}: {err}",
                out.display()
            );
            for f in &fragments {
                assert!(
                    err.contains(f),
                    "{command} --out {}: `{f}` in {err}",
                    out.display()
                );
            }
            assert!(!err.contains("too large"), "{err}");
            assert!(!err.contains("started"), "nothing may start: {err}");
        }
    }
    assert_eq!(
        std::fs::read_to_string(&file).unwrap_or_default(),
        "t\n",
        "the file is left alone"
    );
}

/// The fluid on MPI ranks (`ranks`, `launcher`): what the ranks do not run, a launcher that is
/// not on PATH or has no place for the number of ranks, and no ranks at all are each refused by
/// `check` as by `run`, naming the key, before anything starts (with or without MPI built in).
#[test]
fn ranks_the_fluid_cannot_run_are_refused_by_check_as_by_run() {
    let ranked = |name: &str, from: &str, to: &str| {
        let dir = out_dir(&format!("bad-ranks-{name}"));
        let case = stack_tests::ranked_floating_box(&dir, 2, "scheme = \"explicit\"");
        let text = std::fs::read_to_string(&case).unwrap_or_default();
        assert!(text.contains(from), "the ranked case holds `{from}`");
        std::fs::write(&case, text.replacen(from, to, 1)).unwrap_or_else(|e| panic!("{e}"));
        case
    };
    let mpirun =
        "launcher = \"mpirun --allow-run-as-root --oversubscribe --mca mpi_yield_when_idle 1 -np {ranks}\"";
    for (case, fragments) in [
        (
            ranked(
                "launcher-missing",
                mpirun,
                "launcher = \"no-such-launcher -n {ranks}\"",
            ),
            &[
                "fluid.water.launcher",
                "`no-such-launcher`",
                "not a program on PATH",
            ][..],
        ),
        (
            ranked("launcher-without-ranks", mpirun, "launcher = \"srun\""),
            &["fluid.water.launcher", "{ranks}"][..],
        ),
        (
            ranked("zero-ranks", "ranks = 2", "ranks = 0"),
            &["fluid.water.ranks", "at least 1"][..],
        ),
        (
            ranked("isph", "ranks = 2", "ranks = 2\nmethod = \"isph\""),
            &["fluid.water.ranks", "not yet method = \"isph\"", "ranks = 1"][..],
        ),
        (
            ranked("surface-mesh", "ranks = 2", "ranks = 2\nsurface_mesh = true"),
            &["fluid.water.ranks", "surface_mesh = true"][..],
        ),
    ] {
        refused_by_check_and_run(&case, fragments);
    }
}
