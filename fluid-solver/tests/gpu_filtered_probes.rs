//! Filtered wall-pressure sensors (`window`) on the GPU path: between probe rows the device's
//! particles stay there, and each step in a sensor's window reads the particles around its disc,
//! gathered without the rest (`fluid-solver/src/gpu/gather.rs`). The slab of
//! `gpu_common/compare.rs` with two filtered discs (floor under the column, left wall) and their
//! unfiltered twins, 40 steps on the CPU and on the GPU: the filtered columns agree within a bound
//! derived from f32 rounding, the filter moves the reading by far more than that bound (a GPU that
//! ignored the window could not pass), and a reading from the gathered particles equals the one
//! from the whole copy.

use crate::gpu_common;
use crate::gpu_common::compare;

use fluid_solver::probes::ProbeSet;
use fluid_solver::FluidSolver;
use schemas::validation::Record;
use std::time::Instant;

/// Two discs with a 8 ms box filter and their unfiltered twins (the point-pressure probe takes
/// no `window`: only a wall-pressure sensor has one).
const PROBES: &str = r#"
[[fluid.water.probe]]
name = "floor"
kind = "wall-pressure"
position = [0.08, 0.03, 0.0]
normal = "+z"
diameter = 0.06
window = 0.008

[[fluid.water.probe]]
name = "left"
kind = "wall-pressure"
position = [0.0, 0.03, 0.08]
normal = "+x"
diameter = 0.06
window = 0.008

[[fluid.water.probe]]
name = "floor_raw"
kind = "wall-pressure"
position = [0.08, 0.03, 0.0]
normal = "+z"
diameter = 0.06

[[fluid.water.probe]]
name = "left_raw"
kind = "wall-pressure"
position = [0.0, 0.03, 0.08]
normal = "+x"
diameter = 0.06
"#;

/// Steps of the runs (0.02 s at Δt = 5e-4 s) and steps between probe rows (0.01 s).
const STEPS: usize = 40;
const ROW_STEPS: usize = 20;

/// The bound on |P_gpu − P_cpu| of a filtered sensor over the 40 steps, from f32 rounding as
/// `gpu_common/compare.rs` carries it: the positions walk apart by δr = δa Δt √N t/√3 with
/// δa = 0.044 m/s², N = 40, t = 0.02 s: 1.6e-6 m = 8e-5 Δs. A neighbour moved by δr changes a
/// particle's number density by at most (r_e/r²) δr = 2.1 · 8e-5 = 1.7e-4 (at r = Δs); over about
/// 32 neighbours of random sign √32 · 1.7e-4 = 9.6e-4, of n0 = 14.4: 6.7e-5, so S1-14 moves a
/// pressure by c² ρ0 · 6.7e-5 = 9.8 Pa (c = 12.1 m/s), plus the step's own rounding of 0.11 Pa
/// (`gpu_pressure_stages.rs`). A sensor reads a weighted mean of pair pressures (P_i + P_j)/2, so
/// it moves by no more than a particle's pressure, plus its pair weights' relative change
/// 3 δr/Δs = 2.4e-4 of at most 3 kPa (0.7 Pa); the filter's mean over steps only lowers it.
/// 11 Pa (ρ g Δs = 196 Pa).
const BOUND: f64 = 11.0;

/// The filter must move each sensor's CPU reading by more than this many bounds at a row.
const FILTER_VISIBLE: f64 = 10.0;

