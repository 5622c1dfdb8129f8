//! Particles leaving through an open top are removed and counted (issue 15, item 1): one drop
//! thrown over a side wall leaves, the run goes on to its end with the count, and the run stops
//! only when more than the case's `max_removed_fraction` has left.

use crate::common;

use fluid_solver::{FluidSolver, Kind};
use schemas::case::FluidConfig;

/// Water 0.1 m deep in a 0.2 × 0.2 × 0.16 m open tank at Δs = 0.02 m (500 fluid particles); a
/// surface particle at x = y = 0.11 m is thrown at (2, 0, 2.5) m/s: it passes over the +x wall
/// (x = 0.2 m) at z ≈ 0.19 m, above its top (0.16 m), and leaves the domain through the wall's
/// outer face (x = 0.28 m) at z ≈ 0.27 m after 0.085 s.
fn thrown_drop(max_removed_fraction: f64) -> (FluidSolver, usize) {
    let (_, mut cfg): (_, FluidConfig) = common::load_case("hydrostatic-tank");
    cfg.spacing = 0.02;
    cfg.tank.max = [0.2, 0.2, 0.16];
    cfg.block[0].max = [0.2, 0.2, 0.1];
    cfg.time_step = 1.0e-3;
    cfg.sound_speed = Some(10.0);
    cfg.max_removed_fraction = max_removed_fraction;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let mut solver = FluidSolver::new(&cfg);
    let fluid = solver.particles().count(Kind::Fluid);
    let p = solver.particles_mut();
    let drop = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid.code())
        .filter(|&i| (p.x[i] - 0.11).abs() < 1e-9 && (p.y[i] - 0.11).abs() < 1e-9)
        .max_by(|&a, &b| p.z[a].total_cmp(&p.z[b]))
        .unwrap_or_else(|| panic!("no fluid at x = y = 0.11 m"));
    (p.vx[drop], p.vz[drop]) = (2.0, 2.5);
    (solver, fluid)
}

#[test]
fn a_drop_over_the_open_top_is_removed_and_counted_and_the_run_ends() {
    let (mut solver, fluid) = thrown_drop(0.01);
    solver
        .advance_to(0.15)
        .unwrap_or_else(|e| panic!("the run must go on: {e}"));
    assert_eq!(solver.escaped(), 1, "one drop left through the open top");
    assert_eq!(solver.removed(), 1);
    assert_eq!(solver.particles().count(Kind::Fluid), fluid - 1);
}

#[test]
fn more_than_the_allowed_fraction_leaving_stops_the_run() {
    let (mut solver, _) = thrown_drop(0.0);
    let err = solver
        .advance_to(0.15)
        .err()
        .unwrap_or_else(|| panic!("with max_removed_fraction = 0 one drop must stop the run"));
    assert_eq!(err.quantity, "removed particles", "{err}");
    assert!(err.to_string().contains("max_removed_fraction"), "{err}");
}
