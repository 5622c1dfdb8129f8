//! ISPH against E-MPS on the same dam break (the Koshizuka & Oka column, L = 0.146 m, a slab
//! `--depth` deep) at the same particle size and threads: fluid-particle-steps per second, PPE
//! iterations per step and the PPE's share of the step, wall time to the same physical end time
//! (each method at its own largest stable Δt: E-MPS acoustic, ISPH advective), and the roughness
//! of a pressure probe on the far wall: the RMS of its step-to-step change (the measure),
//! and, since E-MPS takes more, smaller steps (2.4× at Δs = L/20), three measures that do not favour the
//! smaller step ([`probe_signal`]): per unit time RMS(Δp/Δt), the RMS change with both series
//! resampled at ISPH's Δt, and the RMS of the high-passed signal (minus its moving average over
//! 11 ISPH steps). The same measures for a wall-pressure sensor at the same height
//! ([`fluid_solver::wall_sensor`]: the force on a 20 mm disc of the wall's face, per step), which
//! reads the wall's load rather than the particles' pressure field. Then the probe's RMS per step
//! and high-passed by 0.05 s windows from its first wet reading: the front's arrival apart from
//! the wall under water.
//!
//! "kicked/step" counts the fluid particles whose velocity the collision stage changed
//! ([`fluid_solver::collision::kicked`]), per step: a kick is a velocity change whatever the
//! step's length, which ISPH's next projection answers with a pressure ∝ 1/Δt.
//!
//! Then ISPH's PPE iterations per step in windows of 0.05 s of simulated time (before and after
//! the impact), each method's stages (the step's stage timers) with their share, and the load average
//! before and after and the process's CPU time (wall times on a shared machine mean little
//! without them; "per CPU-s × threads" is the rate the threads would give with the cores to
//! themselves).
//!
//! `cargo bench -p fluid-solver --bench isph_vs_emps -- [spacing] [end time] [ppe solver]
//! [--s2] [--only=isph|emps] [--probe-log=PREFIX] [--alpha-d=α] [--gradient=corrected-difference|symmetric]
//! [--radius=r_e/Δs] [--shifting=lind] [--shifting-coefficient=A] [--isph-courant=C]
//! [--kernel-correction=none|moment]`; defaults Δs = L/20 = 0.0073 m (8 000 fluid particles), 0.5 s (past
//! the impact on the far wall at about 0.3 s), "additive-two-level-pcg" (or "two-level-pcg", "jacobi-pcg", "sgs-pcg", "faer-cholesky"), S2's α_d = 5e-3, ISPH's
//! default pressure gradient "conservative" (`--gradient=corrected-difference`, S2-8, or `symmetric`: the case key
//! `isph.pressure_gradient`) at its default support (2.0 Δs, 2.4 with S2-8's gradient; `--radius`: `isph.influence_radius`), no shifting (`--shifting=lind`: `isph.shifting`, with
//! `--shifting-coefficient`: `isph.shifting_coefficient`, default 0.5), ISPH's Δt at advective
//! Courant 0.3 (`--isph-courant`; 0.1275 gives E-MPS's Δt at L/20, for the probe at equal
//! steps), the gradient's default kernel correction (`--kernel-correction`:
//! `isph.kernel_correction`). `--s2` is S2's
//! scale (Table 1): Δs = 5 mm and a slab 76 Δs deep, 127 832 fluid particles (S2: 128 000).
//! `--probe-log=PREFIX` writes `PREFIX-emps.csv` and `PREFIX-isph.csv`, one row per step: what the
//! probe reads and where it comes from ([`probe_log`]).

use fluid_solver::probe_signal::{self, Series};
use fluid_solver::probes::{self, ProbeSet};
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{
    FluidConfig, FluidMethodName, IsphConfig, KernelCorrection, PpeSolver, PressureGradient, ProbeConfig,
    ProbeKind, Shifting,
};
use schemas::case::Case;
use std::path::PathBuf;
use std::time::Instant;

mod bench_process;
mod probe_log;
use bench_process::{cpu_seconds, load_average};

fn case(ds: f64, layers: f64) -> FluidConfig {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../cases/dam-break-koshizuka/case.toml");
    let case = Case::load(&path).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1)
    });
    let mut cfg = case
        .fluid
        .values()
        .next()
        .cloned()
        .unwrap_or_else(|| std::process::exit(1));
    let depth = layers * ds;
    cfg.spacing = ds;
    cfg.tank.max = [0.584, depth, 0.438];
    cfg.block[0].max = [0.146, depth, 0.292];
    cfg.probe.clear();
    cfg
}

