//! The hydrostatic tank's run and checks, shared by the CPU test (`hydrostatic.rs`) and the GPU
//! test (`gpu_hydrostatic.rs`): after settling, the pressure at depth h is ρ g h within 3 % in
//! the interior (issue 3's bound), the floor carries the water's weight, and no particle gets
//! through a wall.

use super::common;
use fluid_solver::probes;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{FluidBackend, ProbeConfig, ProbeKind};
use schemas::validation::{record, Record};
use std::time::Instant;

fn pressure_probe(x: f64, y: f64, z: f64) -> ProbeConfig {
    ProbeConfig {
        name: "p".into(),
        kind: ProbeKind::Pressure,
        position: vec![x, y, z],
        ..Default::default()
    }
}

/// Runs the CI-sized hydrostatic tank on `backend` and checks it.
pub fn settled_pressure_is_rho_g_h_and_walls_hold(backend: FluidBackend) {
    let (_, mut cfg) = common::load_case("hydrostatic-tank");
    // CI size: Δs = 0.02 m, water 0.3 m deep in a 0.2 × 0.2 m tank: 10 × 10 × 15 = 1500 fluid
    // particles; c = √(2 g 0.3)/0.2 = 12.1 m/s, Δt = 8e-4 s (c Δt/Δs = 0.48).
    cfg.spacing = 0.02;
    cfg.tank.max = [0.2, 0.2, 0.4];
    cfg.block[0].max = [0.2, 0.2, 0.3];
    cfg.time_step = 8.0e-4;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let ds = cfg.spacing;
    let rho_g = cfg.density * cfg.gravity_magnitude();
    cfg.backend = backend;
    let started = Instant::now();
    let mut solver = FluidSolver::with_backend(&cfg).unwrap_or_else(|e| panic!("{e}"));
    let fluid = solver.particles().count(Kind::Fluid);
    let tank = solver.tank();

    // Settle for 1.5 s (≈ 15 periods of the column's first acoustic mode 4H/c ≈ 0.1 s), then
    // average over 0.5 s. Pressure at height z: the mean of the point probe over a 5 × 5 grid
    // of the tank's interior (≥ 3 Δs from the side walls).
    solver.advance_to(1.5).unwrap_or_else(|e| panic!("{e}"));
    let impulse_before = solver.totals().wall_impulse[2];
    let heights: Vec<f64> = (1..=14).map(|k| k as f64 * ds).collect();
    let plane = [0.06, 0.08, 0.1, 0.12, 0.14];
    let mut sum_p = vec![0.0; heights.len()];
    let mut top = 0.0;
    let mut samples = 0usize;
    while solver.time() < 2.0 - 1e-9 {
        solver
            .advance_to(solver.time() + 0.01)
            .unwrap_or_else(|e| panic!("{e}"));
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
        }
        top += highest + 0.5 * ds;
        samples += 1;
    }
    assert_eq!(
        solver.particles().count(Kind::Fluid),
        fluid,
        "fluid particles were lost or created"
    );

    // Static equilibrium: the walls carry the weight (time average of their vertical force).
    let wall_force = (solver.totals().wall_impulse[2] - impulse_before) / 0.5;
    let weight = fluid as f64 * solver.particle_mass() * cfg.gravity_magnitude();
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
        run_time_s: started.elapsed().as_secs_f64(),
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
    let mean_p: Vec<f64> = sum_p.iter().map(|s| s / samples as f64).collect();
    let top = top / samples as f64;
    let interior: Vec<(f64, f64)> = heights
        .iter()
        .zip(&mean_p)
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
    for (&z, &p) in heights.iter().zip(&mean_p) {
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
        run_time_s: started.elapsed().as_secs_f64(),
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
