//! The ISPH pressure Poisson equation at growing size: a cube of water of side 0.1 m at rest in a
//! tank that fits it (hydrostatic), at spacings giving about 1e4, 1e5 and (with `--large`) 1e6
//! unknowns. For each: unknowns, the first solve (from the initial pressure, in
//! `FluidSolver::new`) and the solves of the following steps (warm-started from the last
//! pressure): iterations, seconds per solve and the relative residual reached against the case's
//! tolerance, for Jacobi-PCG, block-SGS-PCG and two-level PCG (multiplicative and additive). Jacobi-PCG's iterations grow as
//! the condition number's square root, ∝ 1/Δs ∝ n^(1/3), and its time per solve as n^(4/3); the
//! two-level ones' stay about constant (its coarse matrix grows with n).
//!
//! `cargo bench -p fluid-solver --bench ppe_scaling -- [--large] [--only=SOLVER] [steps]` (default 2
//! steps; `--only=` one of the table's solver names).

use fluid_solver::method::MethodState;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{FluidConfig, FluidMethodName, IsphConfig, PpeSolver};
use schemas::case::Case;
use std::path::PathBuf;
use std::time::Instant;

mod bench_process;
use bench_process::{cpu_seconds, load_average};

/// Side of the cube of water [m].
const SIDE: f64 = 0.1;

fn case(ds: f64, solver: PpeSolver) -> FluidConfig {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../cases/dam-break-koshizuka/case.toml");
    let case = Case::load(&path).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1)
    });
    let Some(mut cfg) = case.fluid.values().next().cloned() else {
        eprintln!("error: the dam-break case has no fluid");
        std::process::exit(1)
    };
    cfg.spacing = ds;
    cfg.tank.max = [SIDE, SIDE, 1.5 * SIDE];
    cfg.block[0].max = [SIDE, SIDE, SIDE];
    cfg.probe.clear();
    cfg.method = FluidMethodName::Isph;
    cfg.sound_speed = None;
    cfg.isph = Some(IsphConfig {
        ppe_solver: solver,
        ..IsphConfig::default()
    });
    cfg.time_step = 0.3 * ds / cfg.advective_velocity();
    if let Err(e) = cfg.validate("fluid.water") {
        eprintln!("error: {e:?}");
        std::process::exit(1);
    }
    cfg
}

/// The last PPE solve's (iterations, residual, unknowns).
fn last_solve(s: &FluidSolver) -> (u32, f64, usize) {
    match s.method_state() {
        MethodState::Isph(st) => (st.ppe.iterations, st.ppe.residual, st.ppe.unknowns),
        MethodState::Emps => (0, 0.0, 0),
    }
}

fn main() {
    let all: Vec<String> = std::env::args().skip(1).collect();
    let large = all.iter().any(|a| a == "--large");
    let only = all.iter().find_map(|a| a.strip_prefix("--only="));
    let steps: u64 = all
        .iter()
        .filter(|a| !a.starts_with("--"))
        .find_map(|s| s.parse().ok())
        .unwrap_or(2);
    // n ≈ (SIDE/Δs)³: 21.5³ ≈ 1e4, 46.4³ ≈ 1e5, 100³ = 1e6.
    let mut spacings = vec![SIDE / 21.5, SIDE / 46.4];
    if large {
        spacings.push(SIDE / 100.0);
    }
    println!(
        "ISPH PPE, hydrostatic cube of {SIDE} m, {} threads",
        rayon::current_num_threads()
    );
    println!("solver      Δs [m]    fluid    unknowns  solve       iterations  PPE wall [s]  step CPU [s]  residual  tolerance  load");
    for (ds, (name, solver)) in spacings
        .iter()
        .flat_map(|&ds| {
            [
                ("jacobi-pcg", PpeSolver::JacobiPcg),
                ("sgs-pcg", PpeSolver::SgsPcg),
                ("two-level", PpeSolver::TwoLevelPcg),
                ("additive", PpeSolver::AdditiveTwoLevelPcg),
            ]
            .map(|s| (ds, s))
        })
        .filter(|(_, (name, _))| only.is_none_or(|o| o == *name))
    {
        let cfg = case(ds, solver);
        let tol = cfg.isph.map_or(0.0, |c| c.ppe_tolerance);
        let (t, cpu0) = (Instant::now(), cpu_seconds());
        let mut solver = FluidSolver::new(&cfg);
        let (setup, setup_cpu) = (t.elapsed().as_secs_f64(), cpu_seconds() - cpu0);
        let fluid = solver.particles().count(Kind::Fluid);
        let (it, res, n) = last_solve(&solver);
        println!(
            "{name:10}  {ds:.5}  {fluid:7}  {n:8}  initial     {it:10}  ({setup:10.2})  ({setup_cpu:10.2})  {res:8.1e}  {tol:9.0e}  {}",
            load_average()
        );
        for k in 1..=steps {
            let before = solver.stage_times().seconds("PPE solve");
            let dt = solver.time_step();
            let cpu0 = cpu_seconds();
            if let Err(e) = solver.step(dt) {
                eprintln!("error: step {k} at Δs = {ds}: {e}");
                std::process::exit(1);
            }
            let secs = solver.stage_times().seconds("PPE solve") - before;
            let cpu = cpu_seconds() - cpu0;
            let (it, res, n) = last_solve(&solver);
            println!(
                "{name:10}  {ds:.5}  {fluid:7}  {n:8}  step {k:<5}  {it:10}  {secs:12.3}  {cpu:12.2}  {res:8.1e}  {tol:9.0e}  {}",
                load_average()
            );
        }
    }
    println!("(the initial row's times, in parentheses, are the whole set-up: layout, search, first solve)");
}