/// Diameter of the far-wall pressure sensor [m]: a transducer's face (5–20 mm is usual; the
/// SPHERIC test 2 sensors are about 9 mm wide).
const SENSOR_DIAMETER: f64 = 0.02;

/// Window of simulated time over which the PPE iterations per step are averaged [s].
const WINDOW: f64 = 0.05;

struct Row {
    name: String,
    stages: Vec<(&'static str, f64)>,
    dt: f64,
    steps: u64,
    /// Time reached (short of the end time when the run stopped).
    reached: f64,
    fluid: usize,
    wall: f64,
    cpu: f64,
    ppe_iterations: u64,
    ppe_share: f64,
    /// Fluid particles kicked by the collision stage, over all steps.
    collisions: u64,
    /// The far-wall probe after each step.
    probe: Series,
    /// The far-wall pressure sensor (a disc of [`SENSOR_DIAMETER`]) after each step.
    sensor: Series,
    /// (time, PPE iterations) of each step.
    ppe_per_step: Vec<(f64, u64)>,
}

fn run(name: &str, cfg: &FluidConfig, end: f64, log: Option<&str>) -> Row {
    let mut solver = FluidSolver::new(cfg);
    let fluid = solver.particles().count(Kind::Fluid);
    let probe = ProbeConfig {
        name: "wall".into(),
        kind: ProbeKind::Pressure,
        position: vec![0.584 - 0.5 * cfg.spacing, 5.0 * cfg.spacing, 0.02],
        ..Default::default()
    };
    let tank = solver.tank();
    // The same height on the wall's face, read as the force on a disc (crate::wall_sensor).
    let disc = ProbeConfig {
        name: "sensor".into(),
        kind: ProbeKind::WallPressure,
        position: vec![0.584, 5.0 * cfg.spacing, 0.02],
        normal: Some("-x".into()),
        diameter: Some(SENSOR_DIAMETER),
        ..Default::default()
    };
    let mut sensor_set = ProbeSet::new(&[disc], &solver).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1)
    });
    let mut sensor = Series::default();
    sensor.0.push((solver.time(), sensor_set.row(&solver)[0]));
    let mut series = Series::default();
    let mut log = log.map(|prefix| {
        let path = format!("{prefix}-{}.csv", name.replace('-', "").to_lowercase());
        probe_log::ProbeLog::create(&path, &probe).unwrap_or_else(|e| {
            eprintln!("error: {path}: {e}");
            std::process::exit(1)
        })
    });
    series.0.push((
        solver.time(),
        probes::sample(&probe, solver.particles(), solver.kernel(), &tank),
    ));
    let start = Instant::now();
    let cpu0 = cpu_seconds();
    let mut ppe_per_step = Vec::new();
    while let Some(dt) = solver.next_step_towards(end) {
        let before = solver.totals().ppe_iterations;
        if let Err(e) = solver.step(dt) {
            eprintln!("{name}: {e}");
            break;
        }
        ppe_per_step.push((solver.time(), solver.totals().ppe_iterations - before));
        let p = probes::sample(&probe, solver.particles(), solver.kernel(), &tank);
        series.0.push((solver.time(), p));
        sensor.0.push((solver.time(), sensor_set.row(&solver)[0]));
        if let Some(log) = &mut log {
            log.row(&solver, dt, p);
        }
    }
    let wall = start.elapsed().as_secs_f64();
    let cpu = cpu_seconds() - cpu0;
    let times = solver.stage_times();
    let ppe = times.seconds("PPE assembly") + times.seconds("PPE solve");
    Row {
        name: name.into(),
        stages: times.stages().to_vec(),
        dt: cfg.time_step,
        steps: solver.steps(),
        reached: solver.time(),
        fluid,
        wall,
        cpu,
        ppe_iterations: solver.totals().ppe_iterations,
        collisions: solver.totals().collisions,
        ppe_share: if times.total() > 0.0 {
            ppe / times.total()
        } else {
            0.0
        },
        probe: series,
        sensor,
        ppe_per_step,
    }
}

/// The value of the argument `NAME=VALUE`.
fn flag<'a>(all: &'a [String], name: &str) -> Option<&'a str> {
    all.iter().find_map(|a| a.strip_prefix(name)?.strip_prefix('='))
}

