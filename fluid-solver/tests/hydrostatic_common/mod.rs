//! The hydrostatic tank's run and checks, shared by the CPU test (`hydrostatic.rs`) and the GPU
//! test (`gpu_hydrostatic.rs`): after settling, the pressure at depth h is ρ g h within 3 % in
//! the interior (issue 3's bound), the floor carries the water's weight, and no particle gets
//! through a wall. The same run carries the wall-pressure sensors `probes.rs` checks: on the CPU
//! it is run once for both tests ([`cpu_tank`]).

use super::common;
use fluid_solver::probes::{self, ProbeSet};
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{FluidBackend, ProbeConfig, ProbeKind};
use schemas::validation::{record, Record};
use std::sync::OnceLock;
use std::time::Instant;

fn pressure_probe(x: f64, y: f64, z: f64) -> ProbeConfig {
    ProbeConfig {
        name: "p".into(),
        kind: ProbeKind::Pressure,
        position: vec![x, y, z],
        ..Default::default()
    }
}

fn sensor(name: &str, position: [f64; 3], normal: &str) -> ProbeConfig {
    ProbeConfig {
        name: name.into(),
        kind: ProbeKind::WallPressure,
        position: position.to_vec(),
        normal: Some(normal.into()),
        diameter: Some(0.08),
        window: Some(0.5),
        ..Default::default()
    }
}

/// The wall-pressure sensors the tank carries (`probes.rs` says why these): discs of 0.08 m
/// (4 spacings) box-filtered over the last 0.5 s, one on the floor and pairs on opposite side
/// walls at z = 0.08 and 0.16 m.
pub fn wall_sensors() -> Vec<ProbeConfig> {
    vec![
        sensor("floor", [0.1, 0.1, 0.0], "+z"),
        sensor("x0-deep", [0.0, 0.1, 0.08], "+x"),
        sensor("x1-deep", [0.2, 0.1, 0.08], "-x"),
        sensor("y0-mid", [0.1, 0.0, 0.16], "+y"),
        sensor("y1-mid", [0.1, 0.2, 0.16], "-y"),
    ]
}

/// The heights of [`wall_sensors`].
pub const SENSOR_HEIGHTS: [f64; 3] = [0.0, 0.08, 0.16];

/// What one run of the tank leaves for the checks.
pub struct SettledTank {
    pub spacing: f64,
    pub rho_g: f64,
    /// Fluid particles at the start and at the end.
    pub fluid: (usize, usize),
    /// The walls' vertical force, time average over 1.5 … 2 s, and the water's weight [N].
    pub wall_force: f64,
    pub weight: f64,
    /// Heights of the point probes, their mean pressure over the interior grid and the samples,
    /// and the water's level (highest particle + Δs/2, time average).
    pub heights: Vec<f64>,
    pub mean_p: Vec<f64>,
    pub top: f64,
    /// The wall sensors' readings at 2 s, and the weight of the water above each of
    /// [`SENSOR_HEIGHTS`] per unit floor area over the same samples [Pa].
    pub sensors: Vec<f64>,
    pub weight_above: [f64; 3],
    pub run_time_s: f64,
}

/// The CPU run, made once for every test that reads it.
pub fn cpu_tank() -> &'static SettledTank {
    static RUN: OnceLock<SettledTank> = OnceLock::new();
    RUN.get_or_init(|| settle(FluidBackend::Cpu))
}

