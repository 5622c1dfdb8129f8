//! Issue 13 (cost): the shares of the point reactions found while sampling at the window end
//! (`FluidSolver::sample_points_for`) are reused by the next step's spreading only while the
//! particles have not moved and the centroids and sample points are the same, and then give the
//! same forces to the last bit as searching the cell list again; the samples are those of
//! `sample_points` to the last bit.
use crate::closed_box;

use fluid_solver::unresolved::spreading::spread;
use fluid_solver::FluidSolver;
use schemas::case::FluidConfig;

#[test]
fn shares_found_while_sampling_spread_as_a_new_search_and_never_after_a_step() {
    let (cfg, mut solver) = stepped_box();
    // Sub-members (centroid, force −f) with their sample points: inside (sample point 4 mm
    // upstream: one search for both), at the floor, at the surface, 6 cm upstream (two searches),
    // just above the water with a wet sample point (spread around the sample point), in the air
    // (dry), and one with no force.
    let reactions = [
        0.1, 0.1, 0.06, 0.3, 0.0, -0.1, //
        0.05, 0.1, 0.005, -0.2, 0.1, 0.0, //
        0.1, 0.1, 0.115, 0.05, 0.05, 0.2, //
        0.15, 0.15, 0.06, 0.1, 0.0, 0.0, //
        0.1, 0.05, 0.165, 0.0, 0.0, 0.1, //
        0.1, 0.1, 0.25, 0.1, 0.0, 0.0, //
        0.12, 0.1, 0.05, 0.0, 0.0, 0.0,
    ];
    let points = [
        0.096, 0.1, 0.06, //
        0.046, 0.1, 0.005, //
        0.096, 0.1, 0.115, //
        0.09, 0.15, 0.06, //
        0.1, 0.05, 0.145, //
        0.096, 0.1, 0.25, //
        0.116, 0.1, 0.05,
    ];
    let searched = |s: &FluidSolver| {
        spread(
            s.particles(),
            s.cell_grid(),
            cfg.spacing,
            &reactions,
            &points,
            &[],
        )
    };
    let (v, lambda) = solver.sample_points_for(&points, &reactions, &[]);
    assert_eq!(
        (v, lambda),
        solver.sample_points(&points),
        "the samples are those of sample_points"
    );
    let reused = solver.spread_point_reactions(&reactions, &points, &[]);
    let fresh = searched(&solver);
    println!(
        "total {:?}, moved {}, unapplied {}",
        fresh.total, fresh.moved, fresh.unapplied
    );
    assert_eq!(
        reused, fresh,
        "reused shares spread as a new search, to the last bit"
    );
    assert_eq!(
        (fresh.moved, fresh.unapplied),
        (1, 1),
        "one moved to its sample point, one unapplied"
    );
    // other reactions (a centroid moved by 1 mm): searched, not taken from the shares
    let mut shifted = reactions;
    shifted[0] += 0.001;
    assert_eq!(
        solver.spread_point_reactions(&shifted, &points, &[]),
        spread(
            solver.particles(),
            solver.cell_grid(),
            cfg.spacing,
            &shifted,
            &points,
            &[]
        )
    );
    // after a step the particles have moved: the shares of the last sampling are stale
    solver.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
    let after = solver.spread_point_reactions(&reactions, &points, &[]);
    assert_eq!(
        after,
        searched(&solver),
        "after a step the cell list is searched again"
    );
    assert_ne!(after.force, reused.force, "the particles moved");
    // and after a particle near the first centroid was moved by hand
    solver.sample_points_for(&points, &reactions, &[]);
    let before = solver.spread_point_reactions(&reactions, &points, &[]);
    let near = solver
        .cell_grid()
        .particles_near(solver.particles(), [0.1, 0.1, 0.06], 0.02)[0];
    solver.particles_mut().x[near] += 1e-3;
    let changed = solver.spread_point_reactions(&reactions, &points, &[]);
    assert_eq!(changed, searched(&solver));
    assert_ne!(changed.force, before.force, "the moved particle's share changed");
}

#[test]
fn a_wide_members_shares_found_while_sampling_spread_as_a_new_search_for_the_same_widths_only() {
    let (cfg, solver) = stepped_box();
    // a member 3 particles wide (a = Δs), its sample points one width upstream, and a thin one
    let reactions = [
        0.1, 0.1, 0.06, 0.3, 0.0, -0.1, //
        0.1, 0.1, 0.005, -0.2, 0.1, 0.0, //
        0.1, 0.1, 0.115, 0.05, 0.05, 0.2, //
        0.15, 0.15, 0.06, 0.1, 0.0, 0.0,
    ];
    let points = [
        0.04, 0.1, 0.06, //
        0.04, 0.1, 0.005, //
        0.04, 0.1, 0.115, //
        0.146, 0.15, 0.06,
    ];
    let widths = [0.06, 0.06, 0.06, 0.004];
    let searched = |s: &FluidSolver, w: &[f64]| {
        spread(s.particles(), s.cell_grid(), cfg.spacing, &reactions, &points, w)
    };
    let (v, lambda) = solver.sample_points_for(&points, &reactions, &widths);
    assert_eq!((v, lambda), solver.sample_points(&points));
    let reused = solver.spread_point_reactions(&reactions, &points, &widths);
    assert_eq!(
        reused,
        searched(&solver, &widths),
        "reused shares, to the last bit"
    );
    assert_eq!(reused.unapplied, 0);
    // other widths (the points' shares): searched again, not taken from the footprints' shares
    let as_points = solver.spread_point_reactions(&reactions, &points, &[]);
    assert_eq!(as_points, searched(&solver, &[]));
    assert_ne!(as_points.force, reused.force);
}

/// The closed box of water 0.2 × 0.2 × 0.12 m, its case and its solver after one step (the cell
/// list sorted).
fn stepped_box() -> (FluidConfig, FluidSolver) {
    let cfg = closed_box::closed_box([0.0, 0.0, 0.0], [0.2, 0.2, 0.12]);
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let mut solver = FluidSolver::new(&cfg);
    solver.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
    (cfg, solver)
}