/// The number of the argument `NAME=VALUE`, or `default` when it is absent or not a number.
fn number(all: &[String], name: &str, default: f64) -> f64 {
    flag(all, name).and_then(|v| v.parse().ok()).unwrap_or(default)
}

fn main() {
    let all: Vec<String> = std::env::args().skip(1).collect();
    let s2 = all.iter().any(|a| a == "--s2");
    let only = flag(&all, "--only").map(str::to_owned);
    let args: Vec<&String> = all.iter().filter(|a| !a.starts_with("--")).collect();
    let ds: f64 = args
        .first()
        .and_then(|s| s.parse().ok())
        .unwrap_or(if s2 { 0.005 } else { 0.0073 });
    let end: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(0.5);
    let solver = match args.get(2).map(|s| s.as_str()) {
        Some("faer-cholesky") => PpeSolver::FaerCholesky,
        Some("sgs-pcg") => PpeSolver::SgsPcg,
        Some("jacobi-pcg") => PpeSolver::JacobiPcg,
        Some("two-level-pcg") => PpeSolver::TwoLevelPcg,
        _ => PpeSolver::AdditiveTwoLevelPcg,
    };
    let log = flag(&all, "--probe-log").map(str::to_owned);
    let layers = if s2 { 76.0 } else { 10.0 };
    let mut emps = case(ds, layers);
    emps.time_step = 0.45 * ds / emps.sound_speed(); // acoustic Courant 0.45, as the case file
    let mut isph = case(ds, layers);
    isph.method = FluidMethodName::Isph;
    isph.sound_speed = None;
    let alpha_d = number(&all, "--alpha-d", IsphConfig::default().alpha_d);
    let pressure_gradient = match flag(&all, "--gradient") {
        Some("symmetric") => PressureGradient::Symmetric,
        Some("corrected-difference") => PressureGradient::CorrectedDifference,
        _ => IsphConfig::default().pressure_gradient,
    };
    let support = IsphConfig {
        pressure_gradient,
        ..IsphConfig::default()
    }
    .support();
    let support = number(&all, "--radius", support);
    let influence_radius = Some(support);
    let shifting = match flag(&all, "--shifting") {
        Some("lind") => Shifting::Lind,
        _ => Shifting::Off,
    };
    let shifting_coefficient = number(
        &all,
        "--shifting-coefficient",
        IsphConfig::default().shifting_coefficient,
    );
    let kernel_correction = match flag(&all, "--kernel-correction") {
        Some("none") => Some(KernelCorrection::None),
        Some("moment") => Some(KernelCorrection::Moment),
        _ => None,
    };
    isph.isph = Some(IsphConfig {
        kernel_correction,
        ppe_solver: solver,
        alpha_d,
        pressure_gradient,
        influence_radius,
        shifting,
        shifting_coefficient,
        ..IsphConfig::default()
    });
    // Advective Courant 0.3 (limit 0.4), or `--isph-courant=C`.
    let courant = number(&all, "--isph-courant", 0.3);
    isph.time_step = courant * ds / isph.advective_velocity();
    for c in [&emps, &isph] {
        if let Err(e) = c.validate("fluid.water") {
            eprintln!("error: {e:?}");
            std::process::exit(1);
        }
    }
    println!(
        "dam break, Δs = {ds} m, slab {layers} Δs deep, end {end} s, ISPH gradient {pressure_gradient:?} (kernel correction {:?}) at a support of {support} Δs, shifting {shifting:?} (A = {shifting_coefficient}), {} threads, load average {}",
        isph.isph.map(|i| i.kernel_correction()),
        rayon::current_num_threads(),
        load_average()
    );
    let mut rows = Vec::new();
    for (name, cfg) in [("E-MPS", &emps), ("ISPH", &isph)] {
        if only
            .as_deref()
            .is_none_or(|o| o.eq_ignore_ascii_case(&name.replace('-', "")))
        {
            rows.push(run(name, cfg, end, log.as_deref()));
        }
    }
    println!("load average after: {}", load_average());
    let threads = rayon::current_num_threads() as f64;
    println!("method  Δt [s]    t [s]   steps  fluid    wall [s]  CPU [s]  fluid-steps/s  per CPU-s × threads  PPE it/step  PPE share  kicked/step");
    for row in &rows {
        println!(
            "{:6}  {:.2e}  {:6.4}  {:5}  {:6}  {:9.2}  {:7.2}  {:13.3e}  {:19.3e}  {:11.1}  {:8.1} %  {:11.1}",
            row.name,
            row.dt,
            row.reached,
            row.steps,
            row.fluid,
            row.wall,
            row.cpu,
            row.fluid as f64 * row.steps as f64 / row.wall,
            row.fluid as f64 * row.steps as f64 * threads / row.cpu.max(1e-9),
            row.ppe_iterations as f64 / row.steps.max(1) as f64,
            100.0 * row.ppe_share,
            row.collisions as f64 / row.steps.max(1) as f64,
        );
    }
    // The common grid: ISPH's Δt.
    let h = isph.time_step;
    println!(
        "far-wall probe (point probe Δs/2 from the wall, 0.02 m up), common grid h = ISPH's Δt = {h:.2e} s, high-pass = minus the moving average over {} points:",
        2 * probe_signal::HALF_WINDOW + 1
    );
    print_roughness(&rows, h, |r| &r.probe);
    println!(
        "far-wall pressure sensor (the force on a disc of {SENSOR_DIAMETER} m on the wall's face, 0.02 m up, per step), same measures:"
    );
    print_roughness(&rows, h, |r| &r.sensor);
    print_roughness_by_window(&rows, h);
    println!("PPE iterations per step by {WINDOW} s of simulated time (the front meets the far wall at about 0.3 s):");
    for row in rows
        .iter()
        .filter(|r| !r.ppe_per_step.is_empty() && r.ppe_iterations > 0)
    {
        let windows = (row.reached / WINDOW).ceil() as usize;
        let line: Vec<String> = (0..windows)
            .map(|w| {
                let (lo, hi) = (w as f64 * WINDOW, (w + 1) as f64 * WINDOW);
                let its: Vec<u64> = row
                    .ppe_per_step
                    .iter()
                    .filter(|(t, _)| *t > lo && *t <= hi)
                    .map(|p| p.1)
                    .collect();
                let mean = its.iter().sum::<u64>() as f64 / its.len().max(1) as f64;
                format!("{lo:.2}–{hi:.2}: {mean:.1}")
            })
            .collect();
        println!("  {}  {}", row.name, line.join("  "));
    }
    for row in &rows {
        let total: f64 = row.stages.iter().map(|s| s.1).sum();
        println!("{} stages (wall time per step, share of the step):", row.name);
        for (stage, secs) in &row.stages {
            println!(
                "  {stage:34} {:9.2} ms  {:5.1} %",
                1e3 * secs / row.steps.max(1) as f64,
                100.0 * secs / total.max(f64::MIN_POSITIVE)
            );
        }
    }
}

