//! The fluid on MPI ranks (issue 39; built with the `mpi` feature): `mpirun -np 2 fluid-solver
//! run` on the tilted dam break of `ranks.rs`, 200 steps. The ranks trade the same particles in
//! the same order as the slabs of one process ([`fluid_solver::ranks::decomposed`]), so the two
//! ranks' fluid must equal the in-process 2-slab run's bit for bit (positions are written as
//! f64); `ranks.rs` holds those slabs within the round-off spread of the undivided run, so the
//! ranks are too (measured 29 Nov 2026 against `fluid-solver run` in one process: 1.7e-15 m after
//! 200 steps, the reversed order's spread 4.7e-15 m). Mass is exact, each particle is in one
//! piece, and the PVTU index and PVD series name every piece; the probe CSV rank 0 writes holds
//! the slabs' rows to the digit. A case the ranks do not run yet is refused once, naming the
//! feature, and nothing runs.

use crate::ranks::{by_id, largest_gap, CHANNEL, TANK};
use fluid_solver::ranks::decomposed::DecomposedFluid;
use schemas::case::{Case, FluidConfig};
use schemas::validation::{record, Record};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// 0.1 s at Δt = 5e-4 s.
const STEPS: usize = 200;

/// `ranks.rs`' tank (1.6 × 0.06 × 0.3 m, column 1.2 × 0.24 m, 2 160 fluid particles, gravity
/// leaning 6 m/s² towards +x) with one frame at the end; `extra` is added to the fluid section.
fn case_text(extra: &str) -> String {
    let text = TANK.replace("output_interval = 0.05", "output_interval = 0.1");
    assert_ne!(text, TANK, "ranks.rs' tank has changed its output interval");
    text.replace(
        "[[fluid.water.block]]",
        &format!("{extra}\n[[fluid.water.block]]"),
    )
}

fn dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap_or_else(|e| panic!("{e}"));
    d
}

/// `fluid-solver run CASE --out OUT`, on `ranks` MPI ranks when `ranks > 1` (as root, which CI
/// is, and with more ranks than cores allowed; one thread per rank).
fn command(case: &Path, out: &Path, ranks: usize) -> Command {
    let solver = env!("CARGO_BIN_EXE_fluid-solver");
    let mut cmd = match ranks {
        1 => Command::new(solver),
        n => {
            let mut c = Command::new("mpirun");
            c.args(["-np", &n.to_string(), "--oversubscribe"]);
            // waiting ranks yield their core: CI runs several tests' ranks on 2 cores
            c.args(["--mca", "mpi_yield_when_idle", "1", solver]);
            c
        }
    };
    cmd.arg("run")
        .arg(case)
        .arg("--out")
        .arg(out)
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .env("RAYON_NUM_THREADS", "1");
    cmd
}

/// [`command`] run to its end.
fn run(case: &Path, out: &Path, ranks: usize) -> Output {
    let mut cmd = command(case, out, ranks);
    cmd.output()
        .unwrap_or_else(|e| panic!("cannot start {cmd:?} (is OpenMPI's mpirun installed?): {e}"))
}

/// The arrays `position`, `id` and `kind` of a VTU frame the fluid wrote (raw appended data,
/// UInt64 block headers).
fn frame(vtu: &Path) -> Vec<(u32, u8, [f64; 3])> {
    let bytes = std::fs::read(vtu).unwrap_or_else(|e| panic!("cannot read {}: {e}", vtu.display()));
    let text = String::from_utf8_lossy(&bytes[..bytes.len().min(4096)]).into_owned();
    let data = text
        .find("<AppendedData encoding=\"raw\">")
        .map(|m| m + text[m..].find('_').unwrap_or(0) + 1)
        .unwrap_or_else(|| panic!("{}: no appended data", vtu.display()));
    let block = |name: &str| -> &[u8] {
        let at = text
            .find(&format!("Name=\"{name}\""))
            .unwrap_or_else(|| panic!("{}: no {name} array", vtu.display()));
        let rest = &text[at..];
        let start = rest.find("offset=\"").unwrap_or(0) + 8;
        let end = start + rest[start..].find('"').unwrap_or(0);
        let offset: usize = rest[start..end].parse().unwrap_or_else(|e| panic!("{e}"));
        let at = data + offset;
        let len = u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap_or_default()) as usize;
        &bytes[at + 8..at + 8 + len]
    };
    let (position, id, kind) = (block("position"), block("id"), block("kind"));
    let f = |i: usize| f64::from_le_bytes(position[8 * i..8 * i + 8].try_into().unwrap_or_default());
    (0..kind.len())
        .map(|i| {
            let id = u32::from_le_bytes(id[4 * i..4 * i + 4].try_into().unwrap_or_default());
            (id, kind[i], [f(3 * i), f(3 * i + 1), f(3 * i + 2)])
        })
        .collect()
}

