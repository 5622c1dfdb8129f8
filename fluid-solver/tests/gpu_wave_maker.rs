//! The wave maker on the GPU path (issue 38): the paddle's particles are placed on the device
//! before each step by the motion the host evaluates for that step (`src/gpu/paddle.rs`,
//! `shaders/paddle.wgsl`), at the instants the CPU path places them (`src/boundaries/paddle.rs`:
//! at t + Δt, with the step's chord velocity), and the water they push ends where the CPU's does
//! within a bound derived from f32 rounding for this scene. A piston makes Goring's solitary
//! wave, a flap regular waves.
//!
//! Each comparison starts while the paddle moves fast: the CPU runs the flume from rest to
//! t0 = 0.48 s, then the CPU and the GPU go on from that state for 80 steps. (From rest, Goring's
//! paddle barely moves in the first 0.2 s, and by then this coarse flume has become chaotic: a CPU
//! run whose state is rounded to f32 after every step parts from the f64 run by 6e-4 m (piston)
//! to 9e-3 m (paddle held) within 300 steps, and the GPU's run parts from it about as fast. Over
//! 80 steps from a common state they stay in the rounding's random walk.) On the CPU alone each
//! paddle moves the water by far more than the bound over those steps, against the same paddle
//! frozen where it stood at t0 (a table of its stroke then), so a GPU that ignored the paddle
//! could not pass. The flap runs again with the device measuring positions from 10⁵ spacings
//! away (wide positions, `gpu_wide_positions.rs`): its paddle is placed by the low parts of its
//! rest positions.

use crate::gpu_common;
use gpu_common::compare::{self, DeviceFrame};

use fluid_solver::{FluidSolver, Kind};
use schemas::case::{Case, FluidConfig};
use schemas::validation::{largest_abs, Record};
use std::collections::HashMap;
use std::path::Path;
use std::time::Instant;

/// Steps on the CPU from rest to the shared start t0 = 0.48 s, and steps compared from there.
const BEFORE: usize = 300;
const STEPS: usize = 80;

/// The bound on |r_gpu − r_cpu| of a fluid particle after [`STEPS`] steps from a common state,
/// derived as `gpu_common/compare.rs` derives the slab's (unit roundoff u = 2⁻²⁴ ≈ 6.0e-8),
/// restated for this scene (Δs = 0.02 m, c = 6 m/s, Δt = 1.6e-3 s, N = 80 steps, t = 0.128 s):
/// - a number density sums K ≈ 300 candidates: u √K = 1.0e-6 of n0; the paddle's particles
///   stand at f32 positions (rest + shift, x ≤ 0.3 m: rounded by up to 1e-8 m = 5e-7 Δs, which
///   moves a neighbour's w(r) by about as much of n0): together 1.2e-6 of n0;
/// - S1-14 makes that δP = c² ρ0 · 1.2e-6 = 36 · 1000 · 1.2e-6 = 0.043 Pa;
/// - S1-3 gives δa ≈ 2 d δP / (ρ0 Δs) = 6 · 0.043 / 20 = 0.013 m/s² per step, of random sign;
/// - over N = 80 steps the velocity walks to δu = δa Δt √N = 0.013 · 1.6e-3 · 8.9 = 1.9e-4 m/s
///   and the position to δu t/√3 = 1.9e-4 · 0.128 / 1.73 = 1.4e-5 m (the positions' own
///   rounding, 0.8 m · u = 4.8e-8 m per step, adds √80 · 4.8e-8 = 4e-7 m; the start's rounding
///   to f32 is of that size too).
///
/// So 2e-5 m = 1e-3 Δs, the slab's bound (its 200 steps of 5e-4 s give 1.8e-5 m the same way).
/// A paddle placed at the step's start instead of its end is off by its speed × Δt, about
/// 0.35 · 1.6e-3 = 5.6e-4 m, at every step.
const POSITION_BOUND: f64 = 2.0e-5;

/// The paddle's own particles: the CPU sets x = rest + X(t + Δt) (or the turned rest) in f64; the
/// device adds f32 rest, shift and turn: three roundings of at most 0.5 u |x| ≤ 0.5 · 6e-8 ·
/// 0.3 m = 9e-9 m each, 2.7e-8 m; 1e-7 m leaves a margin of about 4.
const PADDLE_POSITION_BOUND: f64 = 1.0e-7;

