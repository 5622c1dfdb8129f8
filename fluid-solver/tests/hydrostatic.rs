//! Hydrostatic tank: after settling, the pressure at depth h is ρ g h within 3 % in the interior
//! (issue 3's bound), and no particle gets through a wall.

mod common;

use fluid_solver::probes;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{ProbeConfig, ProbeKind};

fn probe(kind: ProbeKind, position: Vec<f64>) -> ProbeConfig {
    ProbeConfig { name: "p".into(), kind, position, axis: None }
}

#[test]
fn settled_pressure_is_rho_g_h_and_walls_hold() {
    let (_, mut cfg) = common::load_case("hydrostatic-tank");
    // CI size: Δs = 0.02 m, water 0.3 m deep: 10 × 10 × 15 = 1500 fluid particles;
    // c = √(2 g 0.3)/0.2 = 12.1 m/s, Δt = 8e-4 s (c Δt/Δs = 0.48).
    cfg.spacing = 0.02;
    cfg.tank.max = [0.2, 0.2, 0.4];
    cfg.block[0].max = [0.2, 0.2, 0.3];
    cfg.time_step = 8.0e-4;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let ds = cfg.spacing;
    let rho = cfg.density;
    let g = cfg.gravity_magnitude();
    let mut solver = FluidSolver::new(&cfg);
    let fluid = solver.particles().count(Kind::Fluid);
    let tank = solver.tank();

    // Interior points on the tank's axis: 5 spacings from the side walls, and deeper than
    // r_e + r_e,grad = 5.2 Δs below the surface, so every particle the point probe averages
    // over (within r_e,grad) has the full number-density support of S1-15 (the free surface
    // has P = 0 by S1-14 and a truncated sum above it).
    let depths_z: Vec<f64> = (1..=9).map(|k| k as f64 * ds).collect();
    let gauge = probe(ProbeKind::WaterHeight, vec![0.1, 0.1]);

    // Settle for 1.5 s (≈ 15 periods of the column's first acoustic mode 4H/c ≈ 0.1 s),
    // then average over 0.5 s.
    solver.advance_to(1.5).unwrap_or_else(|e| panic!("{e}"));
    let mut sum_p = vec![0.0; depths_z.len()];
    let mut surface = 0.0;
    let mut samples = 0usize;
    while solver.time() < 2.0 - 1e-9 {
        solver.advance_to(solver.time() + 0.01).unwrap_or_else(|e| panic!("{e}"));
        let p = solver.particles();
        for (k, &z) in depths_z.iter().enumerate() {
            sum_p[k] += probes::sample(&probe(ProbeKind::Pressure, vec![0.1, 0.1, z]), p, solver.kernel(), &tank);
        }
        surface += probes::sample(&gauge, p, solver.kernel(), &tank);
        samples += 1;
        for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid.code()) {
            let r = p.position(i);
            let inside = r[0] > -0.5 * ds && r[0] < 0.2 + 0.5 * ds && r[1] > -0.5 * ds && r[1] < 0.2 + 0.5 * ds;
            assert!(inside && r[2] > -0.5 * ds, "particle {} went through a wall: {r:?}", p.id[i]);
        }
    }
    assert_eq!(solver.particles().count(Kind::Fluid), fluid, "fluid particles were lost or created");
    let surface = surface / samples as f64;
    println!("mean free surface {surface:.5} m (initial 0.3 m)");
    println!("z [m]   depth [m]  P [Pa]     rho g h [Pa]  error");
    let mut worst: f64 = 0.0;
    for (k, &z) in depths_z.iter().enumerate() {
        let p = sum_p[k] / samples as f64;
        let depth = surface - z;
        let exact = rho * g * depth;
        let err = (p - exact) / exact;
        println!("{z:.3}   {depth:.5}    {p:9.2}  {exact:9.2}     {:+.2} %", 100.0 * err);
        assert!(depth > 5.2 * ds, "probe at z = {z} is not interior (depth {depth})");
        worst = worst.max(err.abs());
    }
    println!("worst interior error {:.2} %", 100.0 * worst);
    assert!(worst < 0.03, "interior pressure differs from rho g h by {:.2} % (bound 3 %)", 100.0 * worst);
}