/// Fluid positions by id.
fn fluid_by_id(particles: &[(u32, u8, [f64; 3])]) -> HashMap<u32, [f64; 3]> {
    particles
        .iter()
        .filter(|(_, kind, _)| *kind == fluid_solver::Kind::Fluid.code())
        .map(|(id, _, r)| (*id, *r))
        .collect()
}

fn config(path: &Path) -> FluidConfig {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{e}"));
    let case = Case::parse(path, text).unwrap_or_else(|e| panic!("{e}"));
    case.fluid["water"].clone()
}

#[test]
fn two_ranks_step_as_two_slabs_in_one_process_bit_for_bit() {
    let started = std::time::Instant::now();
    let d = dir("mpi-ranks");
    let case = d.join("case.toml");
    std::fs::write(&case, case_text("")).unwrap_or_else(|e| panic!("{e}"));
    let cfg = config(&case);

    let ranked = run(&case, &d.join("ranks"), 2);
    let log = String::from_utf8_lossy(&ranked.stderr);
    println!("{log}");
    assert!(ranked.status.success(), "mpirun -np 2 failed: {log}");
    assert!(
        log.contains("on 2 ranks") && log.matches("done:").count() == 1,
        "rank 0 alone reports the run: {log}"
    );
    let pieces: Vec<PathBuf> = (0..2)
        .map(|r| d.join("ranks").join(format!("water_00001_r{r:04}.vtu")))
        .collect();
    let index = std::fs::read_to_string(d.join("ranks/water_00001.pvtu")).unwrap_or_else(|e| panic!("{e}"));
    for r in 0..2 {
        assert!(
            index.contains(&format!("<Piece Source=\"water_00001_r{r:04}.vtu\"/>")),
            "the index names piece {r}: {index}"
        );
    }
    for array in ["position", "velocity", "pressure", "kind", "id"] {
        assert!(
            index.contains(&format!("Name=\"{array}\"")),
            "the index declares {array}"
        );
    }
    let series = std::fs::read_to_string(d.join("ranks/water.pvd")).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        series.contains("water_00000.pvtu") && series.contains("water_00001.pvtu"),
        "{series}"
    );
    let mut every: Vec<(u32, u8, [f64; 3])> = Vec::new();
    let mut fluid_per_rank = Vec::new();
    for p in &pieces {
        let f = frame(p);
        fluid_per_rank.push(fluid_by_id(&f).len());
        every.extend(f);
    }
    let mut ids: Vec<u32> = every.iter().map(|(id, _, _)| *id).collect();
    ids.sort_unstable();
    let before = ids.len();
    ids.dedup();
    assert_eq!(ids.len(), before, "a particle is in both pieces");
    let ranks = fluid_by_id(&every);

    // the same case in two slabs of one process, stepped as the run steps
    let mut slabs = DecomposedFluid::new(&cfg, 2).unwrap_or_else(|e| panic!("{e}"));
    let mut rows = vec![slabs.probe_row()];
    while let Some(dt) = slabs.parts()[0].solver.next_step_towards(0.1) {
        slabs.step(dt).unwrap_or_else(|e| panic!("{e}"));
        slabs.observe_probes(0.1);
    }
    rows.push(slabs.probe_row());
    let csv = std::fs::read_to_string(d.join("ranks/water_probes.csv")).unwrap_or_else(|e| panic!("{e}"));
    let written: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(written.len(), 2, "rows at 0 and 0.1 s: {csv}");
    for (line, (row, t)) in written.iter().zip(rows.iter().zip([0.0, 0.1])) {
        let expected: Vec<String> = row.iter().map(|v| format!("{v:.6e}")).collect();
        assert_eq!(
            *line,
            format!("{t:.6},{},0", expected.join(",")),
            "rank 0's probe row against the slabs' in one process"
        );
    }
    assert_eq!(slabs.parts()[0].solver.steps(), STEPS as u64);
    let in_process = by_id(&slabs.fluid());
    let same = largest_gap(&ranks, &in_process);
    println!(
        "2 ranks against 2 slabs in one process: largest gap {same:.3e} m; fluid per rank {fluid_per_rank:?}"
    );
    assert!(
        fluid_per_rank.iter().all(|&n| n > 500),
        "each rank owns part of the fluid: {fluid_per_rank:?}"
    );

    record(Record {
        id: "emps-mpi-2-ranks-vs-2-slabs".into(),
        capability: "E-MPS fluid on MPI ranks (slabs along x, halos traded by MPI)".into(),
        reference: "the same case in 2 slabs of one process (whose drift from the undivided run ranks.rs bounds)".into(),
        case: "tilted dam break: 1.6 × 0.06 × 0.3 m tank, column 1.2 × 0.24 m (2 160 fluid particles), gravity 6 m/s² along x".into(),
        resolution: format!("E-MPS, Δs = 0.02 m, {STEPS} steps, mpirun -np 2"),
        measure: "largest |r_ranks − r_slabs| over the fluid particles".into(),
        value: same,
        bound: Some(0.0),
        bound_source: "bit for bit: the ranks do the slabs' arithmetic in the same order".into(),
        unit: "m".into(),
        source: "fluid-solver/tests/mpi_ranks.rs::two_ranks_step_as_two_slabs_in_one_process_bit_for_bit".into(),
        run_time_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    });
    assert!(
        same == 0.0,
        "the ranks' fluid differs from the slabs' by {same:e} m"
    );
}

