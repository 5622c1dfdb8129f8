//! Issue 39: the fluid on MPI ranks inside the three-process stack (`ranks = 2` in its section;
//! the fluid solver built with its `mpi` feature). The coupler starts it through the section's
//! launcher and sees one participant: rank 0 serves the coupler, rank 1 follows it; replayed
//! against its recording, it gives the recorded answers.
//!
//! The two ranks step as the case in two slabs of one process, which `fluid-solver`'s `ranks.rs`
//! holds within the round-off spread of the undivided fluid (a body's loads within 6.3e-13 N of
//! 571 N against a spread of 6.0e-13 N with the particles stored in reverse order: 1e-15 of the
//! load). So the box's history and the probes on two ranks must follow the one-rank run to
//! round-off. The bound, [`ROUND_OFF`], is 1e-9 in every column (m, m/s, rad/s, the quaternion's
//! components, Pa relative): a load 1e-15 off its one-rank value moves a 0.72 kg box by about
//! 1e-15 × 5 N / 0.72 kg × (0.05 s)² ≈ 2e-17 m over the run, so 1e-9 leaves eight orders of
//! growth for round-off to amplify, and is still far below what a share counted twice or lost
//! does: a mutation handing the coupler rank 0's share of the forces instead of their sum broke
//! the ledger's balance and moved the box's vertical velocity by 8.7e-2 m/s in 0.05 s.
//! Measured 30 Nov 2026 on this 2-core machine: 1.1e-14 rad/s (angular velocity), the
//! positions and probes equal to every printed digit.

use schemas::validation::{largest, largest_abs, record, Record};
use stack_tests::{binary, csv_rows, out_dir, ranked_floating_box, stderr};
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The two-rank run's largest difference from the one-rank run in any column of the box's
/// history or the probe CSV (probes relative to their largest reading) — see the module doc.
const ROUND_OFF: f64 = 1e-9;

/// `coupler run CASE --out OUT`.
fn run(case: &Path, out: &Path) -> Output {
    Command::new(binary("coupler"))
        .args([
            "run",
            &case.display().to_string(),
            "--out",
            &out.display().to_string(),
        ])
        .output()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"))
}

/// Runs the floating box with `coupling` on one rank and on two; returns their output folders
/// and the two-rank run's stderr, after checking that both ran and that the ledger balanced
/// every window of the two-rank run.
fn one_and_two_ranks(
    name: &str,
    coupling: &str,
    windows: usize,
) -> (std::path::PathBuf, std::path::PathBuf, String, f64) {
    let dir = out_dir(name);
    let mut outs = Vec::new();
    let mut two = (String::new(), 0.0);
    for ranks in [1, 2] {
        let case_dir = dir.join(format!("ranks-{ranks}"));
        std::fs::create_dir_all(&case_dir).unwrap_or_else(|e| panic!("{e}"));
        let case = ranked_floating_box(&case_dir, ranks, coupling);
        let text = std::fs::read_to_string(&case).unwrap_or_default();
        let end = format!("end_time = {}", windows as f64 / 2000.0);
        std::fs::write(&case, text.replacen("end_time = 0.05", &end, 1)).unwrap_or_else(|e| panic!("{e}"));
        let out = case_dir.join("out");
        let started = Instant::now();
        let result = run(&case, &out);
        let err = stderr(&result);
        assert!(result.status.success(), "{ranks} rank(s): {err}");
        if ranks == 2 {
            two = (err, started.elapsed().as_secs_f64());
        }
        outs.push(out);
    }
    let (err, seconds) = two;
    assert!(
        err.contains(
            "started water (mpirun --allow-run-as-root --oversubscribe --mca mpi_yield_when_idle 1 -np 2"
        ),
        "the coupler starts the fluid through its launcher: {err}"
    );
    let log = std::fs::read_to_string(outs[1].join("water.log")).unwrap_or_default();
    assert!(log.contains("on 2 ranks, 7200 fluid particles"), "{log}");
    let ledger = std::fs::read_to_string(outs[1].join("ledger.csv")).unwrap_or_default();
    let rows: Vec<&str> = ledger.lines().skip(1).collect();
    assert_eq!(rows.len(), windows, "one ledger row per window:\n{ledger}");
    assert!(
        rows.iter().all(|r| r.ends_with(",ok")),
        "action = −reaction in every window on two ranks:\n{ledger}"
    );
    let two = outs.pop().unwrap_or_default();
    let one = outs.pop().unwrap_or_default();
    (one, two, err, seconds)
}

