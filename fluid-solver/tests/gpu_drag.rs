//! The unresolved drag coupling's fluid side on the GPU path (issue 38 item 3,
//! `src/gpu/drag.rs`): the slab's column collapses through a member standing in it whose
//! reactions the device spreads each step (points and a wide member's footprint), beside a
//! reaction whose centroid is dry (spread around its sample point) and one with no water near
//! either point (not applied). Against the CPU from the same start: the fluid within the f32
//! bound of `gpu_common/compare.rs`, the impulse booked as handed to the fluid and as not
//! applied equal to the CPU's (the same reactions took the same path every step), and the flow
//! sampled at the end at points inside the water, at its surface and in the air within bounds
//! derived from the positions' and velocities' f32 differences. The reactions move the water far
//! more than the bound on the CPU. The same again with the device measuring positions from 10⁵
//! spacings away (wide positions, `gpu_wide_positions.rs`): points, centroids and particles in
//! two parts.

use gpu_common::compare::{self, DeviceFrame, POSITION_BOUND, STEPS};

use crate::gpu_common;
use fluid_solver::FluidSolver;
use schemas::validation::{largest_abs, max_or_nan, Record};

/// A member 0.06 m wide (3 particles: a footprint of half-width 0.02 m) standing at x = 0.08 m
/// in the column's lower part, its sub-members 0.02 m apart, each pushing the water by −0.4 N
/// along x and 0.2 N up; its sample points 0.04 m upstream (−x).
fn member() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut reactions = Vec::new();
    let mut points = Vec::new();
    let mut widths = Vec::new();
    for k in 0..5 {
        let z = 0.03 + 0.02 * k as f64;
        reactions.extend([0.08, 0.03, z, -0.4, 0.0, 0.2]);
        points.extend([0.04, 0.03, z]);
        widths.push(if k % 2 == 0 { 0.06 } else { 0.0 });
    }
    // dry centroid above the water, its sample point in the column: spread around the point
    reactions.extend([0.3, 0.03, 0.27, 0.0, 0.0, -0.3]);
    points.extend([0.06, 0.03, 0.06]);
    widths.push(0.0);
    // both points in the air above the far end: not applied
    reactions.extend([0.36, 0.03, 0.27, 0.1, 0.0, 0.0]);
    points.extend([0.36, 0.03, 0.25]);
    widths.push(0.0);
    // no force: not spread
    reactions.extend([0.08, 0.03, 0.05, 0.0, 0.0, 0.0]);
    points.extend([0.04, 0.03, 0.05]);
    widths.push(0.0);
    (reactions, points, widths)
}

/// Where the flow is sampled at the end: inside the water near the floor, near the collapsing
/// front, at the column's surface, and in the air.
const SAMPLE_POINTS: [f64; 12] = [
    0.05, 0.03, 0.03, //
    0.2, 0.03, 0.02, //
    0.06, 0.03, 0.16, //
    0.3, 0.03, 0.25,
];

/// The sampled velocity's bound: a sample is a Shepard average of the particles' velocities, each
/// within δu = 3.1e-4 m/s of the CPU's (the random walk of the f32 equation of state that
/// POSITION_BOUND is derived from, `gpu_common/compare.rs`), with weights W(|x_j − x|) shifted by
/// the positions' difference δx ≤ 2e-5 m: |δW/W| ≤ |W'/W| δx ≈ 5 δx / R = 8e-4 near the
/// support's edge (R = 2.4 Δs = 0.048 m), times |u| ≲ 1 m/s. Together 1.1e-3 m/s: 2e-3 m/s.
const VELOCITY_BOUND: f64 = 2.0e-3;

/// λ_min's bound: the moment matrix Σ V W'(r)/r d ⊗ d is a sum of terms of order V |W'| r ≈ 0.1
/// each (it is 1 for a full support of ~60 particles, most weight on ~20) moved by δx/Δs = 1e-3
/// relative each, and f32 rounding (6e-8 × √60) is far below: 60 × 0.1 × 1e-3 = 6e-3 at worst,
/// of random sign over the terms: 1e-2.
const LAMBDA_BOUND: f64 = 1.0e-2;

/// The impulse booked by the two paths must be the same sums of F Δt (f64 on both) when every
/// reaction took the same path each step: to round-off of ~1e3 additions, 1e-12 relative.
const BOOKED_BOUND: f64 = 1.0e-12;

/// Steps `solver` with the member's reactions handed over before each step.
fn run(mut solver: FluidSolver, dt: f64) -> FluidSolver {
    let (reactions, points, widths) = member();
    for _ in 0..STEPS {
        solver.set_point_reactions(&reactions, &points, &widths);
        solver.step(dt).unwrap_or_else(|e| panic!("{e}"));
    }
    solver
}

#[test]
fn gpu_drag_spreading_and_sampling_match_cpu() {
    drag_spreading_and_sampling(DeviceFrame::Corner);
}

#[test]
fn gpu_drag_spreading_and_sampling_match_cpu_in_wide_positions() {
    drag_spreading_and_sampling(DeviceFrame::Far);
}