/// `ranks.rs`' channel (inflow through x = 0.4 m, outflow behind x = 3.4 m, gravity leaning
/// along x) on 2 ranks to 0.4 s (200 steps, a frame and a balance row every 0.1 s): rank 0
/// feeds the water in, rank 1 lets it out, and both equal 2 slabs of one process bit for bit;
/// the balance CSV rank 0 writes closes exactly, holds the slabs' counts, and counts the
/// undivided layout's walls in every row.
#[test]
fn inflow_and_outflow_on_two_ranks_step_as_two_slabs_and_the_balance_closes() {
    let d = dir("mpi-ranks-channel");
    let case = d.join("case.toml");
    let text = CHANNEL.replace("end_time = 1.0", "end_time = 0.4");
    assert_ne!(text, CHANNEL, "ranks.rs' channel has changed its end time");
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let cfg = config(&case);
    let ranked = run(&case, &d.join("ranks"), 2);
    let log = String::from_utf8_lossy(&ranked.stderr);
    println!("{log}");
    assert!(ranked.status.success(), "mpirun -np 2 failed: {log}");
    let mut every: Vec<(u32, u8, [f64; 3])> = Vec::new();
    for r in 0..2 {
        every.extend(frame(&d.join(format!("ranks/water_00004_r{r:04}.vtu"))));
    }
    let ranks = fluid_by_id(&every);

    let mut slabs = DecomposedFluid::new(&cfg, 2).unwrap_or_else(|e| panic!("{e}"));
    let at_start = slabs.fluid_count();
    for k in 1..=4 {
        let target = k as f64 * 0.1;
        while let Some(dt) = slabs.parts()[0].solver.next_step_towards(target) {
            slabs.step(dt).unwrap_or_else(|e| panic!("{e}"));
        }
        slabs.land_on(target);
    }
    let same = largest_gap(&ranks, &by_id(&slabs.fluid()));
    let b = slabs.balance();
    println!("2 ranks against 2 slabs: largest gap {same:e} m; {b:?}");
    assert!(
        same == 0.0,
        "the ranks' fluid differs from the slabs' by {same:e} m"
    );

    let csv = std::fs::read_to_string(d.join("ranks/water_balance.csv")).unwrap_or_else(|e| panic!("{e}"));
    let last: Vec<&str> = csv.lines().last().unwrap_or_default().split(',').collect();
    let field = |k: usize| -> u64 { last.get(k).and_then(|v| v.parse().ok()).unwrap_or(u64::MAX) };
    assert_eq!(
        csv.lines().count(),
        6,
        "a header and rows at 0, 0.1, …, 0.4 s: {csv}"
    );
    assert_eq!(
        [field(1), field(2), field(3), field(4)],
        [b.inserted, b.entered, b.removed, b.withdrawn],
        "the ranks' counts are the slabs': {csv}"
    );
    assert!(b.entered > 0 && b.removed > 0, "water entered and left: {b:?}");
    assert_eq!(
        field(6),
        ranks.len() as u64,
        "the fluid column counts the pieces' fluid: {csv}"
    );
    assert_eq!(
        field(6),
        at_start + field(2) - field(3),
        "fluid = at the start + entered − removed: {csv}"
    );
    // the walls (every particle but the fluid and the strip) are the undivided layout's, in
    // every row
    let layout = fluid_solver::FluidSolver::new(&cfg);
    let p = layout.particles();
    let walls = p.len() - p.count(fluid_solver::Kind::Fluid) - p.count(fluid_solver::Kind::Inflow);
    for row in csv.lines().skip(1) {
        let n: Vec<usize> = row.split(',').map(|v| v.parse().unwrap_or(usize::MAX)).collect();
        assert_eq!(
            n[7] - n[6] - n[5],
            walls,
            "total − fluid − strip in the row {row}"
        );
    }
}