/// The paddle's velocities: the host's f64 speed and chord rates, rounded to f32 and combined
/// with f32 arms in three products and sums: a few u of |v| ≤ 0.5 m/s, 1e-7 m/s; 1e-6 m/s leaves
/// a margin of about 10.
const PADDLE_VELOCITY_BOUND: f64 = 1.0e-6;

/// The walls' impulse over the compared steps (the paddle's push included) is a sum of f32 pair
/// terms: relative rounding u √(terms) ≈ 6e-8 · √(10⁶) = 6e-5 per step, and the positions'
/// differences shift the pressure pairs by δP/P ≈ 1.2e-6 · c² ρ0 / (ρ0 g d) = 4e-5: 1e-3 of the
/// largest component leaves a margin of about 10 (`gpu_common/compare.rs`'s bound).
const IMPULSE_BOUND: f64 = compare::IMPULSE_BOUND;

/// The paddle must move the water by more than this many [`POSITION_BOUND`]s on the CPU.
const VISIBLE: f64 = 100.0;

/// A quasi-2-D flume 0.8 m long and two particles wide at Δs = 0.02 m, 0.1 m of still water in
/// front of a paddle 4 particles (`wall_layers`) thick at x = `paddle_x` … `paddle_x` + 0.08 m,
/// c = 6 m/s, Δt = 1.6e-3 s (c Δt/Δs = 0.48); `wave_maker` is the rest of the `[wave_maker]`
/// table (`table` files go into `dir`). About 6 300 particles, 370 of them fluid.
fn flume(dir: &Path, paddle_x: f64, wave_maker: &str) -> FluidConfig {
    let front = paddle_x + 0.08;
    let text = format!(
        r#"[case]
name = "flume"
end_time = 0.608

[fluid.flume]
spacing = 0.02
time_step = 1.6e-3
sound_speed = 6.0
output_interval = 0.1
tank = {{ min = [0.0, 0.0, 0.0], max = [0.8, 0.04, 0.2] }}

[fluid.flume.wave_maker]
min = [{paddle_x}, 0.0, 0.0]
max = [{front}, 0.04, 0.2]
depth = 0.1
{wave_maker}

[[fluid.flume.block]]
min = [{front}, 0.0, 0.0]
max = [0.8, 0.04, 0.1]
"#
    );
    let case = Case::parse(&dir.join("case.toml"), text).unwrap_or_else(|e| panic!("{e}"));
    case.fluid["flume"].clone()
}

