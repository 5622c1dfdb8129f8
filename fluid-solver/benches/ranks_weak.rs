//! Weak scaling of the fluid on MPI ranks (issue 39; feature `mpi`, OpenMPI's `mpirun` on the
//! path): a flume 0.3 m deep whose length grows with the ranks (each rank's slab 0.6 m of water
//! at Δs = 0.01 m, about 18 000 fluid particles), E-MPS, one thread per rank, run with
//! `mpirun -np N fluid-solver run` (one rank: the undivided solver in this process, on one
//! thread, as `mpirun -np 1` runs it). Prints per rank count: fluid particles per rank, time per
//! step (rank 0's stepping, exchanges included; frames and set-up left out), weak-scaling
//! efficiency t(1)/t(N), the slowest rank's own step and the longest a rank spent a step in its
//! exchanges and waits, halo copies and bytes sent between ranks per step. With more ranks than
//! cores (`--oversubscribe`) the times show correctness and communication volume, not speed.
//! Then, on paper from the one-rank rate and the efficiency measured with a core per rank, the
//! ranks and hours for 10⁸ and 10⁹ particles over 10⁴ steps, ranks of 10⁶ particles each.
//!
//! `cargo bench -p fluid-solver --features mpi --bench ranks_weak [-- RANKS…]` (default 1 2 4 8).

use fluid_solver::FluidSolver;
use schemas::case::Case;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// Water along x per rank [m].
const SLAB: f64 = 0.6;
/// Steps per run.
const STEPS: usize = 20;
/// Δt [s].
const DT: f64 = 5.0e-4;
/// Fluid particles per rank on paper (a rank's share of a large run).
const RANK_SIZE: f64 = 1.0e6;

/// The flume for `ranks` ranks.
fn case_text(ranks: usize) -> String {
    let length = SLAB * ranks as f64;
    format!(
        r#"[case]
name = "weak"
end_time = {end}

[fluid.water]
spacing = 0.01
time_step = {DT}
sound_speed = 12.1
viscosity_term = false
gravity = [0.5, 0.0, -9.8]
output_interval = {end}
tank = {{ min = [0.0, 0.0, 0.0], max = [{length}, 0.1, 0.4], lid = true }}

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [{length}, 0.1, 0.3]
"#,
        end = STEPS as f64 * DT
    )
}

/// What one run on ranks printed in its closing line.
struct Run {
    ranks: usize,
    fluid: f64,
    steps: f64,
    copies: f64,
    bytes: f64,
    step_seconds: f64,
    /// The most a rank spent in its own steps, and in its exchanges and waits [s].
    own_most: f64,
    exchange_most: f64,
    wall: f64,
}

/// The number just before `label` in `line` ("… 918 fluid particles, …").
fn number_before(line: &str, label: &str) -> Option<f64> {
    let at = line.find(label)?;
    line[..at]
        .split_whitespace()
        .last()?
        .trim_start_matches('(')
        .parse()
        .ok()
}

/// The upper end of the range `A–B` that follows `label` in `line`.
fn range_end_after(line: &str, label: &str) -> Option<f64> {
    let rest = &line[line.find(label)? + label.len()..];
    let range = rest.split_whitespace().next()?;
    range.split('–').nth(1)?.parse().ok()
}

/// One rank: the undivided solver stepped here on a pool of one thread.
fn undivided() -> Result<Run, String> {
    let started = Instant::now();
    let case = Case::parse(Path::new("weak-1.toml"), case_text(1)).map_err(|e| e.to_string())?;
    let cfg = &case.fluid["water"];
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .map_err(|e| e.to_string())?;
    pool.install(|| {
        let mut solver = FluidSolver::new(cfg);
        solver.remove_gates();
        let stepping = Instant::now();
        for _ in 0..STEPS {
            solver.step(DT).map_err(|e| e.to_string())?;
        }
        Ok(Run {
            ranks: 1,
            fluid: solver.particles().count(fluid_solver::Kind::Fluid) as f64,
            steps: STEPS as f64,
            copies: 0.0,
            bytes: 0.0,
            step_seconds: stepping.elapsed().as_secs_f64(),
            own_most: stepping.elapsed().as_secs_f64(),
            exchange_most: 0.0,
            wall: started.elapsed().as_secs_f64(),
        })
    })
}

