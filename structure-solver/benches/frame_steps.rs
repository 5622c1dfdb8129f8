//! Newmark steps per second of ASI-Gauss frames of about 1 000, 10 000 and 100 000 DOFs (cubic
//! building grids, fixed at the base), elastic and with plastic hinges forming, with ASI-Gauss's one
//! solve per step (the default) and, for comparison, with equilibrium corrections in every step; with
//! hinges forming, one solve per step also at Δt = 0.5 ms, where it agrees with the iterated steps.
//! Besides the numeric factorisations per step (and those that assembled the matrix anew), the table
//! gives the products with the effective matrix in the conjugate-gradient solves that follow hinges
//! forming or closing (the kept factor as preconditioner).
//! Run: `cargo bench -p structure-solver --bench frame_steps [grid sizes, e.g. 3 7] [elastic|hinges]
//! [one|iterated] [steps=N]` (`steps=N` times N steps in every chosen row instead of the defaults,
//! e.g. for a short run under callgrind).

#[path = "../tests/frame_common/mod.rs"]
mod frame_common;

use frame_common::building;
use std::time::Instant;
use structure_solver::frame::{Equilibrium, Frame};

/// Untimed steps at most while waiting for the first hinge.
const WARM_UP_LIMIT: usize = 300;

/// CPU time used by this process so far [s], from /proc/self/stat (utime + stime, in Linux's
/// USER_HZ = 100 ticks per second); `None` where that file is not available. On a shared machine
/// this is steadier than wall time (rayon's idle spinning counts in it, so it is an upper bound).
fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // fields after the command name (which is in parentheses and may hold spaces)
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let ticks = |i: usize| fields.get(i)?.parse::<f64>().ok();
    Some((ticks(11)? + ticks(12)?) / 100.0)
}

/// What one timed run measured.
struct Measured {
    dofs: usize,
    steps_per_second: f64,
    cpu_ms_per_step: Option<f64>,
    factorizations_per_step: f64,
    /// Those of them that assembled the matrix anew.
    assemblies_per_step: f64,
    /// Products with the effective matrix in preconditioned conjugate gradients per step.
    cg_iterations_per_step: f64,
    hinge_nodes: usize,
    /// Largest unbalanced force left by a timed step, as a share of its first one.
    worst_unbalance: f64,
    /// Timed steps that did not converge (iterated) or left more than 10 % of their unbalanced
    /// force (one solve).
    unconverged_steps: u64,
}

/// Times `steps` steps of `dt` under a lateral load of `lateral` N on every node (after the first
/// hinges formed, in the plastic case).
fn run(
    n: usize,
    steps: usize,
    dt: f64,
    yield_stress: f64,
    lateral: f64,
    equilibrium: Equilibrium,
) -> Result<Measured, String> {
    let mut cfg = building(n, yield_stress);
    cfg.time_step = dt;
    let mut frame =
        Frame::from_config(&cfg, "bench.frame").map_err(|e| format!("{}: {}", e.key, e.message))?;
    frame.set_equilibrium(equilibrium)?;
    let loads = frame_common::sideways_loads(frame.node_count(), lateral);
    // untimed: one step, and for the plastic case on until the first hinges have formed
    frame.step(frame.time_step(), &loads)?;
    for _ in 0..WARM_UP_LIMIT {
        if yield_stress > 1e11 || !frame.hinge_nodes().is_empty() {
            break;
        }
        frame.step(frame.time_step(), &loads)?;
    }
    let solves0 = frame.factorization_count();
    let assemblies0 = frame.assembly_count();
    let cg0 = frame.cg_iteration_count();
    let unconverged0 = frame.unconverged_steps();
    let mut worst_unbalance = 0.0_f64;
    let cpu0 = process_cpu_seconds();
    let start = Instant::now();
    for _ in 0..steps {
        frame.step(frame.time_step(), &loads)?;
        worst_unbalance = worst_unbalance.max(frame.last_unbalance());
    }
    let seconds = start.elapsed().as_secs_f64();
    let cpu_ms_per_step = cpu0
        .zip(process_cpu_seconds())
        .map(|(a, b)| 1e3 * (b - a) / steps as f64);
    Ok(Measured {
        dofs: 6 * frame.node_count(),
        steps_per_second: steps as f64 / seconds,
        cpu_ms_per_step,
        factorizations_per_step: (frame.factorization_count() - solves0) as f64 / steps as f64,
        assemblies_per_step: (frame.assembly_count() - assemblies0) as f64 / steps as f64,
        cg_iterations_per_step: (frame.cg_iteration_count() - cg0) as f64 / steps as f64,
        hinge_nodes: frame.hinge_nodes().len(),
        worst_unbalance,
        unconverged_steps: frame.unconverged_steps() - unconverged0,
    })
}