/// Runs the CI-sized hydrostatic tank on `backend`: Δs = 0.02 m, water 0.3 m deep in a 0.2 ×
/// 0.2 m tank: 10 × 10 × 15 = 1500 fluid particles; c = √(2 g 0.3)/0.2 = 12.1 m/s, Δt = 8e-4 s
/// (c Δt/Δs = 0.48). Settled for 1.5 s (≈ 15 periods of the column's first acoustic mode 4H/c ≈
/// 0.1 s), then sampled every 10 steps (8 ms) over 0.5 s, one period of the tank's first sloshing
/// mode (ω² = g k tanh(k h), k = π/0.2 m). Pressure at height z: the mean of the point probe over
/// a 5 × 5 grid of the tank's interior (≥ 3 Δs from the side walls). Panics if a particle gets
/// through a wall.
pub fn settle(backend: FluidBackend) -> SettledTank {
    let (_, mut cfg) = common::load_case("hydrostatic-tank");
    cfg.spacing = 0.02;
    cfg.tank.max = [0.2, 0.2, 0.4];
    cfg.block[0].max = [0.2, 0.2, 0.3];
    cfg.time_step = 8.0e-4;
    cfg.probe = wall_sensors();
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let ds = cfg.spacing;
    cfg.backend = backend;
    let started = Instant::now();
    let mut solver = FluidSolver::with_backend(&cfg).unwrap_or_else(|e| panic!("{e}"));
    let mut set = ProbeSet::new(&cfg.probe, &solver).unwrap_or_else(|e| panic!("{e}"));
    let fluid = solver.particles().count(Kind::Fluid);
    let tank = solver.tank();

    solver.advance_to(1.5).unwrap_or_else(|e| panic!("{e}"));
    let impulse_before = solver.totals().wall_impulse[2];
    let heights: Vec<f64> = (1..=14).map(|k| k as f64 * ds).collect();
    let plane = [0.06, 0.08, 0.1, 0.12, 0.14];
    let mut sum_p = vec![0.0; heights.len()];
    let mut above = [0.0; 3];
    let mut top = 0.0;
    let mut samples = 0usize;
    while let Some(dt) = solver.next_step_towards(2.0) {
        solver.step(dt).unwrap_or_else(|e| panic!("{e}"));
        set.observe(&solver, 2.0);
        if !solver.steps().is_multiple_of(10) {
            continue;
        }
        solver.sync_host(); // the GPU path's copy (nothing on the CPU)
        let p = solver.particles();
        for (k, &z) in heights.iter().enumerate() {
            for x in plane {
                for y in plane {
                    sum_p[k] += probes::sample(&pressure_probe(x, y, z), p, solver.kernel(), &tank) / 25.0;
                }
            }
        }
        let mut highest = f64::MIN;
        for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid.code()) {
            let r = p.position(i);
            let inside =
                r[0] > -0.5 * ds && r[0] < 0.2 + 0.5 * ds && r[1] > -0.5 * ds && r[1] < 0.2 + 0.5 * ds;
            assert!(
                inside && r[2] > -0.5 * ds,
                "particle {} went through a wall: {r:?}",
                p.id[i]
            );
            highest = highest.max(r[2]);
            for (n, z) in above.iter_mut().zip(SENSOR_HEIGHTS) {
                if r[2] > z {
                    *n += 1.0;
                }
            }
        }
        top += highest + 0.5 * ds;
        samples += 1;
    }
    solver.land_on(2.0);
    let sensors = set.row(&solver);
    let g = cfg.gravity_magnitude();
    let weight_per_area = solver.particle_mass() * g / (0.2 * 0.2);
    SettledTank {
        spacing: ds,
        rho_g: cfg.density * g,
        fluid: (fluid, solver.particles().count(Kind::Fluid)),
        wall_force: (solver.totals().wall_impulse[2] - impulse_before) / 0.5,
        weight: fluid as f64 * solver.particle_mass() * g,
        heights,
        mean_p: sum_p.iter().map(|s| s / samples as f64).collect(),
        top: top / samples as f64,
        sensors,
        weight_above: above.map(|n| n / samples as f64 * weight_per_area),
        run_time_s: started.elapsed().as_secs_f64(),
    }
}