/// The process of `parent`'s children whose environment says it is MPI rank `rank`.
fn rank_process(parent: u32, rank: usize) -> Option<u32> {
    let wanted = format!("OMPI_COMM_WORLD_RANK={rank}");
    std::fs::read_dir("/proc").ok()?.flatten().find_map(|entry| {
        let pid: u32 = entry.file_name().to_str()?.parse().ok()?;
        let stat = std::fs::read_to_string(entry.path().join("stat")).ok()?;
        // the parent's pid is the second field after the command name's closing parenthesis
        let ppid: u32 = stat.rsplit_once(')')?.1.split_whitespace().nth(1)?.parse().ok()?;
        let environ = std::fs::read(entry.path().join("environ")).ok()?;
        let is_rank = environ.split(|&b| b == 0).any(|v| v == wanted.as_bytes());
        (ppid == parent && is_rank).then_some(pid)
    })
}

/// A rank killed with SIGKILL in the middle of a run: every rank stops within seconds, the
/// launcher names the rank that died and the signal, and the frames written before stay whole.
#[test]
fn a_rank_killed_stops_every_rank_within_seconds_naming_it() {
    let d = dir("mpi-ranks-killed");
    let case = d.join("case.toml");
    // 4 s of the tilted tank (about 3 min on 2 ranks): it is killed long before its end
    let text = TANK
        .replace("end_time = 0.1", "end_time = 4.0")
        .replace("output_interval = 0.05", "output_interval = 0.01");
    assert!(text.contains("end_time = 4.0") && text.contains("output_interval = 0.01"));
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let out = d.join("out");
    let mut child = command(&case, &out, 2)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start mpirun: {e}"));
    let waited = std::time::Instant::now();
    while !out.join("water_00002.pvtu").exists() {
        assert!(waited.elapsed().as_secs() < 120, "no third frame after 120 s");
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let victim = rank_process(child.id(), 1).unwrap_or_else(|| panic!("no process of rank 1 under mpirun"));
    let killed = std::time::Instant::now();
    let status = Command::new("kill")
        .args(["-KILL", &victim.to_string()])
        .status()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(status.success(), "kill -KILL {victim}");
    let stopped = loop {
        if let Some(status) = child.try_wait().unwrap_or_else(|e| panic!("{e}")) {
            break status;
        }
        if killed.elapsed().as_secs() > 30 {
            let _ = child.kill();
            panic!("mpirun still runs 30 s after rank 1 was killed");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    let took = killed.elapsed().as_secs_f64();
    let mut log = String::new();
    if let Some(mut e) = child.stderr.take() {
        let _ = std::io::Read::read_to_string(&mut e, &mut log);
    }
    println!("{log}\nstopped {took:.2} s after the kill: {stopped}");
    assert!(!stopped.success(), "a run with a killed rank must not exit 0");
    assert!(took < 10.0, "every rank stops within seconds: {took} s");
    assert!(
        log.contains("rank 1") && log.contains("signal 9"),
        "the launcher names the rank and the signal: {log}"
    );
    // what was written before the kill is whole: every index names pieces that are there and
    // parse (an index is written once all its pieces are)
    let mut indexes = 0;
    for entry in std::fs::read_dir(&out)
        .unwrap_or_else(|e| panic!("{e}"))
        .flatten()
    {
        let name = entry.file_name().to_string_lossy().into_owned();
        if let Some(frame_name) = name.strip_suffix(".pvtu") {
            indexes += 1;
            for r in 0..2 {
                let piece = frame(&out.join(format!("{frame_name}_r{r:04}.vtu")));
                assert!(!piece.is_empty(), "piece {r} of {name} is empty");
            }
        }
    }
    assert!(indexes >= 3, "the frames before the kill: {indexes}");
}

#[test]
fn a_case_the_ranks_do_not_run_is_refused_once_and_nothing_runs() {
    let d = dir("mpi-ranks-refused");
    let case = d.join("case.toml");
    std::fs::write(&case, case_text("surface_mesh = true")).unwrap_or_else(|e| panic!("{e}"));
    let out = d.join("out");
    let refused = run(&case, &out, 2);
    let log = String::from_utf8_lossy(&refused.stderr);
    println!("{log}");
    assert_eq!(refused.status.code(), Some(2), "{log}");
    assert_eq!(log.matches("not yet surface_mesh = true").count(), 1, "{log}");
    assert!(
        !out.join("water_00000.pvtu").exists(),
        "nothing is written for a refused case"
    );
}

/// The case's end time.
fn cfg_end_time(path: &Path) -> f64 {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{e}"));
    Case::parse(path, text)
        .unwrap_or_else(|e| panic!("{e}"))
        .info
        .end_time
}

/// Cut again on ranks as on the slabs of one process: `ranks.rs`' tilted dam break, whose cut
/// follows the water at step 150 (x = 0.4 → 0.46 m, past a pressure probe and a filtered floor
/// sensor), on 2 ranks to 0.1 s: the ranks count the fluid by bins (an all-reduce), move the
/// cut, hand over the fluid, and pass the sensor's window to its new reader, so the run equals
/// the 2 slabs of one process bit for bit, and rank 0's probe rows equal theirs to the digit.
#[test]
fn two_ranks_cut_again_as_the_water_moves_step_as_two_slabs_bit_for_bit() {
    let d = dir("mpi-ranks-recut");
    let case = d.join("case.toml");
    std::fs::write(&case, crate::ranks::DAM).unwrap_or_else(|e| panic!("{e}"));
    let cfg = crate::ranks::dam();
    let ranked = run(&case, &d.join("ranks"), 2);
    let log = String::from_utf8_lossy(&ranked.stderr);
    println!("{log}");
    assert!(ranked.status.success(), "mpirun -np 2 failed: {log}");
    assert!(
        log.contains("slabs cut again 1 times"),
        "the ranks cut again once: {log}"
    );
    let mut every = Vec::new();
    for r in 0..2 {
        every.extend(frame(&d.join("ranks").join(format!("water_00001_r{r:04}.vtu"))));
    }
    let ranks = fluid_by_id(&every);

    let mut slabs = DecomposedFluid::new(&cfg, 2).unwrap_or_else(|e| panic!("{e}"));
    let interval = cfg.probe_interval.unwrap_or(cfg.output_interval);
    let mut rows = vec![slabs.probe_row()];
    let rows_to_end = (cfg_end_time(&case) / interval).round() as usize;
    for k in 1..=rows_to_end {
        let t = k as f64 * interval;
        while let Some(dt) = slabs.parts()[0].solver.next_step_towards(t) {
            slabs.step(dt).unwrap_or_else(|e| panic!("{e}"));
            slabs.observe_probes(t);
        }
        slabs.land_on(t);
        rows.push(slabs.probe_row());
    }
    assert_eq!(slabs.recuts(), 1, "the slabs cut again once");
    let gap = largest_gap(&ranks, &by_id(&slabs.fluid()));
    println!("2 ranks cut again against 2 slabs in one process: largest gap {gap:.3e} m");
    assert_eq!(gap, 0.0, "bit for bit");
    let csv = std::fs::read_to_string(d.join("ranks/water_probes.csv")).unwrap_or_else(|e| panic!("{e}"));
    let written: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(written.len(), rows.len(), "a row every 5 ms: {csv}");
    for (line, row) in written.iter().zip(&rows) {
        let values: Vec<&str> = line.split(',').skip(1).take(row.len()).collect();
        let expected: Vec<String> = row.iter().map(|v| format!("{v:.6e}")).collect();
        assert_eq!(values, expected, "rank 0's probe row against the slabs'");
    }
}
