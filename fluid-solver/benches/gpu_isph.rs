//! Speed of ISPH on the GPU (src/gpu/isph.rs) against E-MPS on the same device, on the seed's
//! dam-break tank (its open 30 cm walls, as `gpu_emps`): time to solution to the same flow time,
//! particle-steps/s and fluid-particle-steps/s, the PPE's iterations per step, and GPIPS
//! (interacting pairs per second, as GPU SPH codes report it: here the fluid's pairs within the
//! support summed over the step's pair passes, ten fixed ones and two per CG iteration and for the
//! solve's start).
//!
//! Each method takes the largest Δt the case check accepts for it: E-MPS the seed's (scaled with
//! Δs), ISPH its advective limit `0.4 Δs / 2√(gH)` (and shorter steps where the flow outruns it).
//!
//! On a real GPU: Δs = 0.01 m and 0.005 m to t = 0.25 s, then 0.003 m (≥ 1 M particles; the
//! issue's goal for ISPH: ≥ 1e8 fluid-particle-steps/s there). With only a software Vulkan device
//! (lavapipe) it says so and runs one small size to check that the path works; its numbers are
//! not GPU speed.

use fluid_solver::gpu::GpuDevice;
use fluid_solver::neighbours::interacting_pairs::interacting_pairs;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{FluidBackend, FluidConfig, FluidMethodName, IsphConfig};
use schemas::case::Case;
use std::path::PathBuf;
use std::time::Instant;

/// The seed's tank at spacing `ds`, `depth` deep, open 30 cm walls, with `method` at its largest
/// accepted Δt.
fn tank(base: &FluidConfig, ds: f64, depth: f64, method: FluidMethodName) -> FluidConfig {
    let mut cfg = base.clone();
    cfg.spacing = ds;
    cfg.time_step = 5.0e-4 * ds / 0.01;
    cfg.tank.max[1] = depth;
    cfg.tank.max[2] = 0.3;
    cfg.tank.lid = false;
    cfg.block[0].max[1] = depth.min(0.3);
    cfg.gate[0].max[1] = depth.min(0.3);
    cfg.probe.clear();
    cfg.backend = FluidBackend::Gpu;
    if method == FluidMethodName::Isph {
        cfg.method = method;
        cfg.isph = Some(IsphConfig::default());
        cfg.sound_speed = None;
        cfg.time_step = cfg.isph_time_step_limit();
    }
    cfg
}

/// What one run measured.
struct Speed {
    wall: f64,
    steps: u64,
    particles: u64,
    fluid: u64,
    ppe_iterations: u64,
    pairs: u64,
}

/// Runs `cfg` to `t_end` on the device; `None` (said) when it cannot.
fn run(cfg: &FluidConfig, t_end: f64) -> Option<Speed> {
    let dev = GpuDevice::open().map_err(|e| println!("error: {e}")).ok()?;
    let mut solver = FluidSolver::new(cfg);
    solver
        .to_device(cfg, dev)
        .map_err(|e| println!("error: {e}"))
        .ok()?;
    let (particles, fluid) = (
        solver.particle_count() as u64,
        solver.particles().count(Kind::Fluid) as u64,
    );
    let start = Instant::now();
    solver
        .advance_to(t_end)
        .map_err(|e| println!("error: {e}"))
        .ok()?;
    let wall = start.elapsed().as_secs_f64();
    let totals = solver.totals();
    solver.sync_host();
    let radius = match cfg.method {
        FluidMethodName::Isph => cfg.isph_settings().support() * cfg.spacing,
        FluidMethodName::Emps => solver.kernel().re,
    };
    let pairs = interacting_pairs(solver.particles(), solver.cell_grid(), radius);
    Some(Speed {
        wall,
        steps: solver.steps(),
        particles,
        fluid,
        ppe_iterations: totals.ppe_iterations,
        pairs,
    })
}

/// Both methods on the tank at `ds`, `depth` deep, to `t_end`.
fn compare(base: &FluidConfig, ds: f64, depth: f64, t_end: f64) {
    println!("Δs = {ds} m, the tank {depth} m deep, to t = {t_end} s:");
    for method in [FluidMethodName::Emps, FluidMethodName::Isph] {
        let cfg = tank(base, ds, depth, method);
        let Some(s) = run(&cfg, t_end) else { return };
        let steps = s.steps as f64;
        let (passes, name) = match method {
            // number density, gradient (and the viscous pass when on)
            FluidMethodName::Emps => (2.0 + f64::from(u8::from(cfg.viscosity_term)), "E-MPS"),
            // ten fixed passes, two per CG iteration and two for the solve's start
            FluidMethodName::Isph => (12.0 + 2.0 * s.ppe_iterations as f64 / steps, "ISPH"),
        };
        println!(
            "  {name:<5} Δt = {:.2e} s, {} particles ({} fluid), {} steps in {:.2} s: {:.3e} particle-steps/s, {:.3e} fluid-particle-steps/s, {:.1} PPE iterations a step, {:.3} GPIPS ({} interacting pairs at the end × {passes:.1} passes a step)",
            cfg.time_step,
            s.particles,
            s.fluid,
            s.steps,
            s.wall,
            s.particles as f64 * steps / s.wall,
            s.fluid as f64 * steps / s.wall,
            s.ppe_iterations as f64 / steps,
            s.pairs as f64 * passes * steps / s.wall / 1e9,
            s.pairs,
        );
    }
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
        compare(&base, 0.02, 0.1, 0.05);
    } else {
        compare(&base, 0.01, 0.45, 0.25);
        compare(&base, 0.005, 0.45, 0.25);
        compare(&base, 0.003, 0.45, 0.05);
    }
}
