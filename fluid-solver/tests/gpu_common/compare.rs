//! One small case on the CPU and on the GPU from the same start: the scene the feature tests of
//! the GPU path share (a dam-break slab that `extra` keys add solids, zones or terms to), the two
//! runs, and how far apart their fluid ends up.

use fluid_solver::particles::Particles;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::{Case, FluidConfig};
use schemas::validation::{record, Record};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Steps of the slab's runs: 0.1 s of the collapse at Δt = 5e-4 s.
pub const STEPS: usize = 200;

/// The bound on |r_gpu − r_cpu| of a fluid particle after [`STEPS`] steps of the slab, derived
/// as `gpu_dam_break.rs` derives its own from f32 rounding (u = 2⁻²⁴ ≈ 6.0e-8): a number density
/// sums K ≈ 300 candidates, u √K ≈ 1.0e-6 of n0; S1-14 makes that δP = c² ρ0 · 1.0e-6 = 0.15 Pa
/// at c = 12.1 m/s; S1-3 gives δa ≈ 2 d δP / (ρ0 Δs) = 0.044 m/s² per step of random sign; over
/// N = 200 steps of Δt = 5e-4 s the velocity walks to δu = δa Δt √N = 3.1e-4 m/s and the
/// position to δu t/√3 = 1.8e-5 m. So 2e-5 m = 1e-3 Δs (the same scene size, spacing, sound
/// speed, step and steps as `gpu_dam_break.rs`'s slab).
pub const POSITION_BOUND: f64 = 2.0e-5;

/// A feature must move the fluid by more than this many [`POSITION_BOUND`]s (the CPU with it
/// against the CPU without it) for the comparison to see it at all.
pub const VISIBLE: f64 = 100.0;

