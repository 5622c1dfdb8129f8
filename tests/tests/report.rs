//! `coupler report` on the oscillator, through the real binaries: one row per rung, the observed
//! orders of its schemes, the plot's data and `--docs` putting them into a docs folder, an
//! interrupted report, and stability runs classified as stable, stopped or failed silently.
//!
//! Expected orders (the coupler's accuracy table in README.md and `tests/tests/oscillator.rs`;
//! preCICE 3.4's tutorial gives 1 for serial explicit and 2 for implicit linear): explicit with
//! a constant predictor 1 (1.3 and 1.15 measured between 0.01 … 0.0025), implicit linear in the
//! window 2, implicit with cubic waveforms 4.

use stack_tests::{binary, out_dir, stderr, workspace};
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

fn oscillator() -> String {
    workspace()
        .join("cases/oscillator/case.toml")
        .display()
        .to_string()
}

/// The rows of a report CSV, as header name → field.
fn rows(path: &Path) -> Vec<BTreeMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .unwrap_or_default()
        .split(',')
        .map(String::from)
        .collect();
    lines
        .map(|l| {
            // Ladder labels hold commas and are quoted.
            let mut fields = Vec::new();
            let (mut cur, mut quoted) = (String::new(), false);
            for c in l.chars() {
                match c {
                    '"' => quoted = !quoted,
                    ',' if !quoted => fields.push(std::mem::take(&mut cur)),
                    c => cur.push(c),
                }
            }
            fields.push(cur);
            header.iter().cloned().zip(fields).collect()
        })
        .collect()
}

/// Width and height of a PNG file, after checking its signature, its IHDR and its IEND.
fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(
        &bytes[..8],
        b"\x89PNG\r\n\x1a\n",
        "{} is not a PNG",
        path.display()
    );
    assert_eq!(&bytes[12..16], b"IHDR");
    assert_eq!(
        &bytes[bytes.len() - 8..bytes.len() - 4],
        b"IEND",
        "PNG not complete"
    );
    let be = |i: usize| u32::from_be_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
    (be(16), be(20))
}

#[test]
fn oscillator_report_reproduces_the_orders_with_one_row_per_rung() {
    let out = out_dir("report-oscillator");
    let run = Command::new(binary("coupler"))
        .args([
            "report",
            &oscillator(),
            "--out",
            out.to_str().unwrap_or_default(),
            "--repeats",
            "1",
        ])
        .output()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    assert!(run.status.success(), "{}", stderr(&run));
    let table = rows(&out.join("accuracy.csv"));
    // The case's CI ladders: 6 ladders of 3 windows each.
    assert_eq!(table.len(), 18, "one row per rung");
    let mut by_ladder: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for r in &table {
        assert_eq!(r["status"], "ok", "{r:?}");
        let n = |k: &str| r[k].parse::<f64>().unwrap_or(f64::NAN);
        assert!(
            n("wall_s") > 0.0 && n("cpu_s") > 0.0 && n("peak_mb") > 1.0,
            "measured: {r:?}"
        );
        assert!(n("sweeps_per_window") >= 1.0);
        assert_eq!(n("steps"), (1.0 / n("value")).round(), "one step per window");
        by_ladder
            .entry(r["ladder"].clone())
            .or_default()
            .push((n("value"), n("error")));
    }
    let order = |l: &str| {
        let p = &by_ladder[l];
        let (a, b) = (p[p.len() - 2], p[p.len() - 1]);
        (a.1 / b.1).ln() / (a.0 / b.0).ln()
    };
    let explicit = order("explicit, constant predictor");
    let linear = order("implicit, linear, IQN-ILS");
    let cubic = order("implicit, cubic, IQN-ILS");
    println!("orders: explicit {explicit:.2}, implicit linear {linear:.2}, implicit cubic {cubic:.2}");
    assert!((0.9..1.5).contains(&explicit), "explicit: {explicit}");
    assert!((1.8..2.3).contains(&linear), "implicit linear: {linear}");
    assert!((3.7..4.3).contains(&cubic), "implicit cubic: {cubic}");
    for l in ["implicit, cubic, Aitken", "implicit, cubic, constant relaxation"] {
        assert!((3.7..4.3).contains(&order(l)), "{l}: {}", order(l));
    }
    // The Markdown shows the observed orders beside the expected ones.
    let md = std::fs::read_to_string(out.join("accuracy.md")).unwrap_or_default();
    assert!(
        md.contains("| implicit, cubic, IQN-ILS | 4 | 3.99, 4.00 |"),
        "{md}"
    );
    assert!(md.contains("The cheapest setting reaching"), "summary paragraph");
    // The plot: one line per ladder, each with its three rungs.
    assert_eq!(png_size(&out.join("oscillator-work-precision.png")), (1000, 700));
    let plot = rows(&out.join("oscillator-work-precision.plot.csv"));
    let mut lines: BTreeMap<String, usize> = BTreeMap::new();
    for p in &plot {
        *lines.entry(p["series"].clone()).or_default() += 1;
    }
    assert_eq!(lines.len(), 6, "one line per method: {lines:?}");
    assert!(lines.values().all(|&n| n == 3), "{lines:?}");
    // `--docs` puts that report into a docs folder: its Markdown as docs/validation.md's
    // fragment, its plot beside the page's figures, linked from the fragment.
    let docs = out.join("docs");
    let put = Command::new(binary("coupler"))
        .args([
            "report",
            "--docs",
            docs.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
        ])
        .output()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    assert!(put.status.success(), "{}", stderr(&put));
    let fragment = std::fs::read_to_string(docs.join("validation/report-accuracy.md")).unwrap_or_default();
    assert!(
        fragment.contains("](img/report/oscillator-work-precision.png)"),
        "{fragment}"
    );
    assert_eq!(
        png_size(&docs.join("img/report/oscillator-work-precision.png")),
        (1000, 700)
    );
}

