//! The fluid in slabs ([`fluid_solver::ranks`]) against the undivided solver: a 3 m flume 30 cm
//! deep at Δs = 0.01 m (about 270 000 fluid particles; the viscous term off, as in the seed's
//! tank) in 1, 2, 4 and 8 slabs along x, stepped in one process. Prints, per slab count: particles stepped (every slab's own fluid, halo copies and
//! walls) against the undivided run's, halo copies and their bytes per step (69 B of state a
//! particle), fluid handed over per step, and wall time per step. On this machine's cores the
//! slabs share the threads, so the time shows what the halos cost, not what ranks would gain;
//! run on a many-core machine for that.

use fluid_solver::particles::STATE_BYTES_PER_PARTICLE;
use fluid_solver::ranks::decomposed::DecomposedFluid;
use fluid_solver::FluidSolver;
use schemas::case::{Case, FluidConfig};
use std::path::Path;
use std::time::Instant;

/// Steps timed per run (after 5 untimed).
const STEPS: u32 = 20;

fn flume() -> Result<FluidConfig, String> {
    let text = r#"[case]
name = "flume"
end_time = 1.0

[fluid.water]
spacing = 0.01
time_step = 5.0e-4
sound_speed = 12.1
viscosity_term = false
gravity = [0.5, 0.0, -9.8]
output_interval = 1.0
tank = { min = [0.0, 0.0, 0.0], max = [3.0, 0.3, 0.5], lid = true }

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [3.0, 0.3, 0.3]
"#;
    let case = Case::parse(Path::new("flume.toml"), text.to_string()).map_err(|e| e.to_string())?;
    Ok(case.fluid["water"].clone())
}

fn main() {
    let cfg = match flume() {
        Ok(c) => c,
        Err(e) => {
            println!("error: {e}");
            return;
        }
    };
    let dt = cfg.time_step;
    let mut whole = FluidSolver::new(&cfg);
    let n = whole.particles().len();
    for _ in 0..5 {
        if let Err(e) = whole.step(dt) {
            println!("error: {e}");
            return;
        }
    }
    let t = Instant::now();
    for _ in 0..STEPS {
        if let Err(e) = whole.step(dt) {
            println!("error: {e}");
            return;
        }
    }
    let undivided = t.elapsed().as_secs_f64() / f64::from(STEPS);
    println!(
        "3 m flume, Δs = 0.01 m, {n} particles, {} threads",
        rayon::current_num_threads()
    );
    println!("| slabs | particles stepped / undivided | halo copies per step | halo bytes per step | handed over per step | wall per step |");
    println!("|---|---|---|---|---|---|");
    println!("| 1 (undivided) | 1.00 | 0 | 0 | 0 | {:.1} ms |", 1e3 * undivided);
    for parts in [2, 4, 8] {
        let mut d = match DecomposedFluid::new(&cfg, parts) {
            Ok(d) => d,
            Err(e) => {
                println!("| {parts} | error: {e} |");
                continue;
            }
        };
        for _ in 0..5 {
            if let Err(e) = d.step(dt) {
                println!("| {parts} | error: {e} |");
                continue;
            }
        }
        let (copied, handed) = (d.copied(), d.handed_over());
        let t = Instant::now();
        for _ in 0..STEPS {
            if let Err(e) = d.step(dt) {
                println!("| {parts} | error: {e} |");
                return;
            }
        }
        let wall = t.elapsed().as_secs_f64() / f64::from(STEPS);
        let stepped: usize = d.parts().iter().map(|s| s.solver.particles().len()).sum();
        let per_step = |k: u64| k as f64 / f64::from(STEPS);
        let copies = per_step(d.copied() - copied);
        println!(
            "| {parts} | {:.2} | {copies:.0} | {:.1} MB | {:.0} | {:.1} ms |",
            stepped as f64 / n as f64,
            copies * STATE_BYTES_PER_PARTICLE as f64 / 1e6,
            per_step(d.handed_over() - handed),
            1e3 * wall
        );
    }
}