fn run(ranks: usize, dir: &Path) -> Result<Run, String> {
    if ranks == 1 {
        return undivided();
    }
    let case = dir.join(format!("weak-{ranks}.toml"));
    std::fs::write(&case, case_text(ranks)).map_err(|e| format!("{}: {e}", case.display()))?;
    let solver = env!("CARGO_BIN_EXE_fluid-solver");
    let started = Instant::now();
    let out = Command::new("mpirun")
        .args(["-np", &ranks.to_string(), "--oversubscribe", solver, "run"])
        .arg(&case)
        .arg("--out")
        .arg(dir.join(format!("out-{ranks}")))
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .env("RAYON_NUM_THREADS", "1")
        .output()
        .map_err(|e| format!("cannot start mpirun (is OpenMPI installed?): {e}"))?;
    let wall = started.elapsed().as_secs_f64();
    let log = String::from_utf8_lossy(&out.stderr);
    let done = log
        .lines()
        .find(|l| l.contains("done:"))
        .ok_or_else(|| format!("{ranks} ranks: no closing line:\n{log}"))?;
    let field = |label: &str| {
        number_before(done, label).ok_or_else(|| format!("{ranks} ranks: no `{label}` in: {done}"))
    };
    Ok(Run {
        ranks,
        fluid: field("fluid particles")?,
        steps: field("steps on")?,
        copies: field("halo copies")?,
        bytes: field("bytes sent")?,
        step_seconds: field("s in the steps")?,
        own_most: range_end_after(done, "own steps ")
            .ok_or_else(|| format!("{ranks} ranks: no own steps' range in: {done}"))?,
        exchange_most: range_end_after(done, "exchanges and waits ")
            .ok_or_else(|| format!("{ranks} ranks: no exchanges' range in: {done}"))?,
        wall,
    })
}

fn main() {
    let mut counts: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .filter(|&n| n > 0)
        .collect();
    if counts.is_empty() {
        counts = vec![1, 2, 4, 8];
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("ranks-weak");
    if let Err(e) = std::fs::create_dir_all(&dir) {
        println!("error: {}: {e}", dir.display());
        return;
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!("Weak scaling on MPI ranks: {SLAB} m of water per rank at Δs = 0.01 m, {STEPS} steps, one thread per rank, {cores} cores here");
    println!(
        "| ranks | fluid per rank | time per step | efficiency t(1)/t(N) | a rank's own step (slowest) | exchanges and waits (longest) | halo copies per step | bytes sent per step | wall (with set-up) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut runs: Vec<Run> = Vec::new();
    for &n in &counts {
        match run(n, &dir) {
            Ok(r) => {
                let per_step = r.step_seconds / r.steps;
                let base = runs.first().map_or(per_step, |b| b.step_seconds / b.steps);
                println!(
                    "| {} | {:.0} | {:.1} ms | {:.0} % | {:.1} ms | {:.1} ms | {:.0} | {:.2} MB | {:.1} s |",
                    r.ranks,
                    r.fluid / r.ranks as f64,
                    1e3 * per_step,
                    100.0 * base / per_step,
                    1e3 * r.own_most / r.steps,
                    1e3 * r.exchange_most / r.steps,
                    r.copies / r.steps,
                    r.bytes / r.steps / 1e6,
                    r.wall
                );
                runs.push(r);
            }
            Err(e) => {
                println!("error: {e}");
                return;
            }
        }
    }
    let (Some(one), Some(last)) = (runs.first(), runs.iter().rev().find(|r| r.ranks <= cores)) else {
        return;
    };
    // on paper: ranks of RANK_SIZE fluid particles, each stepping at the one-rank rate per
    // particle times the efficiency measured with a core per rank
    let rate = one.fluid / (one.step_seconds / one.steps);
    let efficiency = (one.step_seconds / one.steps) / (last.step_seconds / last.steps);
    let per_step = RANK_SIZE / rate / efficiency;
    let copies = runs.iter().map(|r| r.copies).sum::<f64>();
    let bytes_per_copy = runs.iter().map(|r| r.bytes).sum::<f64>() / copies.max(1.0);
    println!();
    println!(
        "On paper: ranks of {RANK_SIZE:.0e} fluid particles, each at the one-rank rate ({rate:.3e} particle-steps/s on a core) and the {:.0} % efficiency measured on {} ranks with a core each: {:.2} s a step. A halo copy costs {bytes_per_copy:.0} B; a rank sends the fluid within a halo (8.0 Δs in this flume without the viscous term, docs/guide/ranks.md) of each inner face a step.",
        100.0 * efficiency,
        last.ranks,
        per_step
    );
    println!("| particles | ranks | hours for 10⁴ steps |");
    println!("|---|---|---|");
    for total in [1e8, 1e9] {
        println!(
            "| {total:.0e} | {:.0} | {:.1} |",
            (total / RANK_SIZE).ceil(),
            1e4 * per_step / 3600.0
        );
    }
    let last = runs.last().map_or(0, |r| r.ranks);
    if last > cores {
        println!("(more ranks than the {cores} cores here: the times above share cores; run on a machine with a core per rank for speed)");
    }
}