#[test]
fn interrupted_report_keeps_its_rows_and_names_the_missing_ones() {
    let out = out_dir("report-interrupted");
    let mut child = Command::new(binary("coupler"))
        .args([
            "report",
            &oscillator(),
            "--out",
            out.to_str().unwrap_or_default(),
            "--repeats",
            "2",
        ])
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    let csv = out.join("accuracy.csv");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    while rows(&csv).len() < 3 && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    // SAFETY: kill(2) on our own child.
    unsafe { libc::kill(child.id() as i32, libc::SIGINT) };
    let status = child.wait().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(status.code(), Some(130), "an interrupted report exits 130");
    let done = rows(&csv);
    assert!(done.len() >= 3 && done.len() < 18, "{} rows kept", done.len());
    assert!(
        done.iter().all(|r| r["status"] == "ok"),
        "only finished rows: {done:?}"
    );
    let md = std::fs::read_to_string(out.join("accuracy.md")).unwrap_or_default();
    let missing = md
        .lines()
        .find(|l| l.starts_with("**Missing"))
        .unwrap_or_else(|| panic!("no missing line:\n{md}"));
    let named = missing.matches("coupling.window = ").count();
    assert_eq!(
        named + done.len(),
        18,
        "every rung is either a row or named missing: {missing}"
    );
}

/// The oscillator made to diverge: explicit coupling with a constant predictor, the middle
/// spring 10 × stiffer and windows of 0.05 s. Energy bounds |u1| by √(1 + 40) = 6.4 m; the run
/// grows past that within 1 s (and claims success: failed silently, which the suite must
/// catch), and reaches a non-finite state at t ≈ 44 s, where the structure solver stops it.
/// The implicit run of the same spring is stable.
#[test]
fn stability_runs_are_stable_stopped_or_caught_failing_silently() {
    let out = out_dir("report-stability");
    let source = std::fs::read_to_string(workspace().join("cases/oscillator/case.toml")).unwrap_or_default();
    let plain = &source[..source.find("\n[reference]").unwrap_or(source.len())];
    let text = format!(
        r#"{plain}
[report]
target_error = 1.0

[[report.limit]]
participant = "mass-left"
file = "point-m1.csv"
column = "ux"
max_abs = 6.5
reason = "energy conservation: |u1| ≤ √(1 + k_middle/k_left) = √41 = 6.4 m"

[[report.stability]]
family = "made to diverge"
set = {{ "coupling.window" = 0.05, "coupling.samples" = 1, "coupling.spring.0.stiffness" = 1579.1367041742973 }}
[[report.stability.axis]]
name = "coupling"
labels = ["implicit", "explicit", "explicit, detector off"]
set = [{{}}, {{ "coupling.scheme" = "explicit", "coupling.predictor" = "constant" }}, {{ "coupling.scheme" = "explicit", "coupling.predictor" = "constant", "coupling.created_energy_limit" = 1e300 }}]
[[report.stability.axis]]
name = "end time"
labels = ["1 s", "60 s"]
set = [{{ "case.end_time" = 1.0 }}, {{ "case.end_time" = 60.0 }}]
"#
    );
    let case = out.join("case.toml");
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let run = Command::new(binary("coupler"))
        .args([
            "report",
            "--stability",
            case.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
        ])
        .output()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    assert!(run.status.success(), "{}", stderr(&run));
    let outcomes = rows(&out.join("stability.csv"));
    let state = |run: &str| {
        outcomes
            .iter()
            .find(|r| r["run"] == run)
            .unwrap_or_else(|| panic!("no run {run}: {outcomes:?}"))
            .clone()
    };
    assert_eq!(state("implicit / 1 s")["state"], "stable");
    assert_eq!(state("implicit / 60 s")["state"], "stable");
    // The coupler's instability detector stops the explicit runs in their first window, with
    // the energy the coupling created.
    for run in ["explicit / 1 s", "explicit / 60 s"] {
        let stopped = state(run);
        assert_eq!(stopped["state"], "stopped", "{stopped:?}");
        assert!(
            stopped["diagnostic"].contains("coupling instability in window 0")
                && stopped["diagnostic"].contains("shorten coupling.window"),
            "the diagnostic says what, where and when: {stopped:?}"
        );
    }
    // With the detector switched off, the report still catches what the run does.
    let silent = state("explicit, detector off / 1 s");
    assert_eq!(silent["state"], "FAILED SILENTLY", "{silent:?}");
    assert!(silent["diagnostic"].contains("point-m1.csv"), "{silent:?}");
    // Over 60 s it grows to 1e304 J, past even a limit of 1e300 energy scales, or to a value
    // that is no longer finite: stopped either way, with what, where and when.
    let stopped = state("explicit, detector off / 60 s");
    assert_eq!(stopped["state"], "stopped", "{stopped:?}");
    let d = &stopped["diagnostic"];
    assert!(
        (d.contains("non-finite") && d.contains("m1")) || d.contains("coupling instability in window"),
        "the diagnostic says what, where and when: {stopped:?}"
    );
    let md = std::fs::read_to_string(out.join("stability.md")).unwrap_or_default();
    assert!(
        md.contains("6 runs: 2 stable, 0 warned, 3 stopped, 0 refused by the case check, 1 failed silently."),
        "{md}"
    );
    // The map: rows coupling × columns end time, one cell per run.
    let map = out.join("oscillator-made-to-diverge-map.png");
    assert!(png_size(&map).0 > 0);
    let cells = rows(&map.with_extension("plot.csv"));
    assert_eq!(cells.len(), 6, "{cells:?}");
    assert!(cells
        .iter()
        .any(|c| c["row"] == "explicit" && c["column"] == "60 s" && c["state"] == "stopped"));
}