fn main() {
    // grid sizes and case names ("elastic", "hinges") from the command line (cargo bench adds
    // `--bench`), by default all
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    let chosen: Vec<usize> = args.iter().filter_map(|a| a.parse().ok()).collect();
    let steps_override: Option<usize> = args
        .iter()
        .find_map(|a| a.strip_prefix("steps=").and_then(|s| s.parse().ok()));
    let words: Vec<&String> = args
        .iter()
        .filter(|a| a.parse::<usize>().is_err() && !a.starts_with("steps="))
        .collect();
    let cases: Vec<&String> = words
        .iter()
        .copied()
        .filter(|a| !["one", "iterated"].contains(&a.as_str()))
        .collect();
    let modes: Vec<&String> = words
        .iter()
        .copied()
        .filter(|a| ["one", "iterated"].contains(&a.as_str()))
        .collect();
    println!(
        "| grid | DOFs | case | steps | steps/s | ms/step | CPU ms/step | factorisations/step (assembled anew) | CG products/step \
         | hinge nodes | worst unbalance | unconverged steps |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    let iterate = Equilibrium::Iterate { tolerance: 1e-6 };
    for (n, steps) in [(3, 400), (7, 200), (15, 20)] {
        if !chosen.is_empty() && !chosen.contains(&n) {
            continue;
        }
        // elastic: steel that never yields; hinges: σy = 20 MPa and 20 kN on every node sideways
        for (case, yield_stress, lateral) in [("elastic", 1e12, 1e3), ("hinges forming", 2e7, 2e4)] {
            if !cases.is_empty() && !cases.iter().any(|c| case.starts_with(c.as_str())) {
                continue;
            }
            // while hinges form, one solve per step needs Δt ≈ 0.5 ms here to agree with the iterated
            // steps (see ONE_SOLVE_UNBALANCE_LIMIT): that row shows the speed at an accurate Δt
            let half_step = yield_stress < 1e11;
            for (mode, equilibrium, steps, dt) in [
                ("one solve", Equilibrium::OneSolve, steps, 1e-3),
                (
                    "one solve, Δt = 0.5 ms",
                    Equilibrium::OneSolve,
                    if half_step { steps } else { 0 },
                    5e-4,
                ),
                ("iterated", iterate, steps / 4, 1e-3),
            ] {
                if steps == 0 || !modes.is_empty() && !modes.iter().any(|m| mode.starts_with(m.as_str())) {
                    continue;
                }
                let steps = steps_override.unwrap_or(steps);
                match run(n, steps, dt, yield_stress, lateral, equilibrium) {
                    Ok(m) => println!(
                        "| {n}×{n}×{n} | {} | {case} | {mode} | {:.1} | {:.2} | {} | {:.2} ({:.2}) | {:.2} | {} | {:.1e} | {} |",
                        m.dofs,
                        m.steps_per_second,
                        1e3 / m.steps_per_second,
                        m.cpu_ms_per_step.map_or("–".to_string(), |c| format!("{c:.2}")),
                        m.factorizations_per_step,
                        m.assemblies_per_step,
                        m.cg_iterations_per_step,
                        m.hinge_nodes,
                        m.worst_unbalance,
                        m.unconverged_steps
                    ),
                    Err(e) => println!("| {n}×{n}×{n} | – | {case} | {mode} | failed: {e} | | | | | | | |"),
                }
            }
        }
    }
}