/// The largest difference between two CSV files' rows, column by column (each column scaled by
/// its largest magnitude when `relative`), after checking they hold as many rows; NaN when
/// either file holds a NaN, but for a text column (the ledger's status), NaN in every row of both.
fn largest_difference(a: &Path, b: &Path, relative: bool) -> f64 {
    let (x, y) = (csv_rows(a), csv_rows(b));
    assert!(!x.is_empty(), "{} has rows", a.display());
    assert_eq!(
        x.len(),
        y.len(),
        "{} and {} hold as many rows",
        a.display(),
        b.display()
    );
    let text = |c: usize| x.iter().chain(&y).all(|r| r[c].is_nan());
    let numbers = (0..x[0].len()).filter(|&c| !text(c));
    largest(
        numbers.map(|c| {
            let scale = match relative {
                true => largest(x.iter().map(|r| r[c].abs()), 1e-300),
                false => 1.0,
            };
            largest_abs(x.iter().zip(&y).map(|(p, q)| (p[c] - q[c]) / scale))
        }),
        0.0,
    )
}

#[test]
fn a_floating_box_with_its_fluid_on_two_ranks_follows_the_one_rank_run() {
    let (one, two, _, run_time_s) = one_and_two_ranks("ranked-floating-box", "scheme = \"explicit\"", 100);
    let history = largest_difference(
        &one.join("floater/body-box.csv"),
        &two.join("floater/body-box.csv"),
        false,
    );
    let probes = largest_difference(
        &one.join("water/water_probes.csv"),
        &two.join("water/water_probes.csv"),
        true,
    );
    println!("two ranks against one: box history {history:.2e}, probes {probes:.2e} (relative)");
    let moved = csv_rows(&one.join("floater/body-box.csv"));
    let (first, last) = (&moved[0], &moved[moved.len() - 1]);
    assert!(
        (last[1] - first[1]).abs() > 1e-3,
        "the box drifts along the flow, across the cut: x {} → {}",
        first[1],
        last[1]
    );
    record(Record {
        id: "emps-mpi-2-ranks-coupled-floating-box".into(),
        capability: "the fluid on MPI ranks in the three-process stack (E-MPS)".into(),
        reference: "the same case with the fluid on one rank".into(),
        case: "a 0.72 kg box floating across the cut of two slabs, gravity leaning 6 m/s² along x, 0.05 s".into(),
        resolution: "E-MPS, Δs = 0.02 m (7 200 fluid particles), explicit coupling, window 5e-4 s; 2 ranks on 2 cores".into(),
        measure: "largest difference of the box's history (position, quaternion, velocities) from the one-rank run".into(),
        value: history,
        bound: Some(ROUND_OFF),
        bound_source: "round-off: the slabs step as the undivided fluid, their loads within the reversed-order spread (ranks.rs); see the test's doc".into(),
        source: "tests/tests/ranked_fluid.rs::a_floating_box_with_its_fluid_on_two_ranks_follows_the_one_rank_run".into(),
        run_time_s,
        ..Default::default()
    });
    assert!(
        history <= ROUND_OFF,
        "the box on two ranks is {history:.2e} off the one-rank run"
    );
    assert!(
        probes <= ROUND_OFF,
        "the probes on two ranks are {probes:.2e} off the one-rank run"
    );

    // the fluid on its ranks replayed against the recording: the same answers
    let replay = Command::new(binary("coupler"))
        .args([
            "replay",
            &two.join("recording.rec").display().to_string(),
            "--participant",
            "water",
        ])
        .args(["--out", &two.with_file_name("replay").display().to_string()])
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    let text = format!("{}{}", String::from_utf8_lossy(&replay.stdout), stderr(&replay));
    println!("{text}");
    assert!(replay.status.success() && text.contains("PASS"), "{text}");
    assert!(
        text.contains("-np 2"),
        "the replay starts the fluid on its ranks: {text}"
    );

    // the frames: one index per frame naming both pieces, each piece written
    let pvd = std::fs::read_to_string(two.join("water/water.pvd")).unwrap_or_default();
    for k in 0..3 {
        let index = format!("water_{k:05}.pvtu");
        assert!(pvd.contains(&index), "the series names {index}: {pvd}");
        let pvtu = std::fs::read_to_string(two.join("water").join(&index)).unwrap_or_default();
        for r in 0..2 {
            let piece = format!("water_{k:05}_r{r:04}.vtu");
            assert!(pvtu.contains(&piece), "{index} names {piece}");
            assert!(two.join("water").join(&piece).is_file(), "{piece} is written");
        }
    }
}