/// A `resolved-run` reference runs another case file (with its `set`) and the `integral`
/// measure compares time integrals. The cantilever against itself under twice the tip load: the
/// elastic response is linear in the load (2 kN: 24 MPa at the root, a tenth of the yield
/// stress), so |∫(z₁ − z₂) dt| / |∫ z₂ dt| = ½ up to rounding. A reference without its case
/// file is refused by `coupler check`, naming the field.
#[test]
fn a_resolved_run_reference_compares_the_integral_against_another_case_file() {
    let dir = out_dir("report-resolved-run");
    let source = workspace().join("cases/structure-cantilever/case.toml");
    let text = std::fs::read_to_string(&source).unwrap_or_default();
    let scene = text.split("\n[reference]").next().unwrap_or_default();
    assert!(
        scene.contains("value = [0.0, 0.0, -1000.0"),
        "the cantilever's tip load"
    );
    std::fs::write(
        dir.join("resolved.toml"),
        scene.replace("value = [0.0, 0.0, -1000.0", "value = [0.0, 0.0, -2000.0"),
    )
    .unwrap_or_else(|e| panic!("cannot write the resolved case: {e}"));
    let reference = |case_line: &str| {
        format!(
            "{scene}\n[reference]\nagainst = \"resolved-run\"\n{case_line}participant = \"beam\"\nfile = \"node-5.csv\"\n\
             column = \"z\"\nmeasure = \"integral\"\nrelative = true\nsource = \"the cantilever under 2 kN\"\n\
             set = {{ \"case.end_time\" = 0.2 }}\n\n[report]\ntarget_error = 0.1\nrepeats = 1\n\n[[report.ladder]]\n\
             label = \"one solve\"\nset = {{ \"case.end_time\" = 0.2 }}\nvary = [\"structure.beam.frame.time_step\"]\nvalues = [1e-4]\n"
        )
    };
    let case = dir.join("case.toml");
    std::fs::write(&case, reference("")).unwrap_or_else(|e| panic!("cannot write the case: {e}"));
    let check = Command::new(binary("coupler"))
        .args(["check", case.to_str().unwrap_or_default()])
        .output()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    assert!(!check.status.success(), "a resolved run needs its case file");
    assert!(stderr(&check).contains("reference.case"), "{}", stderr(&check));
    std::fs::write(&case, reference("case = \"missing.toml\"\n"))
        .unwrap_or_else(|e| panic!("cannot write the case: {e}"));
    let check = Command::new(binary("coupler"))
        .args(["check", case.to_str().unwrap_or_default()])
        .output()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    let err = stderr(&check);
    assert_eq!(check.status.code(), Some(2), "{err}");
    assert!(
        err.contains("reference.case")
            && err.contains("missing.toml")
            && err.contains("cannot read the case file"),
        "a missing resolved case is named: {err}"
    );
    assert!(!err.contains("``"), "no empty key in the message: {err}");
    std::fs::write(&case, reference("case = \"resolved.toml\"\n"))
        .unwrap_or_else(|e| panic!("cannot write the case: {e}"));
    let out = dir.join("report");
    let run = Command::new(binary("coupler"))
        .args([
            "report",
            case.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
        ])
        .output()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    assert!(run.status.success(), "{}", stderr(&run));
    let table = rows(&out.join("accuracy.csv"));
    assert_eq!(table.len(), 1, "one rung");
    let error: f64 = table[0]["error"].parse().unwrap_or(f64::NAN);
    assert!((error - 0.5).abs() < 1e-6, "error {error}, {:?}", table[0]);
    let md = std::fs::read_to_string(out.join("accuracy.md")).unwrap_or_default();
    assert!(md.contains("against the resolved run of the same scene"), "{md}");
}