fn drag_spreading_and_sampling(frame: DeviceFrame) {
    let dir = compare::folder(&format!("drag-{frame:?}"));
    let cfg = compare::slab(&dir, "");
    let Some(dev) = gpu_common::device() else {
        return;
    };
    let device = dev.description();
    let started = std::time::Instant::now();
    let cpu = run(FluidSolver::new(&cfg), cfg.time_step);
    let mut gpu = FluidSolver::new(&cfg);
    compare::to_device(&mut gpu, &cfg, dev, frame);
    let gpu = run(gpu, cfg.time_step);
    // sampled on the device, before its particles come back
    let (gpu_u, gpu_lambda) = gpu.sample_points(&SAMPLE_POINTS);
    let mut gpu = gpu;
    gpu.sync_host();
    let (cpu_u, cpu_lambda) = cpu.sample_points(&SAMPLE_POINTS);
    let run_time_s = started.elapsed().as_secs_f64();
    println!("samples CPU u {cpu_u:?} λ {cpu_lambda:?}\n        GPU u {gpu_u:?} λ {gpu_lambda:?}");

    let worst = compare::largest_fluid_distance(cpu.particles(), gpu.particles());
    let du = cpu_u
        .iter()
        .zip(&gpu_u)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, max_or_nan);
    let dl = cpu_lambda
        .iter()
        .zip(&gpu_lambda)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, max_or_nan);
    let (c, g) = (cpu.totals(), gpu.totals());
    let booked = |a: [f64; 3], b: [f64; 3]| {
        largest_abs((0..3).map(|k| a[k] - b[k])) / largest_abs(a).max(f64::MIN_POSITIVE)
    };
    let handed = booked(c.reaction_impulse, g.reaction_impulse);
    let unapplied = booked(c.unapplied_impulse, g.unapplied_impulse);
    println!(
        "positions {worst:.3e} m; samples: velocity {du:.3e} m/s, λ_min {dl:.3e}; reactions' impulse CPU {:?} GPU {:?}, not applied CPU {:?} GPU {:?}",
        c.reaction_impulse, g.reaction_impulse, c.unapplied_impulse, g.unapplied_impulse
    );
    let (tag, wide, test) = match frame {
        DeviceFrame::Corner => ("drag", "", "gpu_drag_spreading_and_sampling_match_cpu"),
        DeviceFrame::Far => (
            "drag-wide",
            " in wide positions 10⁵ spacings from the frame's origin",
            "gpu_drag_spreading_and_sampling_match_cpu_in_wide_positions",
        ),
    };
    let row = Record {
        capability: format!("Unresolved drag coupling, the fluid's side, on the GPU (f32){wide}"),
        reference: "the CPU's f64 step from the same start".into(),
        case: "the slab's column (0.4 × 0.06 × 0.3 m tank) collapsing through a member's 8 reactions (points, a 0.06 m footprint, one around its sample point, one not applied, one without force), 200 steps of 5e-4 s; the flow sampled at 4 points at the end".into(),
        resolution: "E-MPS, Δs = 0.02 m".into(),
        source: format!("fluid-solver/tests/gpu_drag.rs::{test}"),
        run_time_s,
        machine: format!("{device}; {}", schemas::validation::machine()),
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
                "f32 rounding carried through the equation of state over the steps (gpu_common/compare.rs)",
                "m",
            ),
            (
                "sampled-velocity",
                "largest |u_gpu − u_cpu| of the sampled velocity over the points and axes",
                du,
                VELOCITY_BOUND,
                "the particles' velocity and position differences through the Shepard average (gpu_drag.rs)",
                "m/s",
            ),
            (
                "sampled-lambda",
                "largest |λ_gpu − λ_cpu| of λ_min over the points",
                dl,
                LAMBDA_BOUND,
                "the positions' difference through the moment matrix's terms (gpu_drag.rs)",
                "",
            ),
            (
                "reaction-impulse",
                "largest |impulse_gpu − impulse_cpu| of the reactions handed to the fluid / the largest component",
                handed,
                BOOKED_BOUND,
                "the same f64 sums of F Δt when every reaction took the same path (gpu_drag.rs)",
                "",
            ),
        ],
    );
    assert!(
        worst < POSITION_BOUND,
        "a fluid particle is {worst:.3e} m from its CPU position"
    );
    assert!(
        du < VELOCITY_BOUND,
        "the sampled velocities differ by {du:.3e} m/s"
    );
    assert!(dl < LAMBDA_BOUND, "λ_min differs by {dl:.3e}");
    assert!(
        handed < BOOKED_BOUND && unapplied < BOOKED_BOUND,
        "the impulse booked differs: handed to the fluid {handed:.3e}, not applied {unapplied:.3e} of the CPU's"
    );
    // every kind of reaction was exercised: the dry one's impulse was booked as not applied,
    // and the one spread around its sample point pushed down (−0.3 N over the run)
    let t = cpu.time();
    assert!(
        (c.unapplied_impulse[0] - 0.1 * t).abs() < 1e-12,
        "the reaction with no water near was booked {:?} N s as not applied, not 0.1 N × {t} s",
        c.unapplied_impulse
    );
    let down = 5.0 * 0.2 * t - 0.3 * t;
    assert!(
        (c.reaction_impulse[2] - down).abs() < 1e-9,
        "the fluid took {:?} N s upward, not the member's 5 × 0.2 N less the moved reaction's 0.3 N over {t} s",
        c.reaction_impulse
    );
    // the samples see water, a surface and air where they should
    assert!(
        cpu_lambda[0] > 0.8 && cpu_lambda[3] == 0.0,
        "λ_min at the points: {cpu_lambda:?}"
    );
    let bare = compare::run_cpu(&cfg, STEPS);
    compare::assert_visible("the drag coupling", &cpu, &bare);
}