/// `cfg`'s paddle frozen where its motion has it at `t0`: a table of that stroke (written to
/// `dir`), the rest of the `[wave_maker]` table `rest`.
fn frozen(dir: &Path, cfg: &FluidConfig, t0: f64, paddle_x: f64, rest: &str) -> FluidConfig {
    let motion = cfg
        .wave_maker
        .as_ref()
        .and_then(|w| w.built.clone())
        .unwrap_or_else(|| panic!("no wave maker"));
    let x0 = motion.stroke(t0);
    std::fs::write(
        dir.join("frozen.csv"),
        format!("t, X\n0.0, {x0:e}\n1.0, {x0:e}\n"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    flume(
        dir,
        paddle_x,
        &format!("{rest}motion = \"table\"\ntable = \"frozen.csv\""),
    )
}

/// The largest differences of the paddle's particles between `cpu` and `gpu` (position [m],
/// velocity [m/s], largest component), over the particles whose id is in `paddle`, and how many
/// there were.
fn paddle_difference(cpu: &FluidSolver, gpu: &FluidSolver, paddle: &[u32]) -> (f64, f64, usize) {
    let (c, g) = (cpu.particles(), gpu.particles());
    let at: HashMap<u32, usize> = (0..g.len()).map(|j| (g.id[j], j)).collect();
    let (mut dr, mut dv, mut seen) = (0.0f64, 0.0f64, 0);
    for i in (0..c.len()).filter(|&i| paddle.contains(&c.id[i])) {
        let j = at[&c.id[i]];
        assert_eq!(g.kind[j], Kind::Wall.code());
        let (a, b) = (c.position(i), g.position(j));
        let (u, w) = (c.velocity(i), g.velocity(j));
        for k in 0..3 {
            dr = schemas::validation::max_or_nan(dr, (a[k] - b[k]).abs());
            dv = schemas::validation::max_or_nan(dv, (u[k] - w[k]).abs());
        }
        seen += 1;
    }
    (dr, dv, seen)
}

/// The ids of the paddle's particles: the walls inside its box at rest (x from `paddle_x` over
/// 0.08 m, inside the tank's width, above its floor).
fn paddle_ids(cfg: &FluidConfig, paddle_x: f64) -> Vec<u32> {
    let solver = FluidSolver::new(cfg);
    let p = solver.particles();
    (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Wall.code())
        .filter(|&i| p.x[i] > paddle_x && p.x[i] < paddle_x + 0.08)
        .filter(|&i| p.y[i] > 0.0 && p.y[i] < 0.04 && p.z[i] > 0.0)
        .map(|i| p.id[i])
        .collect()
}

/// Runs `cfg` on the CPU to t0, then on both paths for [`STEPS`] steps (the device in `frame`);
/// checks the fluid, the paddle and the walls' impulse against their bounds, and on the CPU that
/// the paddle moved the water (against `still`, the paddle frozen at t0); records the rows
/// `gpu-<tag>-vs-cpu-…`.
fn check(
    cfg: &FluidConfig,
    still: &FluidConfig,
    (paddle_x, frame): (f64, DeviceFrame),
    (tag, capability, scene, source): (&str, &str, &str, &str),
) {
    let Some(dev) = gpu_common::device() else {
        return;
    };
    let device = dev.description();
    let t = Instant::now();
    let mut before = FluidSolver::new(cfg);
    for _ in 0..BEFORE {
        before.step(cfg.time_step).unwrap_or_else(|e| panic!("CPU: {e}"));
    }
    let state = before.save_state();
    let t_before = t.elapsed().as_secs_f64();
    let (cpu, t_cpu) = compare::run_from(cfg, &state, None, STEPS, |_| ());
    let (gpu, t_gpu) = compare::run_from(cfg, &state, Some((dev, frame)), STEPS, |_| ());
    let (held, _) = compare::run_from(still, &state, None, STEPS, |_| ());
    println!(
        "{} particles: {BEFORE} steps on the CPU to t0 = {:.3} s in {t_before:.2} s, then {STEPS} steps: CPU {t_cpu:.2} s, GPU {t_gpu:.2} s",
        cpu.particle_count(),
        state.time
    );
    let paddle = paddle_ids(cfg, paddle_x);
    let worst = compare::largest_fluid_distance(cpu.particles(), gpu.particles());
    let (dr, dv, seen) = paddle_difference(&cpu, &gpu, &paddle);
    let start = state.totals.wall_impulse;
    let (ic, ig) = (cpu.totals().wall_impulse, gpu.totals().wall_impulse);
    let impulse = largest_abs((0..3).map(|a| ig[a] - ic[a])) / largest_abs((0..3).map(|a| ic[a] - start[a]));
    let moved = compare::largest_fluid_distance(cpu.particles(), held.particles());
    println!(
        "largest fluid position difference {worst:.3e} m (bound {POSITION_BOUND:e}); {seen} paddle particles: position {dr:.3e} m (bound {PADDLE_POSITION_BOUND:e}), velocity {dv:.3e} m/s (bound {PADDLE_VELOCITY_BOUND:e}); the walls' impulse over the steps differs by {impulse:.3e} of its largest component (bound {IMPULSE_BOUND:e}); the paddle moves the water by up to {moved:.3e} m on the CPU against it frozen"
    );
    let row = Record {
        capability: format!("{capability} on the GPU (f32)"),
        reference: "the CPU's f64 step from the same state".into(),
        case: scene.into(),
        resolution: "E-MPS, Δs = 0.02 m".into(),
        source: format!("fluid-solver/tests/{source}"),
        run_time_s: t.elapsed().as_secs_f64(),
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
                "f32 rounding carried through the equation of state over the steps (gpu_wave_maker.rs)",
                "m",
            ),
            (
                "paddle",
                "largest component of |r_gpu − r_cpu| over the paddle's particles",
                dr,
                PADDLE_POSITION_BOUND,
                "f32 rounding of the paddle's placement (gpu_wave_maker.rs)",
                "m",
            ),
            (
                "wall-impulse",
                "largest |impulse_gpu − impulse_cpu| of the walls over the steps / its largest component",
                impulse,
                IMPULSE_BOUND,
                "f32 rounding of the pair sums, with a margin of about 10 (gpu_common/compare.rs)",
                "",
            ),
        ],
    );
    assert!(
        seen > 0 && seen == paddle.len(),
        "{seen} paddle particles of {}",
        paddle.len()
    );
    assert!(
        worst < POSITION_BOUND,
        "a fluid particle is {worst:.3e} m from its CPU position (bound {POSITION_BOUND:e} m)"
    );
    assert!(
        dr < PADDLE_POSITION_BOUND && dv < PADDLE_VELOCITY_BOUND,
        "a paddle particle is {dr:.3e} m from its CPU position, {dv:.3e} m/s from its CPU velocity"
    );
    assert!(
        impulse < IMPULSE_BOUND,
        "the walls' impulse differs by {impulse:.3e} of its largest component (bound {IMPULSE_BOUND:e})"
    );
    assert!(
        moved > VISIBLE * POSITION_BOUND,
        "the paddle moved the water by only {moved:.3e} m: the comparison could not see it"
    );
}

