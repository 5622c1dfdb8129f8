//! A block of water thrown down onto a box held fixed: the fluid's momentum change is gravity's
//! impulse minus the impulse of the loads the fluid reports on the box (viscous and pressure
//! pairs and collisions together), to round-off: every bit of momentum the fluid gives the body
//! is in the loads, and the reaction the fluid reports balances them, forces and moments. No
//! water particle gets through the box's outer particle layer.

use crate::bodies_common;

use bodies_common::tank_with_body;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::Aabb;
use schemas::validation::{largest_abs, record, Record};
use std::time::Instant;

#[test]
fn the_loads_carry_all_the_momentum_the_fluid_gives_the_body() {
    // Δs = 0.02 m; a 16 × 16 × 8 cm box on 4 cm legs of nothing (held in place) in the middle of
    // a 0.4 × 0.4 m tank; an 8 cm cube of water 4 cm above it, thrown down at 1.5 m/s. It hits
    // at t ≈ 0.02 s with ≈ 1.6 m/s and spreads over the box's top; in 0.1 s it reaches neither
    // the walls nor the floor, so the box is all it touches.
    let body = Aabb {
        min: [0.12, 0.12, 0.04],
        max: [0.28, 0.28, 0.12],
    };
    let drop = Aabb {
        min: [0.16, 0.16, 0.16],
        max: [0.24, 0.24, 0.24],
    };
    let mut cfg = tank_with_body([0.4, 0.4, 0.4], 0.02, 8.0e-4, drop, body);
    // The viscous term on, with ν large enough (ν Δt/Δs² = 2e-3) for its exchange with the box
    // to count in the balance.
    cfg.viscosity_term = true;
    cfg.viscosity = 1.0e-3;
    let started = Instant::now();
    let mut solver = FluidSolver::new(&cfg);
    let fluid = Kind::Fluid.code();
    let p = solver.particles_mut();
    for i in (0..p.len()).filter(|&i| p.kind[i] == fluid) {
        p.vz[i] = -1.5;
    }
    let mass = solver.particle_mass() * solver.particles().count(Kind::Fluid) as f64;
    let start = solver.fluid_momentum();

    let mut impulse_on_body = [0.0; 3];
    let mut peak: f64 = 0.0;
    while let Some(dt) = solver.next_step_towards(0.1) {
        solver.step(dt).unwrap_or_else(|e| panic!("{e}"));
        let (loads, reaction) = (solver.body_loads(), solver.body_reactions());
        let size = loads.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        for (a, (l, r)) in loads.iter().zip(&reaction).enumerate() {
            assert!(
                (l + r).abs() <= 1e-9 * size,
                "component {a}: load {l}, reaction {r}"
            );
        }
        (0..3).for_each(|a| impulse_on_body[a] += loads[a] * dt);
        peak = peak.max(-loads[2]);
        let p = solver.particles();
        for i in (0..p.len()).filter(|&i| p.kind[i] == fluid) {
            let r = p.position(i);
            let through = (0..3).all(|a| r[a] > body.min[a] + 0.01 && r[a] < body.max[a] - 0.01);
            assert!(
                !through,
                "particle {} is inside the box at t = {}: {r:?}",
                p.id[i],
                solver.time()
            );
            assert!(
                r[2] > 0.03,
                "particle {} reached the floor: the scene is too long",
                p.id[i]
            );
        }
    }
    let end = solver.fluid_momentum();
    let gravity = cfg.gravity.map(|g| mass * g * solver.time());
    let scale = mass * 1.5 + gravity[2].abs();
    let residual: Vec<f64> = (0..3)
        .map(|a| end[a] - start[a] - gravity[a] + impulse_on_body[a])
        .collect();
    println!(
        "fluid momentum {start:?} → {end:?} kg m/s; gravity's impulse {gravity:?}; impulse of the loads on the box {impulse_on_body:?}; residual {residual:?}; peak downward load {peak:.3} N"
    );
    // The drop must have hit: the box took most of its downward momentum.
    assert!(
        impulse_on_body[2] < -0.5 * mass * 1.5,
        "the box was hardly hit: {impulse_on_body:?}"
    );
    record(Record {
        id: "body-emps-momentum-drop-on-a-box".into(),
        capability: "E-MPS momentum shared with a held body".into(),
        reference:
            "Newton's second law: the fluid's momentum changes by gravity's impulse minus the impulse of \
                    its loads on the box"
                .into(),
        case:
            "an 8 cm cube of water thrown down at 1.5 m/s onto a 16 × 16 × 8 cm held box, viscous, 0 … 0.1 s"
                .into(),
        resolution: "E-MPS, Δs = 0.02 m, Δt = 8e-4 s".into(),
        measure: "largest |momentum residual| over the axes / (m · 1.5 m/s + gravity's impulse)".into(),
        value: largest_abs(residual.iter().copied()) / scale,
        bound: Some(1e-9),
        bound_source: "round-off: the loads are the fluid's pair terms with the body".into(),
        source:
            "fluid-solver/tests/bodies_momentum.rs::the_loads_carry_all_the_momentum_the_fluid_gives_the_body"
                .into(),
        run_time_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    });
    for (a, r) in residual.iter().enumerate() {
        assert!(
            r.abs() < 1e-9 * scale,
            "momentum balance along axis {a}: residual {r} kg m/s"
        );
    }
}
