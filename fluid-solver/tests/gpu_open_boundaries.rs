//! Inflow and outflow boundaries on the GPU path (issue 38): the host runs the CPU's rule on its
//! copy of the inflow strip and the device converts, moves, withdraws and removes particles by
//! it, compacting its arrays (`src/gpu/open_boundary.rs`, `shaders/open_boundary.wgsl`). A small
//! channel is fed by a strip whose level rises, then falls (a `series`), and drained behind an
//! outflow plane; from a common mid-run state the CPU and the GPU go on for [`STEPS`] steps and
//! must end with the same particle balance (inserted, entered, removed, withdrawn), the same
//! fluid count and particle ids, and the fluid within a bound derived from f32 rounding. The
//! balance moves in all four counts over the compared steps, so a GPU that ignored the
//! boundaries could not pass.

use crate::gpu_common;
use gpu_common::compare::{self, DeviceFrame};

use fluid_solver::open_boundary::ParticleBalance;
use fluid_solver::state::FluidState;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::{Case, FluidConfig};
use schemas::validation::{record, Record};
use std::collections::BTreeSet;
use std::path::Path;
use std::time::Instant;

/// Steps on the CPU from rest to the shared start t0 = 0.16 s, and steps compared from there.
const BEFORE: usize = 100;
const STEPS: usize = 80;

/// The bound on |r_gpu − r_cpu| of a fluid particle after [`STEPS`] steps from a common state:
/// the scene has the wave makers' flume's spacing, sound speed, step and steps
/// (`gpu_wave_maker.rs`, Δs = 0.02 m, c = 6 m/s, Δt = 1.6e-3 s, N = 80, t = 0.128 s), and the
/// derivation of `gpu_common/compare.rs` restated for it (unit roundoff u = 2⁻²⁴ ≈ 6.0e-8):
/// - a number density sums K ≈ 300 candidates: u √K = 1.0e-6 of n0; the strip's particles stand
///   at f32 positions moved by an f32 u Δt each step (x ≤ 0.1 m: each step rounds by up to
///   0.5 u · 0.1 m = 3e-9 m, a random walk of √(N_total) · 3e-9 ≤ 5e-8 m = 2.5e-6 Δs over the
///   180 steps of a run, which moves a neighbour's w(r) by about as much of n0): together at most
///   2.7e-6 of n0 at the strip, 1.0e-6 elsewhere;
/// - S1-14 makes that δP = c² ρ0 · 2.7e-6 = 36 · 1000 · 2.7e-6 = 0.097 Pa;
/// - S1-3 gives δa ≈ 2 d δP / (ρ0 Δs) = 6 · 0.097 / 20 = 0.029 m/s² per step, of random sign;
/// - over N = 80 steps the velocity walks to δu = δa Δt √N = 0.029 · 1.6e-3 · 8.9 = 4.1e-4 m/s
///   and the position to δu t/√3 = 4.1e-4 · 0.128 / 1.73 = 3.0e-5 m near the strip (1.4e-5 m
///   elsewhere, the flume's figure); a fluid particle that entered during the steps starts
///   from its strip position, within the strip's 5e-8 m.
///
/// So 3e-5 m = 1.5e-3 Δs. (A particle converted or removed one step late on one path would be a
/// missing id or a count off by one, not a small distance.)
const POSITION_BOUND: f64 = 3.0e-5;