/// A piston making Goring's solitary wave of H = 0.05 m on d = 0.1 m (H/d = 0.5): from
/// t0 = 0.48 s it moves at about 0.35 m/s, 4.5 cm over the 80 compared steps.
#[test]
fn gpu_piston_solitary_wave_matches_cpu() {
    let dir = compare::folder("wave-maker-piston");
    let cfg = flume(&dir, 0.0, "motion = \"solitary\"\nwave_height = 0.05");
    let still = frozen(&dir, &cfg, 0.48, 0.0, "");
    check(
        &cfg,
        &still,
        (0.0, DeviceFrame::Corner),
        (
            "piston",
            "E-MPS with a piston wave maker",
            "a 0.8 × 0.04 m flume, 0.1 m of water, a piston making Goring's solitary wave H = 0.05 m: 300 steps of 1.6e-3 s on the CPU, then 80 on both",
            "gpu_wave_maker.rs::gpu_piston_solitary_wave_matches_cpu",
        ),
    );
}

/// A flap hinged at the floor at its front face (x = 0.18 m), making regular waves of
/// H = 0.03 m and T = 0.6 s started over 0.15 s: from t0 = 0.48 s, near its backmost, it swings
/// forward through its upright position.
#[test]
fn gpu_flap_regular_waves_match_cpu() {
    flap_regular_waves(DeviceFrame::Corner);
}

/// The flap of [`gpu_flap_regular_waves_match_cpu`] with the device measuring positions from
/// 10⁵ spacings away (wide positions): the same bounds.
#[test]
fn gpu_flap_regular_waves_match_cpu_in_wide_positions() {
    flap_regular_waves(DeviceFrame::Far);
}

fn flap_regular_waves(frame: DeviceFrame) {
    let dir = compare::folder(&format!("wave-maker-flap-{frame:?}"));
    let flap = "kind = \"flap\"\nhinge_z = 0.0\n";
    let cfg = flume(
        &dir,
        0.1,
        &format!("{flap}motion = \"regular\"\nwave_height = 0.03\nperiod = 0.6\nramp = 0.15"),
    );
    let still = frozen(&dir, &cfg, 0.48, 0.1, flap);
    let (tag, capability, source) = match frame {
        DeviceFrame::Corner => (
            "flap",
            "E-MPS with a flap wave maker",
            "gpu_wave_maker.rs::gpu_flap_regular_waves_match_cpu",
        ),
        DeviceFrame::Far => (
            "flap-wide",
            "E-MPS with a flap wave maker in wide positions 10⁵ spacings from the frame's origin",
            "gpu_wave_maker.rs::gpu_flap_regular_waves_match_cpu_in_wide_positions",
        ),
    };
    check(
        &cfg,
        &still,
        (0.1, frame),
        (
            tag,
            capability,
            "a 0.8 × 0.04 m flume, 0.1 m of water, a flap hinged at the floor making regular waves H = 0.03 m, T = 0.6 s (ramp 0.15 s): 300 steps of 1.6e-3 s on the CPU, then 80 on both",
            source,
        ),
    );
}
