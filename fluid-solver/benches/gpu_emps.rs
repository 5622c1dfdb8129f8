//! Speed of the GPU path (src/gpu) on the seed's dam-break tank: particle-steps per second, GPIPS
//! (interacting pairs per second, as GPU SPH codes report it) and pair candidates examined per
//! second (with the pairs beyond the kernel's reach), time
//! per stage (each stage submitted and waited for, so the sum is above the plain step) and the
//! bytes crossing between host and device per step and per probe window (0.01 s).
//!
//! On a real GPU: Δs = 0.01 m and 0.005 m to t = 0.25 s (the time to solution), and
//! 0.003 m for ≥ 1 M particles (the goal: ≥ 2e8 particle-steps/s there), that size
//! again in wide positions (the device measuring from 10⁵ spacings away, as a tank that long holds
//! its far end: src/gpu/frame.rs) to price them. With only a software Vulkan device (lavapipe)
//! it says so and runs one small size each way to check that the path works; its numbers are not
//! GPU speed.

use fluid_solver::gpu::GpuDevice;
use fluid_solver::neighbours::interacting_pairs::interacting_pairs;
use fluid_solver::FluidSolver;
use schemas::case::fluid::FluidConfig;
use schemas::case::Case;
use std::path::PathBuf;
use std::time::Instant;

/// The seed's tank at spacing `ds`, `depth` deep (the seed's 0.45 m, or a slab), open 30 cm
/// walls as in the CPU benchmark, Δt scaled with Δs (c Δt/Δs = 0.6).
fn tank(base: &FluidConfig, ds: f64, depth: f64) -> FluidConfig {
    let mut cfg = base.clone();
    cfg.spacing = ds;
    cfg.time_step = 5.0e-4 * ds / 0.01;
    cfg.tank.max[1] = depth;
    cfg.tank.max[2] = 0.3;
    cfg.tank.lid = false;
    cfg.block[0].max[1] = depth.min(0.3);
    cfg.gate[0].max[1] = depth.min(0.3);
    cfg.probe.clear();
    cfg
}

/// How far before the tank the device's frame lies for a run in wide positions, in spacings.
const WIDE_SPACINGS: f64 = 1.0e5;

/// Runs the tank at `ds`, `depth` deep, for `steps` steps (then 20 profiled), in wide positions
/// when `wide`, and prints its speed.
fn run(base: &FluidConfig, ds: f64, depth: f64, steps: u64, wide: bool) {
    let cfg = tank(base, ds, depth);
    let dev = match GpuDevice::open() {
        Ok(d) => d,
        Err(e) => {
            println!("error: {e}");
            return;
        }
    };
    let setup = Instant::now();
    let mut solver = FluidSolver::new(&cfg);
    let started = match wide {
        false => solver.to_device(&cfg, dev),
        true => {
            let lo = cfg.tank.min;
            solver.to_device_from(&cfg, dev, [lo[0] - WIDE_SPACINGS * ds, lo[1], lo[2]])
        }
    };
    if let Err(e) = started {
        println!("error: {e}");
        return;
    }
    let setup = setup.elapsed().as_secs_f64();
    let n = solver.particle_count() as u64;
    let dt = cfg.time_step;
    let before = solver.totals().candidates;
    let start = Instant::now();
    for _ in 0..steps {
        if let Err(e) = solver.step(dt) {
            println!("error: {e}");
            return;
        }
    }
    let plain = start.elapsed().as_secs_f64();
    let candidates = solver.totals().candidates - before;
    let interactions = interactions_per_step(&mut solver, &cfg);
    let Some(d) = solver.device_mut() else { return };
    let (up0, down0) = d.bytes_moved();
    d.set_profile(true);
    let profiled = steps.min(20);
    for _ in 0..profiled {
        if let Err(e) = solver.step(dt) {
            println!("error: {e}");
            return;
        }
    }
    let Some(d) = solver.device() else { return };
    let (up1, down1) = d.bytes_moved();
    let per_step = (up1 - up0 + down1 - down0) as f64 / profiled as f64;
    let window = (0.01 / dt).round();
    let positions = match wide {
        true => "wide positions, 10⁵ spacings from the frame's origin",
        false => "plain f32 positions",
    };
    println!(
        "Δs = {ds} m ({positions}), {n} particles, {steps} steps: {:.3e} particle-steps/s ({:.2} ms/step); {:.3} GPIPS ({interactions} interacting pairs a step: a fluid particle and a neighbour within r_e, in the number density, pressure gradient and, when on, viscous passes, counted at the run's end); {:.3} G pair candidates/s (every pair the passes examine, those beyond r_e included)",
        (n * steps) as f64 / plain,
        1e3 * plain / steps as f64,
        (interactions * steps) as f64 / plain / 1e9,
        candidates as f64 / plain / 1e9
    );
    println!(
        "  set-up (particles placed on the host, uploaded) {setup:.2} s; {steps} steps = {:.3} s of flow in {:.2} s wall; device memory {:.1} MB, {:.0} B per particle ({} cells of the grid included)",
        steps as f64 * dt,
        setup + plain,
        d.device_bytes() as f64 / 1e6,
        d.device_bytes() as f64 / n as f64,
        solver.cell_grid().cell_count()
    );
    println!(
        "  host↔device per step: {per_step:.0} B (reduction partials + uniforms); per 0.01 s probe window ({window} steps): {:.0} B + one particle copy of {} B",
        per_step * window,
        n * 44
    );
    println!("  time per stage (each waited for), ms/step:");
    for (name, s) in d.stage_times().stages().iter().filter(|(n, _)| *n != "step") {
        println!("    {name:<24} {:8.3}", 1e3 * s / profiled as f64);
    }
}

/// The pairs the step's pair passes sum over, counted on the particles as they are now (a whole
/// copy from the device): the number density's (r_e), the pressure gradient's (r_e of the
/// gradient), and the viscous term's (r_e) when it is on; the collision stage's few close pairs
/// are left out.
fn interactions_per_step(solver: &mut FluidSolver, cfg: &FluidConfig) -> u64 {
    solver.sync_host();
    let (p, grid, k) = (solver.particles(), solver.cell_grid(), solver.kernel());
    let density = interacting_pairs(p, grid, k.re);
    let gradient = interacting_pairs(p, grid, k.re_grad);
    density * (1 + u64::from(cfg.viscosity_term)) + gradient
}

fn main() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../cases/dam-break-tank/case.toml");
    let case = match Case::load(&path) {
        Ok(c) => c,
        Err(e) => {
            println!("error: {e}");
            return;
        }
    };
    let Some(base) = case.fluid.values().next().cloned() else {
        println!("error: the case has no fluid section");
        return;
    };
    let software = match GpuDevice::open() {
        Ok(d) => {
            println!("device: {}", d.description());
            d.is_software()
        }
        Err(e) => {
            println!("no GPU: {e}\nGPU speed: not measured");
            return;
        }
    };
    if software {
        println!("only a software Vulkan device is present: GPU speed not measured; one small size to check that the path works");
        run(&base, 0.02, 0.1, 50, false);
        run(&base, 0.02, 0.1, 50, true);
    } else {
        // The seed's tank to t = 0.25 s (the time to solution), then ≥ 1 M particles.
        run(&base, 0.01, 0.45, 500, false);
        run(&base, 0.005, 0.45, 1000, false);
        run(&base, 0.003, 0.45, 300, false);
        run(&base, 0.003, 0.45, 300, true);
        run(&base, 0.0025, 0.45, 200, false);
    }
}