/// A quasi-2-D channel 0.6 m long and two particles wide at Δs = 0.02 m, c = 6 m/s,
/// Δt = 1.6e-3 s (c Δt/Δs = 0.48): a strip 0.1 m (5 layers) upstream of the plane x = 0.1 m
/// moves at 0.3 m/s with the level of `inflow.csv` (0.06 m to t = 0.17 s, up to 0.10 m at
/// 0.21 s, down to 0.04 m at 0.28 s: two rows added, then three withdrawn, within the compared
/// steps 0.16 … 0.288 s); 0.06 m of still water from the plane to the end, drained behind
/// x = 0.56 m. About 5 000 particles, 150 of them fluid at the start. (With the outflow plane at
/// x = 0.5 m the water's face collapsing past it makes the flow there sensitive to rounding: the
/// GPU parts from the CPU by 2.5e-5 m over the same steps in jumps at steps where nothing is
/// removed, while at 0.56 m it stays within 7e-7 m.)
fn channel(dir: &Path) -> FluidConfig {
    std::fs::write(
        dir.join("inflow.csv"),
        "t, level, velocity\n0.0, 0.06, 0.3\n0.17, 0.06, 0.3\n0.21, 0.10, 0.3\n0.28, 0.04, 0.3\n",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let text = r#"[case]
name = "channel"
end_time = 0.288

[fluid.channel]
spacing = 0.02
time_step = 1.6e-3
sound_speed = 6.0
output_interval = 0.1
tank = { min = [0.0, 0.0, 0.0], max = [0.6, 0.04, 0.2] }

[fluid.channel.inflow]
plane = 0.1
strip_length = 0.1
series = "inflow.csv"

[fluid.channel.outflow]
plane = 0.56

[[fluid.channel.block]]
min = [0.1, 0.0, 0.0]
max = [0.6, 0.04, 0.06]
"#;
    let case = Case::parse(&dir.join("case.toml"), text.to_string()).unwrap_or_else(|e| panic!("{e}"));
    case.fluid["channel"].clone()
}

/// A solver of `cfg` from `state` (the GPU's when `dev` is given, its arrays made without
/// headroom so that the strip's new rows regrow them), run for [`STEPS`] steps; and its wall
/// time [s].
fn run_from(
    cfg: &FluidConfig,
    state: &FluidState,
    dev: Option<(fluid_solver::gpu::GpuDevice, DeviceFrame)>,
) -> (FluidSolver, f64) {
    let no_headroom = |s: &mut FluidSolver| {
        // the strip's first new rows regrow the device's arrays
        if let Some(d) = s.device_mut() {
            d.regrow(0).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(d.capacity(), d.len());
        }
    };
    let (s, t) = compare::run_from(cfg, state, dev, STEPS, no_headroom);
    if let Some(d) = s.device() {
        assert!(
            d.capacity() > state.particles.len(),
            "the arrays were not regrown"
        );
    }
    (s, t)
}

/// The ids of the particles of `kind` in `s`.
fn ids(s: &FluidSolver, kind: Kind) -> BTreeSet<u32> {
    let p = s.particles();
    (0..p.len())
        .filter(|&i| p.kind[i] == kind.code())
        .map(|i| p.id[i])
        .collect()
}

/// The counts of `b` less those of `a`.
fn since(a: ParticleBalance, b: ParticleBalance) -> [u64; 4] {
    [
        b.inserted - a.inserted,
        b.entered - a.entered,
        b.removed - a.removed,
        b.withdrawn - a.withdrawn,
    ]
}

#[test]
fn gpu_inflow_and_outflow_match_cpu() {
    inflow_and_outflow(DeviceFrame::Corner);
}

/// The channel of [`gpu_inflow_and_outflow_match_cpu`] with the device measuring positions from
/// 10⁵ spacings away (wide positions, `gpu_wide_positions.rs`): the strip travels by its low
/// parts, its new rows arrive split in two; the same counts and bounds.
#[test]
fn gpu_inflow_and_outflow_match_cpu_in_wide_positions() {
    inflow_and_outflow(DeviceFrame::Far);
}

fn inflow_and_outflow(frame: DeviceFrame) {
    let Some(dev) = gpu_common::device() else {
        return;
    };
    let device = dev.description();
    let dir = compare::folder(&format!("open-boundaries-{frame:?}"));
    let cfg = channel(&dir);
    let t = Instant::now();
    let mut before = FluidSolver::new(&cfg);
    for _ in 0..BEFORE {
        before.step(cfg.time_step).unwrap_or_else(|e| panic!("CPU: {e}"));
    }
    let state = before.save_state();
    let t_before = t.elapsed().as_secs_f64();
    let (cpu, t_cpu) = run_from(&cfg, &state, None);
    let (gpu, t_gpu) = run_from(&cfg, &state, Some((dev, frame)));
    let start = state.open_boundaries.balance();
    let (bc, bg) = (cpu.open_boundaries().balance(), gpu.open_boundaries().balance());
    println!(
        "{} particles at t0 = {:.3} s ({BEFORE} CPU steps in {t_before:.2} s), then {STEPS} steps: CPU {t_cpu:.2} s, GPU {t_gpu:.2} s; balance at t0 {start:?}, CPU {bc:?}, GPU {bg:?}; over the steps (inserted, entered, removed, withdrawn) CPU {:?}, GPU {:?}",
        state.particles.len(),
        state.time,
        since(start, bc),
        since(start, bg)
    );
    let (fluid_c, fluid_g) = (ids(&cpu, Kind::Fluid), ids(&gpu, Kind::Fluid));
    let (strip_c, strip_g) = (ids(&cpu, Kind::Inflow), ids(&gpu, Kind::Inflow));
    let worst = schemas::validation::max_or_nan(
        compare::largest_fluid_distance(cpu.particles(), gpu.particles()),
        compare::largest_fluid_distance(gpu.particles(), cpu.particles()),
    );
    println!(
        "fluid: CPU {}, GPU {}; strip: CPU {}, GPU {}; all: CPU {}, GPU {}; largest fluid position difference {worst:.3e} m (bound {POSITION_BOUND:e} m)",
        fluid_c.len(),
        fluid_g.len(),
        strip_c.len(),
        strip_g.len(),
        cpu.particle_count(),
        gpu.particle_count()
    );
    let (tag, capability, test) = match frame {
        DeviceFrame::Corner => (
            "open-boundaries",
            "E-MPS with an inflow (series) and an outflow on the GPU (f32)",
            "gpu_inflow_and_outflow_match_cpu",
        ),
        DeviceFrame::Far => (
            "open-boundaries-wide",
            "E-MPS with an inflow (series) and an outflow on the GPU (f32) in wide positions 10⁵ spacings from the frame's origin",
            "gpu_inflow_and_outflow_match_cpu_in_wide_positions",
        ),
    };
    let row = Record {
        capability: capability.into(),
        reference: "the CPU's f64 step from the same state".into(),
        case: "a 0.6 × 0.04 m channel, a strip at 0.3 m/s whose level rises 0.06 → 0.10 m then falls to 0.04 m, 0.06 m of water drained behind x = 0.56 m: 100 steps of 1.6e-3 s on the CPU, then 80 on both".into(),
        resolution: "E-MPS, Δs = 0.02 m".into(),
        source: format!("fluid-solver/tests/gpu_open_boundaries.rs::{test}"),
        run_time_s: t.elapsed().as_secs_f64(),
        machine: format!("{device}; {}", schemas::validation::machine()),
        ..Default::default()
    };
    record(Record {
        id: format!("gpu-{tag}-vs-cpu-positions"),
        measure: "largest |r_gpu − r_cpu| over the fluid particles, matched by id".into(),
        value: worst,
        bound: Some(POSITION_BOUND),
        bound_source: "f32 rounding carried through the equation of state over the steps, the strip's f32 travel included (gpu_open_boundaries.rs)".into(),
        unit: "m".into(),
        ..row.clone()
    });
    let off = since(start, bc)
        .iter()
        .zip(since(start, bg))
        .map(|(&c, g)| c.abs_diff(g))
        .sum::<u64>();
    record(Record {
        id: format!("gpu-{tag}-vs-cpu-balance"),
        measure: "Σ |count_gpu − count_cpu| of inserted, entered, removed and withdrawn over the steps"
            .into(),
        value: off as f64,
        bound: Some(0.0),
        bound_source: "exact: the balance is a count".into(),
        unit: "particles".into(),
        ..row
    });
    let moved = since(start, bc);
    assert!(
        moved.iter().all(|&c| c > 0),
        "the CPU's balance must move in every count over the compared steps (inserted, entered, removed, withdrawn): {moved:?}"
    );
    assert_eq!(bg, bc, "the GPU's particle balance differs from the CPU's");
    assert_eq!(
        fluid_g, fluid_c,
        "the GPU's fluid particles (by id) differ from the CPU's"
    );
    assert_eq!(
        strip_g, strip_c,
        "the GPU's strip particles (by id) differ from the CPU's"
    );
    assert_eq!(gpu.particle_count(), cpu.particle_count());
    assert!(
        worst < POSITION_BOUND,
        "a fluid particle is {worst:.3e} m from its CPU position (bound {POSITION_BOUND:e} m)"
    );
}

/// The small bridge's strip (`cases/bridge-washout-small`: u = 10 m/s, Δs = 4 m, Δt = 0.024 s)
/// brings a layer exactly onto the inflow plane at t = 3.0 s, the 125th step's end. Its 170
/// particles share the layer's x only up to f64 rounding (rows added when the level rose started
/// at the layer's x, the others travelled there), so the CPU once let 68 of them enter at the
/// next step and the rest one step later, while the device, whose f32 positions cannot tell them
/// apart, let all 170 enter and stopped ("the GPU's inflow strip parted from the host's"). A
/// particle within `PLANE_SLACK` spacings short of the plane now counts as across it on both
/// paths: the whole layer enters in one step, and the two runs stepped past t = 3.0 s keep the
/// same balance.
#[test]
fn a_layer_landing_on_the_inflow_plane_enters_whole_on_both_paths() {
    let (_, cfg) = crate::common::load_case("bridge-washout-small");
    let Some(dev) = gpu_common::device() else {
        return;
    };
    let mut cpu = FluidSolver::new(&cfg);
    let mut gpu = FluidSolver::new(&cfg);
    gpu.to_device(&cfg, dev).unwrap_or_else(|e| panic!("{e}"));
    let mut entered_at_126 = 0;
    for step in 1..=127 {
        let before = cpu.open_boundaries().balance().entered;
        cpu.step(cfg.time_step)
            .unwrap_or_else(|e| panic!("CPU, step {step}: {e}"));
        gpu.step(cfg.time_step)
            .unwrap_or_else(|e| panic!("GPU, step {step}: {e}"));
        if step == 126 {
            entered_at_126 = cpu.open_boundaries().balance().entered - before;
        }
    }
    let (c, g) = (cpu.open_boundaries().balance(), gpu.open_boundaries().balance());
    println!("step 126 entered {entered_at_126}; balance CPU {c:?}, GPU {g:?}");
    assert_eq!(
        entered_at_126 % 170,
        0,
        "a layer of 170 particles was split: {entered_at_126} entered"
    );
    assert!(
        entered_at_126 > 0,
        "no layer reached the plane at t = 3.0 s: the scene changed"
    );
    assert_eq!(
        [c.inserted, c.entered, c.withdrawn],
        [g.inserted, g.entered, g.withdrawn],
        "the strip's balance"
    );
}
