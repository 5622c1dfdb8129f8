//! Conservation: fluid mass is the particle count; the fluid's momentum changes only by
//! gravity and the forces of the walls; save/restore and advance-to behave as the coupler needs.

use crate::closed_box;
use crate::common;

use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{Aabb, FluidConfig};
use schemas::validation::{largest_abs, record, Record};
use std::time::Instant;

/// A closed box 0.2 × 0.2 × 0.3 m with a water block held 0.1 m above the floor.
fn free_drop() -> FluidConfig {
    let mut cfg = closed_box::closed_box([0.04, 0.04, 0.1], [0.16, 0.16, 0.22]);
    cfg.viscosity = 1.0e-4; // large enough that the viscous wall force matters
    cfg.viscosity_term = true;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}

#[test]
fn momentum_changes_only_by_gravity_and_wall_forces() {
    let cfg = free_drop();
    let started = Instant::now();
    let mut solver = FluidSolver::new(&cfg);
    let fluid = solver.particles().count(Kind::Fluid);
    let mass = fluid as f64 * solver.particle_mass();
    let p0 = solver.fluid_momentum();
    assert_eq!(p0, [0.0; 3]);
    solver.advance_to(0.4).unwrap_or_else(|e| panic!("{e}"));
    let t = solver.time();
    let p1 = solver.fluid_momentum();
    let wall = solver.totals().wall_impulse;
    let gravity = cfg.gravity.map(|g| mass * g * t);
    let scale = mass * cfg.gravity_magnitude() * t;
    println!("momentum {p1:?}, gravity impulse {gravity:?}, wall impulse {wall:?}");
    // The walls must have acted (the water hit the floor) …
    assert!(
        wall[2] > 0.5 * scale,
        "the floor did not stop the water: wall impulse {wall:?}"
    );
    // … and the balance closes to round-off: fluid–fluid pressure (S1-3, (P_i + P_j) r_ij is
    // antisymmetric), viscous (S1-4) and collision forces cancel in pairs.
    let worst = largest_abs((0..3).map(|a| p1[a] - p0[a] - gravity[a] - wall[a]));
    record(Record {
        id: "emps-momentum-closed-box-drop".into(),
        capability: "E-MPS momentum budget".into(),
        reference:
            "Newton's second law: the fluid's momentum changes only by gravity's and the walls' impulse"
                .into(),
        case: "a water block dropped 0.1 m in a closed box 0.2 × 0.2 × 0.3 m, viscous, 0 … 0.4 s".into(),
        resolution: "E-MPS, Δs = 0.02 m".into(),
        measure: "largest |Δp − gravity impulse − wall impulse| over the axes / (m g t)".into(),
        value: worst / scale,
        bound: Some(1e-9),
        bound_source: "round-off: pressure (S1-3), viscous (S1-4) and collision pair forces cancel in pairs"
            .into(),
        source: "fluid-solver/tests/conservation.rs::momentum_changes_only_by_gravity_and_wall_forces".into(),
        run_time_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    });
    for a in 0..3 {
        let residual = p1[a] - p0[a] - gravity[a] - wall[a];
        assert!(
            residual.abs() < 1e-9 * scale,
            "axis {a}: momentum residual {residual} of {scale}"
        );
    }
    // Mass: the count of fluid particles (each ρ0 Δs³) never changes.
    assert_eq!(solver.particles().count(Kind::Fluid), fluid);
}

#[test]
fn fluid_mass_is_the_particle_count_through_a_dam_break() {
    let (_, mut cfg) = common::load_case("dam-break-tank");
    cfg.spacing = 0.03;
    cfg.time_step = 1.0e-3;
    cfg.gate = vec![Aabb {
        min: [0.3, 0.0, 0.0],
        max: [0.36, 0.3, 0.3],
    }];
    cfg.validate("fluid.tank").unwrap_or_else(|e| panic!("{e:?}"));
    let mut solver = FluidSolver::new(&cfg);
    let fluid = solver.particles().count(Kind::Fluid);
    assert_eq!(fluid, 10 * 10 * 10);
    let gate = solver.particles().count(Kind::Gate);
    assert_eq!(gate, 2 * 10 * 10, "the board is in the initial layout");
    let total = solver.particles().len();
    solver.advance_to(0.3).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        solver.particles().count(Kind::Gate),
        0,
        "the board is gone after t = 0"
    );
    assert_eq!(solver.particles().len(), total - gate);
    assert_eq!(solver.particles().count(Kind::Fluid), fluid);
    let mut ids: Vec<u32> = solver.particles().id.clone();
    ids.sort_unstable();
    ids.dedup();
    assert_eq!(ids.len(), total - gate, "every particle keeps a distinct id");
}

#[test]
fn restore_then_advance_repeats_the_run_and_lands_on_the_window_end() {
    let cfg = free_drop();
    let mut solver = FluidSolver::new(&cfg);
    solver.advance_to(0.05).unwrap_or_else(|e| panic!("{e}"));
    let saved = solver.save_state();
    // A window end that is not a multiple of Δt: the last substep is shortened.
    let end = 0.05 + 7.3 * cfg.time_step;
    solver.advance_to(end).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(solver.time(), end);
    let first = solver.particles().clone();
    solver.restore_state(&saved);
    assert_eq!(solver.time(), 0.05);
    solver.advance_to(end).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        solver.particles(),
        &first,
        "a restored run must repeat bit for bit"
    );
}