/// Checks the point probes, the floor force and the walls of a run on `backend` (the CPU's
/// shared run, or a GPU run of its own).
pub fn settled_pressure_is_rho_g_h_and_walls_hold(backend: FluidBackend) {
    let gpu_run;
    let run = match backend {
        FluidBackend::Cpu => cpu_tank(),
        FluidBackend::Gpu => {
            gpu_run = settle(backend);
            &gpu_run
        }
    };
    let (ds, rho_g) = (run.spacing, run.rho_g);
    assert_eq!(run.fluid.1, run.fluid.0, "fluid particles were lost or created");

    // Static equilibrium: the walls carry the weight (time average of their vertical force).
    let (wall_force, weight) = (run.wall_force, run.weight);
    println!("floor force {wall_force:.3} N, weight {weight:.3} N");
    let row = Row::of(backend);
    record(Record {
        id: format!("{}-hydrostatic-floor-force", row.method),
        capability: format!("{} hydrostatic tank: floor force", row.capability),
        reference: "the water's weight (closed form)".into(),
        measure: "|wall force / weight − 1|, vertical, time average over 1.5 … 2 s".into(),
        value: 100.0 * (wall_force / weight - 1.0).abs(),
        bound: Some(1.0),
        bound_source: "the test's: static equilibrium to 1 %".into(),
        run_time_s: run.run_time_s,
        ..row.record()
    });
    assert!(
        (wall_force / weight - 1.0).abs() < 0.01,
        "walls carry {wall_force} N of a {weight} N weight (bound 1 %)"
    );

    // Depths are taken from the water's level, the highest particle + Δs/2 (time average), not
    // from the pressures. The pressure's own zero, S = mean(z + P/ρg) over the interior points
    // (deeper than r_e = 3.1 Δs below the highest particle, where the number density of S1-15
    // has its full support), must agree with that level within one spacing.
    let (heights, mean_p, top) = (&run.heights, &run.mean_p, run.top);
    let interior: Vec<(f64, f64)> = heights
        .iter()
        .zip(mean_p)
        .filter(|(z, _)| top - **z >= 3.1 * ds)
        .map(|(z, p)| (*z, *p))
        .collect();
    assert!(interior.len() >= 8, "too few interior points: {interior:?}");
    let surface = interior.iter().map(|(z, p)| z + p / rho_g).sum::<f64>() / interior.len() as f64;
    println!("free surface from P = 0: {surface:.4} m; highest particle + Δs/2: {top:.4} m (initial 0.3 m)");
    assert!(
        (surface - top).abs() < ds,
        "the pressure's free surface {surface} is more than Δs from the water top {top}"
    );
    println!("z [m]   depth [m]  P [Pa]     rho g h [Pa]  error");
    let mut worst: f64 = 0.0;
    for (&z, &p) in heights.iter().zip(mean_p) {
        let depth = top - z;
        let exact = rho_g * depth;
        let err = (p - exact) / exact;
        println!(
            "{z:.3}   {depth:.5}    {p:9.2}  {exact:9.2}     {:+.2} %",
            100.0 * err
        );
        if interior.iter().any(|(zi, _)| *zi == z) {
            worst = worst.max(err.abs());
        }
    }
    println!("worst interior error {:.2} %", 100.0 * worst);
    record(Record {
        id: format!("{}-hydrostatic-pressure", row.method),
        capability: format!("{} hydrostatic tank: pressure", row.capability),
        reference: "ρ g h (closed form), depth from the water's level (highest particle + Δs/2)".into(),
        measure: "worst |P / ρgh − 1| over interior heights (≥ r_e below the top), time average over \
                  1.5 … 2 s of a 5 × 5 grid of point probes"
            .into(),
        value: 100.0 * worst,
        bound: Some(3.0),
        bound_source: "issue 3's bound".into(),
        run_time_s: run.run_time_s,
        ..row.record()
    });
    assert!(
        worst < 0.03,
        "interior pressure differs from rho g h by {:.2} % (bound 3 %)",
        100.0 * worst
    );
}

/// What the CPU and the GPU test's records say alike, by backend.
struct Row {
    method: &'static str,
    capability: &'static str,
    resolution: &'static str,
    source: &'static str,
    machine: String,
}

impl Row {
    fn of(backend: FluidBackend) -> Row {
        match backend {
            FluidBackend::Cpu => Row {
                method: "emps",
                capability: "E-MPS",
                resolution: "E-MPS, Δs = 0.02 m (1 500 fluid), Δt = 8e-4 s",
                source: "fluid-solver/tests/hydrostatic.rs::settled_pressure_is_rho_g_h_and_walls_hold",
                machine: String::new(),
            },
            FluidBackend::Gpu => Row {
                method: "gpu",
                capability: "E-MPS on the GPU (f32)",
                resolution: "E-MPS on the GPU, Δs = 0.02 m (1 500 fluid), Δt = 8e-4 s",
                source: "fluid-solver/tests/gpu_hydrostatic.rs::settled_pressure_is_rho_g_h_and_walls_hold_on_the_gpu",
                machine: fluid_solver::gpu::GpuDevice::open()
                    .map(|d| format!("{}; {}", d.description(), schemas::validation::machine()))
                    .unwrap_or_default(),
            },
        }
    }

    /// The fields every row of this test shares.
    fn record(&self) -> Record {
        Record {
            case: "cases/hydrostatic-tank: water 0.3 m deep in a 0.2 × 0.2 m tank, settled 1.5 s".into(),
            resolution: self.resolution.into(),
            unit: "%".into(),
            source: self.source.into(),
            machine: self.machine.clone(),
            ..Default::default()
        }
    }
}