/// Implicit coupling saves and restores the fluid's state in every window (three sweeps per
/// window here, 20 windows): on two ranks each rank restores its own slab and its ownership.
#[test]
fn an_implicit_window_on_two_ranks_iterates_as_on_one() {
    let coupling = "scheme = \"implicit\"\nacceleration = \"iqn-ils\"\ntolerance = 1.0e-6";
    let (one, two, _, _) = one_and_two_ranks("ranked-floating-box-implicit", coupling, 20);
    let sweeps =
        |out: &Path| -> Vec<f64> { csv_rows(&out.join("ledger.csv")).iter().map(|r| r[2]).collect() };
    assert!(
        sweeps(&one).iter().all(|&s| s >= 2.0),
        "the windows iterate: {:?}",
        sweeps(&one)
    );
    assert_eq!(sweeps(&one), sweeps(&two), "as many sweeps in every window");
    let history = largest_difference(
        &one.join("floater/body-box.csv"),
        &two.join("floater/body-box.csv"),
        false,
    );
    println!("implicit, two ranks against one: box history {history:.2e}");
    assert!(
        history <= ROUND_OFF,
        "the box on two ranks is {history:.2e} off the one-rank run"
    );
}

/// A rank killed with SIGKILL in the middle of the run: `mpirun` stops the other, the coupler
/// names the fluid participant and the window within seconds, and the structure is stopped.
#[test]
fn a_rank_killed_stops_the_stack_naming_the_fluid_and_the_window() {
    let dir = out_dir("ranked-floating-box-killed");
    let case = ranked_floating_box(&dir, 2, "scheme = \"explicit\"");
    // long enough that the run is still going when the rank is killed
    let text = std::fs::read_to_string(&case)
        .unwrap_or_default()
        .replace("end_time = 0.05", "end_time = 5.0");
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let log = dir.join("coupler.txt");
    let err_file = std::fs::File::create(&log).unwrap_or_else(|e| panic!("{e}"));
    let mut coupler = Command::new(binary("coupler"))
        .args([
            "run",
            &case.display().to_string(),
            "--out",
            &out.display().to_string(),
        ])
        .stdout(Stdio::null())
        .stderr(err_file)
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    // rank 1: the second child of `mpirun`, once the first frames are written
    let deadline = Instant::now() + Duration::from_secs(60);
    let rank_one = loop {
        assert!(Instant::now() < deadline, "no second rank started");
        assert!(coupler.try_wait().ok().flatten().is_none(), "the run ended early");
        let text = std::fs::read_to_string(&log).unwrap_or_default();
        let mpirun = text
            .lines()
            .find(|l| l.starts_with("started water"))
            .and_then(|l| l.rsplit_once("pid "))
            .map(|(_, p)| p.trim_end_matches(')').to_string());
        let children =
            mpirun.and_then(|pid| std::fs::read_to_string(format!("/proc/{pid}/task/{pid}/children")).ok());
        let pids: Vec<String> = children
            .unwrap_or_default()
            .split_whitespace()
            .map(str::to_string)
            .collect();
        if pids.len() == 2 && out.join("water/water_00001.pvtu").is_file() {
            break pids[1].clone();
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let killed = Instant::now();
    let _ = Command::new("kill").args(["-KILL", &rank_one]).status();
    let status = loop {
        if let Some(status) = coupler.try_wait().ok().flatten() {
            break status;
        }
        if killed.elapsed() > Duration::from_secs(30) {
            let _ = coupler.kill();
            panic!("the stack did not stop within 30 s of the rank's death");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let seconds = killed.elapsed().as_secs_f64();
    let text = std::fs::read_to_string(&log).unwrap_or_default();
    println!("{text}\nstopped {seconds:.2} s after the kill");
    assert!(!status.success(), "a run whose rank died fails");
    assert!(seconds < 10.0, "the stack stops within seconds: {seconds:.1} s");
    assert!(
        text.contains("error: participant `water` in window"),
        "the coupler names the fluid and the window: {text}"
    );
    let water_log = std::fs::read_to_string(out.join("water.log")).unwrap_or_default();
    assert!(
        water_log.contains("rank 1") && water_log.contains("signal 9"),
        "the fluid's log names the rank and the signal: {water_log}"
    );
}

/// A dam break on a tilted tank (`fluid-solver`'s `ranks.rs` scene: 2.0 × 0.06 × 0.4 m, a column
/// 0.8 × 0.3 m, 1 800 fluid particles at Δs = 0.02 m, gravity leaning 20 m/s² along x) whose
/// water moves enough for the two ranks to cut their slabs again (at the start of window 151,
/// 0.075 s), coupled to a 0.1 × 0.04 × 0.04 m box resting on the floor at the far end: the fluid
/// on `ranks`, checkpoints every 0.05 s, 0.1 s.
fn ranked_dam_break(dir: &Path, ranks: usize) -> std::path::PathBuf {
    let text = format!(
        r#"[case]
name = "ranked-dam-break"
end_time = 0.1

[fluid.water]
spacing = 0.02
time_step = 5.0e-4
sound_speed = 12.1
gravity = [20.0, 0.0, -9.8]
output_interval = 0.05
probe_interval = 0.005
tank = {{ min = [0.0, 0.0, 0.0], max = [2.0, 0.06, 0.4], lid = true }}
ranks = {ranks}
launcher = "mpirun --allow-run-as-root --oversubscribe --mca mpi_yield_when_idle 1 -np {{ranks}}"

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.8, 0.06, 0.3]

[[fluid.water.body]]
name = "box"
min = [1.8, 0.02, 0.0]
max = [1.9, 0.04, 0.04]

[[fluid.water.probe]]
name = "floor-sensor"
kind = "wall-pressure"
position = [0.43, 0.03, 0.0]
normal = "+z"
diameter = 0.04
window = 0.005

[[fluid.water.probe]]
name = "front"
kind = "surge-front"
axis = "x"

[structure.block]
max_step = 1.0e-4
gravity = [20.0, 0.0, -9.8]

[[structure.block.body]]
name = "box"
mass = 0.2
centre = [1.85, 0.03, 0.02]
inertia = {{ box = [0.1, 0.02, 0.04] }}

[structure.block.history]
interval = 0.005
bodies = ["box"]

[coupling]
window = 5.0e-4
scheme = "explicit"
order = ["water", "block"]
predictor = "linear"
checkpoint_interval = 0.05

[[coupling.body]]
fluid = "water/box"
structure = "block/box"
"#
    );
    std::fs::create_dir_all(dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
    path
}

/// The ranks cut their slabs again in a coupled run (at a window's start), and the checkpoint
/// at 0.1 s, taken after that, keeps the cuts: a run on two ranks to 0.1 s extended to 0.125 s
/// from its checkpoint writes the same bytes as one run to 0.125 s, and follows the one-rank run
/// within [`ROUND_OFF`] (the box's history, the probes).
#[test]
fn two_ranks_cut_again_in_a_coupled_run_extend_from_their_checkpoint_and_follow_one_rank() {
    let dir = out_dir("ranked-dam-break");
    let case = ranked_dam_break(&dir.join("ranks-2"), 2);
    let path = case.display().to_string();
    let straight = dir.join("straight");
    crate::resume::coupler_ok(&[
        "run",
        &path,
        "--out",
        &straight.display().to_string(),
        "--end-time",
        "0.125",
    ]);
    let extended = dir.join("extended");
    let e = extended.display().to_string();
    crate::resume::coupler_ok(&["run", &path, "--out", &e]);
    let log = std::fs::read_to_string(extended.join("water.log")).unwrap_or_default();
    assert!(
        log.contains("slabs cut again") && !log.contains("slabs cut again 0 times"),
        "the ranks cut again before the checkpoint at 0.1 s: {log}"
    );
    let err = crate::resume::coupler_ok(&["run", &path, "--resume", &e, "--end-time", "0.125"]);
    assert!(err.contains("(t = 0.1 s)"), "extended from its end: {err}");
    crate::resume::assert_same_outputs(&straight, &extended);

    let one_case = ranked_dam_break(&dir.join("ranks-1"), 1);
    let one = dir.join("one");
    crate::resume::coupler_ok(&[
        "run",
        &one_case.display().to_string(),
        "--out",
        &one.display().to_string(),
        "--end-time",
        "0.125",
    ]);
    let history = largest_difference(
        &one.join("block/body-box.csv"),
        &straight.join("block/body-box.csv"),
        false,
    );
    let probes = largest_difference(
        &one.join("water/water_probes.csv"),
        &straight.join("water/water_probes.csv"),
        true,
    );
    println!("cut again, two ranks against one: box history {history:.2e}, probes {probes:.2e} (relative)");
    assert!(
        history <= ROUND_OFF,
        "the box on two ranks is {history:.2e} off the one-rank run"
    );
    assert!(
        probes <= ROUND_OFF,
        "the probes on two ranks are {probes:.2e} off the one-rank run"
    );
}

/// [`ranked_dam_break`]'s tilted tank with a 2 × 2 mm steel column fixed at both ends at
/// x = 0.405 m, 5 mm from the two ranks' cut (its reactions spread over particles of both
/// slabs), coupled by the unresolved drag law, 0.05 s: the fluid on `ranks`.
fn ranked_drag_column(dir: &Path, ranks: usize) -> std::path::PathBuf {
    let case = ranked_dam_break(dir, ranks);
    let text = std::fs::read_to_string(&case).unwrap_or_default();
    let start = text.find("[[fluid.water.body]]").unwrap_or(0);
    let probes = text.find("[[fluid.water.probe]]").unwrap_or(0);
    let structure = text.find("[structure.block]").unwrap_or(0);
    // the drag column of DRAG_COLUMN_CASE, moved to 5 mm from the cut, under the tank's gravity
    let lib = stack_tests::DRAG_COLUMN_CASE;
    let mut column = lib[lib.find("[structure.column]").unwrap_or(0)..]
        .replace("SCHEME", "explicit")
        .replace("TOLERANCE", "");
    for (from, to) in [
        ("gravity = [0.0, 0.0, -9.8]", "gravity = [20.0, 0.0, -9.8]"),
        ("position = [0.25, 0.05, 0.0]", "position = [0.405, 0.03, 0.0]"),
        ("position = [0.25, 0.05, 0.15]", "position = [0.405, 0.03, 0.2]"),
    ] {
        assert!(column.contains(from), "DRAG_COLUMN_CASE has changed: no `{from}`");
        column = column.replacen(from, to, 1);
    }
    let text = format!("{}{}{}", &text[..start], &text[probes..structure], column)
        .replace("end_time = 0.1", "end_time = 0.05");
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    case
}

/// The drag coupling with the fluid on two ranks: the flow at each sample point comes from the
/// rank whose slab holds it, and every rank spreads every reaction over the particles it holds,
/// so the drag forces the coupler computes (the ledger, every window) and the fluid's probes
/// follow the one-rank run within [`ROUND_OFF`] (relative).
#[test]
fn the_drag_coupling_with_the_fluid_on_two_ranks_follows_the_one_rank_run() {
    let dir = out_dir("ranked-drag-column");
    let mut outs = Vec::new();
    for ranks in [1, 2] {
        let case = ranked_drag_column(&dir.join(format!("ranks-{ranks}")), ranks);
        let out = dir.join(format!("out-{ranks}"));
        let result = run(&case, &out);
        let err = stderr(&result);
        assert!(result.status.success(), "{ranks} rank(s): {err}");
        outs.push(out);
    }
    // relative to the largest drag: a force component that is round-off noise about 0 (the
    // drag across the flow) differs relatively by its whole size
    let ledger = largest_difference(&outs[0].join("ledger.csv"), &outs[1].join("ledger.csv"), false);
    let probes = largest_difference(
        &outs[0].join("water/water_probes.csv"),
        &outs[1].join("water/water_probes.csv"),
        true,
    );
    let rows = csv_rows(&outs[1].join("ledger.csv"));
    let header = std::fs::read_to_string(outs[1].join("ledger.csv")).unwrap_or_default();
    let header: Vec<&str> = header.lines().next().unwrap_or_default().split(',').collect();
    let fx = header
        .iter()
        .position(|h| *h == "column_fx")
        .unwrap_or_else(|| panic!("{header:?}"));
    let largest_drag = largest_abs(rows.iter().map(|r| r[fx]));
    let ledger = ledger / largest_drag;
    println!("drag on two ranks against one: ledger {ledger:.2e}, probes {probes:.2e} (relative); largest drag {largest_drag:.3e} N");
    assert!(
        largest_drag > 1e-4,
        "the water drags the column: {largest_drag} N"
    );
    assert!(
        ledger <= ROUND_OFF,
        "the drag on two ranks is {ledger:.2e} off the one-rank run"
    );
    assert!(
        probes <= ROUND_OFF,
        "the probes on two ranks are {probes:.2e} off the one-rank run"
    );
}