/// The columns of one run's rows, by name.
struct Rows {
    names: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Rows {
    fn at(&self, row: usize, name: &str) -> f64 {
        let c = self.names.iter().position(|n| n == name).unwrap();
        self.rows[row][c]
    }
}

/// The unfiltered twins read from the gathered particles and from the whole copy [Pa].
type Twin = (Vec<f64>, Vec<f64>);

/// Steps `solver`, observing `probes` after every step as `run.rs` does, with a row every
/// [`ROW_STEPS`] steps (the GPU: after its copy). At step `check` (GPU only) the unfiltered
/// twins are read once from the gathered particles and once from the whole copy: returned.
fn run(
    solver: &mut FluidSolver,
    probes: &mut ProbeSet,
    check: Option<(usize, &mut ProbeSet)>,
) -> (Rows, Option<Twin>) {
    let dt = solver.time_step();
    let mut rows = Vec::new();
    let mut twin = None;
    let (check_at, mut raw) = match check {
        Some((k, raw)) => (k, Some(raw)),
        None => (usize::MAX, None),
    };
    for k in 1..=STEPS {
        solver.step(dt).unwrap_or_else(|e| panic!("{e}"));
        let next_row = (k.div_ceil(ROW_STEPS) * ROW_STEPS) as f64 * dt;
        probes.observe(solver, next_row);
        if k == check_at {
            if let Some(raw) = raw.as_deref_mut() {
                let gathered = raw.row(solver);
                solver.sync_host();
                twin = Some((gathered, raw.row(solver)));
            }
        }
        if k % ROW_STEPS == 0 {
            solver.sync_host();
            rows.push(probes.row(solver));
        }
    }
    let names = probes.names().iter().map(|s| s.to_string()).collect();
    (Rows { names, rows }, twin)
}

#[test]
fn gpu_filtered_wall_pressure_sensors_match_the_cpu() {
    let dir = compare::folder("filtered-probes");
    let cfg = compare::slab(&dir, PROBES);
    let Some(dev) = gpu_common::device() else { return };
    let device = dev.description();
    let t = Instant::now();
    let mut cpu = FluidSolver::new(&cfg);
    let mut cpu_probes = ProbeSet::new(&cfg.probe, &cpu).unwrap_or_else(|e| panic!("{e}"));
    let (cpu_rows, _) = run(&mut cpu, &mut cpu_probes, None);
    let mut gpu = FluidSolver::new(&cfg);
    gpu.to_device(&cfg, dev).unwrap_or_else(|e| panic!("{e}"));
    let mut gpu_probes = ProbeSet::new(&cfg.probe, &gpu).unwrap_or_else(|e| panic!("{e}"));
    let raw: Vec<_> = cfg.probe.iter().filter(|p| p.window.is_none()).cloned().collect();
    let mut raw_probes = ProbeSet::new(&raw, &gpu).unwrap_or_else(|e| panic!("{e}"));
    let (gpu_rows, twin) = run(&mut gpu, &mut gpu_probes, Some((STEPS / 2 + 3, &mut raw_probes)));
    let run_time_s = t.elapsed().as_secs_f64();

    let mut worst: f64 = 0.0;
    let mut least_filter = f64::INFINITY;
    for name in ["floor", "left"] {
        let mut moved: f64 = 0.0;
        for r in 0..cpu_rows.rows.len() {
            let (c, g) = (cpu_rows.at(r, name), gpu_rows.at(r, name));
            let raw = cpu_rows.at(r, &format!("{name}_raw"));
            println!("row {r} {name}: CPU {c:.3} Pa, GPU {g:.3} Pa, CPU unfiltered {raw:.3} Pa");
            worst = schemas::validation::max_or_nan(worst, (g - c).abs());
            moved = schemas::validation::max_or_nan(moved, (c - raw).abs());
        }
        least_filter = least_filter.min(moved);
    }
    let (gathered, whole) = twin.expect("the GPU run read the twins");
    let gather_diff = gathered
        .iter()
        .zip(&whole)
        .map(|(a, b)| (a - b).abs() / b.abs().max(1.0))
        .fold(0.0, schemas::validation::max_or_nan);
    println!(
        "filtered sensors: largest |GPU − CPU| {worst:.3e} Pa (bound {BOUND} Pa); the filter moves each sensor's CPU reading by up to {least_filter:.1} Pa or more; gathered {gathered:?} against the whole copy {whole:?} Pa ({gather_diff:.1e}); {run_time_s:.2} s"
    );
    let row = Record {
        capability: "filtered wall-pressure sensors on the GPU (f32)".into(),
        reference: "the CPU's f64 step and sensors from the same start".into(),
        case: "dam-break slab, two 6 cm discs with an 8 ms window, 40 steps".into(),
        resolution: "E-MPS, Δs = 0.02 m".into(),
        source: "fluid-solver/tests/gpu_filtered_probes.rs".into(),
        run_time_s,
        machine: format!("{device}; {}", schemas::validation::machine()),
        ..Default::default()
    };
    compare::record_measures(
        &row,
        |what| format!("gpu-filtered-sensor-vs-cpu-{what}"),
        &[(
            "pressure",
            "largest |P_gpu − P_cpu| of the filtered sensors' rows",
            worst,
            BOUND,
            "f32 rounding carried through the positions into S1-14 (gpu_filtered_probes.rs)",
            "Pa",
        )],
    );
    assert!(
        worst < BOUND,
        "a filtered sensor reads {worst:.3e} Pa from the CPU's (bound {BOUND} Pa)"
    );
    assert!(
        least_filter > FILTER_VISIBLE * BOUND,
        "the window moves a sensor's readings by only {least_filter:.1} Pa: a GPU ignoring it could pass"
    );
    // the same f32 particles, summed in another order (the host's copy is re-sorted)
    assert!(
        gather_diff < 1e-9,
        "the gathered particles read {gathered:?} Pa, the whole copy {whole:?} Pa"
    );
}