/// A fresh folder for a test's case files.
pub fn folder(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("gpu-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

/// The slab: a 0.4 × 0.06 × 0.3 m tank with its lid at Δs = 0.02 m (three particles deep), a
/// water column 0.16 m wide and 0.24 m high on its left (288 fluid particles, about 7 300 in
/// all), c = 12.1 m/s (the seed's), Δt = 5e-4 s; `extra` is appended to the section (its files
/// are in `dir`).
pub fn slab(dir: &Path, extra: &str) -> FluidConfig {
    slab_at(dir, extra, [0.0; 3])
}

/// The [`slab`] with every position moved by `away` [m].
pub fn slab_at(dir: &Path, extra: &str, away: [f64; 3]) -> FluidConfig {
    let at = |p: [f64; 3]| format!("[{}, {}, {}]", p[0] + away[0], p[1] + away[1], p[2] + away[2]);
    let text = format!(
        r#"[case]
name = "slab"
end_time = 0.1

[fluid.water]
spacing = 0.02
time_step = 5.0e-4
sound_speed = 12.1
output_interval = 0.05
tank = {{ min = {}, max = {}, lid = true }}

[[fluid.water.block]]
min = {}
max = {}
{extra}"#,
        at([0.0, 0.0, 0.0]),
        at([0.4, 0.06, 0.3]),
        at([0.0, 0.0, 0.0]),
        at([0.16, 0.06, 0.24])
    );
    let case = Case::parse(&dir.join("case.toml"), text).unwrap_or_else(|e| panic!("{e}"));
    case.fluid["water"].clone()
}

/// The two runs of one case after the same steps.
pub struct Runs {
    pub cpu: FluidSolver,
    pub gpu: FluidSolver,
    /// The GPU in words; the wall time of both runs [s].
    pub device: String,
    pub run_time_s: f64,
}

/// Runs `cfg` for `steps` steps on the CPU and on the GPU (`None`: no adapter, skipped).
pub fn run_both(cfg: &FluidConfig, steps: usize) -> Option<Runs> {
    run_both_in(cfg, steps, DeviceFrame::Corner)
}

/// [`run_both`] with the device measuring positions from `frame`.
pub fn run_both_in(cfg: &FluidConfig, steps: usize, frame: DeviceFrame) -> Option<Runs> {
    let dev = super::device()?;
    let device = dev.description();
    let t = Instant::now();
    let cpu = run_cpu(cfg, steps);
    let t_cpu = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let mut gpu = FluidSolver::new(cfg);
    to_device(&mut gpu, cfg, dev, frame);
    for _ in 0..steps {
        gpu.step(cfg.time_step).unwrap_or_else(|e| panic!("GPU: {e}"));
    }
    gpu.sync_host();
    let t_gpu = t.elapsed().as_secs_f64();
    println!(
        "{} particles, {steps} steps: CPU {t_cpu:.2} s, GPU {t_gpu:.2} s",
        cpu.particle_count()
    );
    Some(Runs {
        cpu,
        gpu,
        device,
        run_time_s: t_cpu + t_gpu,
    })
}

/// `cfg` run for `steps` steps on the CPU.
pub fn run_cpu(cfg: &FluidConfig, steps: usize) -> FluidSolver {
    let mut cpu = FluidSolver::new(cfg);
    for _ in 0..steps {
        cpu.step(cfg.time_step).unwrap_or_else(|e| panic!("CPU: {e}"));
    }
    cpu
}

/// The largest |r_a − r_b| over the fluid particles of `a`, each matched by id in `b` [m].
pub fn largest_fluid_distance(a: &Particles, b: &Particles) -> f64 {
    let at: HashMap<u32, usize> = (0..b.len()).map(|j| (b.id[j], j)).collect();
    (0..a.len())
        .filter(|&i| a.kind[i] == Kind::Fluid.code())
        .map(|i| {
            let j = *at
                .get(&a.id[i])
                .unwrap_or_else(|| panic!("fluid particle {} is missing", a.id[i]));
            let (p, q) = (a.position(i), b.position(j));
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
        })
        .fold(0.0, schemas::validation::max_or_nan)
}

/// The largest component of |impulse_gpu − impulse_cpu| of the walls on the fluid, relative to
/// the largest component of the CPU's.
pub fn wall_impulse_difference(runs: &Runs) -> f64 {
    let (c, g) = (runs.cpu.totals().wall_impulse, runs.gpu.totals().wall_impulse);
    let scale = schemas::validation::largest_abs(c);
    (0..3)
        .map(|a| (g[a] - c[a]).abs())
        .fold(0.0, schemas::validation::max_or_nan)
        / scale
}

/// The walls' impulse on the fluid is a sum of f32 pair terms: relative rounding u √(terms) ≈
/// 6e-8 · √(10⁶) = 6e-5 per step, and the positions' differences shift the pressure pairs by
/// δP/P ≈ 5e-5 (`gpu_dam_break.rs`'s IMPULSE_BOUND): 1e-3 of the largest component leaves a
/// margin of about 10.
pub const IMPULSE_BOUND: f64 = 1.0e-3;

/// Checks the slab's runs against [`POSITION_BOUND`] and [`IMPULSE_BOUND`] and records both as
/// `gpu-<tag>-vs-cpu-…` rows of the test `source` (`file.rs::test`) on `scene`, for the GPU
/// path's `capability`; returns the positions' difference.
pub fn check_and_record(runs: &Runs, (tag, capability, scene, source): (&str, &str, &str, &str)) -> f64 {
    let worst = largest_fluid_distance(runs.cpu.particles(), runs.gpu.particles());
    let impulse = wall_impulse_difference(runs);
    println!(
        "largest position difference {worst:.3e} m (bound {POSITION_BOUND:e}); wall impulse CPU {:?}, GPU {:?} N s: {impulse:.3e} of the largest (bound {IMPULSE_BOUND:e})",
        runs.cpu.totals().wall_impulse,
        runs.gpu.totals().wall_impulse
    );
    let row = Record {
        capability: format!("{capability} on the GPU (f32)"),
        reference: "the CPU's f64 step from the same start".into(),
        case: scene.into(),
        resolution: "E-MPS, Δs = 0.02 m".into(),
        source: format!("fluid-solver/tests/{source}"),
        run_time_s: runs.run_time_s,
        machine: format!("{}; {}", runs.device, schemas::validation::machine()),
        ..Default::default()
    };
    record_measures(
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
                "wall-impulse",
                "largest |impulse_gpu − impulse_cpu| of the walls / the largest component",
                impulse,
                IMPULSE_BOUND,
                "f32 rounding of the pair sums, with a margin of about 10 (gpu_common/compare.rs)",
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
    worst
}

/// Asserts that `feature` moved the fluid: the CPU run `with` it ends more than [`VISIBLE`]
/// position bounds from the CPU run `without` it, so that the comparison with the GPU sees it.
pub fn assert_visible(feature: &str, with: &FluidSolver, without: &FluidSolver) {
    let moved = largest_fluid_distance(with.particles(), without.particles());
    println!("{feature} moves the fluid by up to {moved:.3e} m on the CPU");
    assert!(
        moved > VISIBLE * POSITION_BOUND,
        "{feature} moved the fluid by only {moved:.3e} m: the comparison could not see it"
    );
}

/// One measure of a GPU run against the CPU's: what (the id's part), measure, value, bound, the
/// bound's source, unit.
pub type Measure<'a> = (&'a str, &'a str, f64, f64, &'a str, &'a str);

/// Records each of `measures` as a row like `row`, with the id `id` makes of its `what`.
pub fn record_measures(row: &Record, id: impl Fn(&str) -> String, measures: &[Measure]) {
    for &(what, measure, value, bound, bound_source, unit) in measures {
        record(Record {
            id: id(what),
            measure: measure.into(),
            value,
            bound: Some(bound),
            bound_source: bound_source.into(),
            unit: unit.into(),
            ..row.clone()
        });
    }
}

/// Where a GPU run's device measures positions from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DeviceFrame {
    /// The tank's lower corner, as a case gets it.
    Corner,
    /// [`FAR`] m before the tank's lower corner along x: the device keeps wide positions and
    /// holds the numbers a tank of 10⁵ spacings holds at its far end (`gpu_wide_positions.rs`).
    Far,
}

/// How far [`DeviceFrame::Far`] lies from the tank [m]: 10⁵ spacings at Δs = 0.02 m, where
/// plain f32 positions would round by 1.2e-4 m, six times [`POSITION_BOUND`].
pub const FAR: f64 = 2000.0;

/// Moves `s` (of `cfg`) to `dev`, measuring positions from `frame`.
pub fn to_device(
    s: &mut FluidSolver,
    cfg: &FluidConfig,
    dev: fluid_solver::gpu::GpuDevice,
    frame: DeviceFrame,
) {
    let started = match frame {
        DeviceFrame::Corner => s.to_device(cfg, dev),
        DeviceFrame::Far => {
            let origin = [cfg.tank.min[0] - FAR, cfg.tank.min[1], cfg.tank.min[2]];
            s.to_device_from(cfg, dev, origin)
        }
    };
    started.unwrap_or_else(|e| panic!("{e}"));
    let wide = s.device().is_some_and(|d| d.frame().wide());
    assert_eq!(
        wide,
        frame == DeviceFrame::Far,
        "the device's positions are wide only when measured from far away"
    );
}

/// A solver of `cfg` from the saved `state`, moved to `dev` in its frame when one is given
/// (then `on_device` sees it first), run for `steps` steps of the case's Δt, with its host copy
/// brought up to date; and its wall time [s]. For comparisons that start mid-run, where a scene
/// amplifies rounding.
pub fn run_from(
    cfg: &FluidConfig,
    state: &fluid_solver::FluidState,
    dev: Option<(fluid_solver::gpu::GpuDevice, DeviceFrame)>,
    steps: usize,
    on_device: impl FnOnce(&mut FluidSolver),
) -> (FluidSolver, f64) {
    let t = Instant::now();
    let mut s = FluidSolver::new(cfg);
    s.restore_state(state);
    if let Some((dev, frame)) = dev {
        to_device(&mut s, cfg, dev, frame);
        on_device(&mut s);
    }
    for _ in 0..steps {
        s.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
    }
    s.sync_host();
    (s, t.elapsed().as_secs_f64())
}
