//! Issue 38 item 4: ISPH on the device (`method = "isph"`, `backend = "gpu"`, fluid-solver's
//! `gpu/isph.rs`) against ISPH on the CPU, on the CI dam break of `isph_slab` (Δs = L/10, 800
//! fluid particles, the default settings): step by step from the same start, from a frame 2 km
//! away (wide positions), and its surge front against the experiments with the CPU test's bounds.
//!
//! The device solves the PPE by Jacobi-preconditioned CG in f32 (the CPU by the two-level
//! preconditioner in f64); both stop at the relative tolerance 1e-6.

use crate::front_common;
use crate::front_record::{self, FrontRecord};
use crate::gpu_common::{self, compare};
use crate::isph_slab::isph_slab;
use compare::DeviceFrame;
use fluid_solver::FluidSolver;
use schemas::case::fluid::FluidBackend;
use schemas::validation::Record;
use std::time::Instant;

/// Steps of the step-by-step comparison: 0.016 s of the collapse.
const STEPS: usize = 10;

/// The bound on |r_gpu − r_cpu| of a fluid particle after [`STEPS`] steps (Δs = 0.0146 m,
/// Δt = 1.6e-3 s):
/// - f32 rounds a position by u · 0.58 m = 3.5e-8 m (u = 2⁻²⁴ ≈ 6e-8, the tank's length), each
///   step: 3.5e-7 m over 10 steps;
/// - both solves stop at the relative residual 1e-6: δp ≈ 1e-6 · ρ g 2L ≈ 3e-3 Pa, an
///   acceleration δp/(ρ Δs) = 2e-4 m/s², 3e-8 m over the run;
/// - a particle that S2-11's thresholds or the umbrella put on the free surface in f32 and not in
///   f64 (or the reverse) takes, for a step, its Dirichlet value instead of its solved pressure:
///   at most ρ g Δs/2 = 72 Pa, an acceleration of δp/(ρ Δs) = 4.9 m/s² and a move of
///   4.9 · Δt² = 1.3e-5 m.
///
/// So one such flag within the run stays inside 1.3e-5 m (9e-4 Δs); measured 1.0e-7 m on
/// lavapipe (one flag differed at the 10th step: 0.75 Pa). A gradient 1 % of g off moves a
/// particle by ½ · 0.098 · (0.016 s)² = 1.3e-5 m in these steps, a missing pair term by far more.
const POSITION_BOUND: f64 = 1.3e-5;

/// The walls' impulse over the run: f32 pair sums (relative u √terms ≈ 6e-5 a step), and one
/// flag as above on a wall's neighbour: 72 Pa on Δs² = 2.1e-4 m², 0.015 N of the walls' 5 N
/// (3e-3); measured 2e-5.
const IMPULSE_BOUND: f64 = 3.0e-3;

/// The slab for the GPU (the CPU run of the comparison ignores the backend).
fn slab_on_the_gpu() -> schemas::case::FluidConfig {
    let mut cfg = isph_slab();
    cfg.backend = FluidBackend::Gpu;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}