/// The far-wall probe's RMS step-to-step change and high-passed RMS by [`WINDOW`] of simulated
/// time, from the window in which it first reads water: the front's arrival (an impact, whose
/// own rise a longer step sees as a larger change per step) apart from the wall under water.
fn print_roughness_by_window(rows: &[Row], h: f64) {
    let Some(wet) = rows.iter().filter_map(|r| r.probe.first_wet()).reduce(f64::min) else {
        return;
    };
    println!("far-wall probe by {WINDOW} s of simulated time from its first wet reading, RMS Δp per step / RMS high-pass [Pa]:");
    for row in rows {
        let first = (wet / WINDOW).floor() as usize;
        let last = (row.reached / WINDOW).ceil() as usize;
        let line: Vec<String> = (first..last)
            .map(|w| {
                let (lo, hi) = (w as f64 * WINDOW, (w + 1) as f64 * WINDOW);
                let s = row.probe.between(lo, hi);
                format!("{lo:.2}–{hi:.2}: {:.1} / {:.1}", s.step_rms(), s.high_pass_rms(h))
            })
            .collect();
        println!("  {:6} {}", row.name, line.join("  "));
    }
}

/// The roughness measures of one series of each row ([`probe_signal`]), on the common grid `h`.
fn print_roughness(rows: &[Row], h: f64, series: impl Fn(&Row) -> &Series) {
    println!("method  RMS Δp per step [Pa]  max |Δp| [Pa]  RMS Δp/Δt [Pa/s]  RMS Δp at h [Pa]  RMS high-pass [Pa]  max p [Pa]");
    for row in rows {
        let s = series(row);
        println!(
            "{:6}  {:20.1}  {:13.1}  {:16.4e}  {:16.1}  {:18.1}  {:10.1}",
            row.name,
            s.step_rms(),
            s.step_max(),
            s.rate_rms(),
            s.resampled_step_rms(h),
            s.high_pass_rms(h),
            s.max()
        );
    }
}