/// Runs the slab for [`STEPS`] steps on the CPU and on the GPU (positions measured from
/// `frame`), checks the positions and the walls' impulse against their bounds and records both.
fn compare_steps(frame: DeviceFrame, tag: &str, test: &str) {
    let cfg = slab_on_the_gpu();
    let Some(runs) = compare::run_both_in(&cfg, STEPS, frame) else {
        return;
    };
    let worst = compare::largest_fluid_distance(runs.cpu.particles(), runs.gpu.particles());
    let impulse = compare::wall_impulse_difference(&runs);
    let (ppe_cpu, ppe_gpu) = (runs.cpu.totals().ppe_iterations, runs.gpu.totals().ppe_iterations);
    println!(
        "largest position difference {worst:.3e} m (bound {POSITION_BOUND:e}); walls' impulse CPU {:?}, GPU {:?} N s: {impulse:.3e} (bound {IMPULSE_BOUND:e}); PPE iterations CPU {ppe_cpu}, GPU {ppe_gpu}",
        runs.cpu.totals().wall_impulse,
        runs.gpu.totals().wall_impulse
    );
    let row = Record {
        capability: "ISPH on the GPU (f32)".into(),
        reference: "the CPU's f64 ISPH step from the same start".into(),
        case: "the ISPH CI dam break (Koshizuka & Oka's column, L/10, slab 4 particles deep), 10 steps of 1.6e-3 s".into(),
        resolution: "ISPH defaults, Δs = 0.0146 m".into(),
        source: format!("fluid-solver/tests/gpu_isph.rs::{test}"),
        run_time_s: runs.run_time_s,
        machine: format!("{}; {}", runs.device, schemas::validation::machine()),
        ..Default::default()
    };
    compare::record_measures(
        &row,
        |what| format!("gpu-{tag}-vs-cpu-{what}"),
        &[
            (
                "positions",
                "largest |r_gpu − r_cpu| over the fluid particles",
                worst,
                POSITION_BOUND,
                "f32 rounding and one surface flag decided differently (gpu_isph.rs)",
                "m",
            ),
            (
                "wall-impulse",
                "largest |impulse_gpu − impulse_cpu| of the walls / the largest component",
                impulse,
                IMPULSE_BOUND,
                "f32 pair sums and one surface flag beside a wall (gpu_isph.rs)",
                "",
            ),
        ],
    );
    assert!(
        worst < POSITION_BOUND,
        "a fluid particle is {worst:.3e} m from its CPU position (bound {POSITION_BOUND:e} m)"
    );
    assert!(
        impulse < IMPULSE_BOUND,
        "the walls' impulse differs by {impulse:.3e} of its largest component (bound {IMPULSE_BOUND:e})"
    );
    assert!(
        ppe_gpu >= STEPS as u64,
        "the device reported {ppe_gpu} PPE iterations over {STEPS} steps"
    );
    // the steps moved the water by far more than the bound: the comparison sees the flow
    let start = FluidSolver::new(&cfg);
    let moved = compare::largest_fluid_distance(start.particles(), runs.cpu.particles());
    assert!(
        moved > 100.0 * POSITION_BOUND,
        "the column moved by only {moved:e} m"
    );
}

#[test]
fn isph_on_the_gpu_follows_the_cpu_step_by_step() {
    compare_steps(
        DeviceFrame::Corner,
        "isph",
        "isph_on_the_gpu_follows_the_cpu_step_by_step",
    );
}

#[test]
fn isph_on_the_gpu_keeps_its_precision_100_000_spacings_from_the_frame_origin() {
    compare_steps(
        DeviceFrame::Far,
        "isph-wide",
        "isph_on_the_gpu_keeps_its_precision_100_000_spacings_from_the_frame_origin",
    );
}

/// The surge front of ISPH on the device against Koshizuka & Oka and Martin & Moyce, with the
/// CPU test's setting and bounds (`isph_dam_break.rs`): the whole collapse to the far wall,
/// landing steps on the samples' times included.
#[test]
fn isph_surge_front_on_the_gpu_follows_the_experiments() {
    let Some(gpu) = gpu_common::device().map(|d| d.description()) else {
        return;
    };
    let cfg = slab_on_the_gpu();
    let started = Instant::now();
    let e = front_common::front_errors(&cfg, 0.006, 4);
    front_record::record(
        &e,
        &FrontRecord {
            method: "gpu-isph",
            scale: "l10",
            capability: "ISPH dam-break front on the GPU (f32)",
            resolution: "ISPH defaults on the GPU, Δs = L/10 = 0.0146 m, slab 4 particles deep (800 fluid), Δt = 1.6e-3 s",
            source: "fluid-solver/tests/gpu_isph.rs::isph_surge_front_on_the_gpu_follows_the_experiments",
            bounds: [0.33, 0.05],
            bound_source: "the CPU ISPH test's (isph_dam_break.rs), those of E-MPS at this resolution",
            run_time_s: started.elapsed().as_secs_f64(),
            machine: format!("{gpu}; {}", schemas::validation::machine()),
        },
    );
    front_common::assert_within_the_e_mps_bounds(&e, true);
}
