//! Issue 13: point reactions of the drag coupling change the fluid's momentum by exactly their
//! impulse: with reactions at the surface, at the floor and inside, the budget
//! `Δp = M g t + wall impulse + reaction impulse` closes to round-off (as conservation.rs's does
//! without them), and the reaction impulse is Σ F Δt; the same for reactions spread over a wide
//! member's footprint.
use crate::closed_box;

use fluid_solver::{FluidSolver, Kind};
use schemas::validation::{largest_abs, record, Record};

#[test]
fn point_reactions_change_the_fluid_momentum_by_their_impulse() {
    momentum_budget_closes(&[]);
}

/// The same reactions from members 0.06 m wide (3 particles: spread over their footprints).
#[test]
fn a_wide_members_reactions_change_the_fluid_momentum_by_their_impulse() {
    momentum_budget_closes(&[0.06; 3]);
}

/// Steps the box with three reactions from members `widths` wide (none: points) and checks the
/// fluid's momentum budget.
fn momentum_budget_closes(widths: &[f64]) {
    let cfg = closed_box::closed_box([0.0, 0.0, 0.0], [0.2, 0.2, 0.12]);
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let started = std::time::Instant::now();
    let mut solver = FluidSolver::new(&cfg);
    let mass = solver.particles().count(Kind::Fluid) as f64 * solver.particle_mass();
    // Three sub-members: at the surface, on the floor, inside (point, force −f).
    let reactions = [
        0.1, 0.1, 0.115, 0.3, 0.0, -0.1, //
        0.05, 0.1, 0.005, -0.2, 0.1, 0.0, //
        0.15, 0.15, 0.06, 0.05, 0.05, 0.2,
    ];
    solver.set_point_reactions(&reactions, &[], widths);
    let steps = 100;
    for _ in 0..steps {
        solver.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
    }
    let t = solver.time();
    let p1 = solver.fluid_momentum();
    let totals = solver.totals();
    let given: Vec<f64> = (0..3)
        .map(|c| reactions.chunks_exact(6).map(|r| r[3 + c]).sum::<f64>() * t)
        .collect();
    let scale = mass * 9.8 * t;
    println!(
        "momentum {p1:?}, reactions {:?} (given {given:?}), walls {:?}",
        totals.reaction_impulse, totals.wall_impulse
    );
    let worst =
        largest_abs((0..3).map(|c| {
            p1[c] - mass * cfg.gravity[c] * t - totals.wall_impulse[c] - totals.reaction_impulse[c]
        }));
    let (tag, members, test) = match widths.is_empty() {
        true => (
            "points",
            "three point reactions",
            "point_reactions_change_the_fluid_momentum_by_their_impulse",
        ),
        false => (
            "wide-members",
            "three reactions of members 0.06 m wide (spread over their footprints)",
            "a_wide_members_reactions_change_the_fluid_momentum_by_their_impulse",
        ),
    };
    record(Record {
        id: format!("drag-fluid-momentum-{tag}"),
        capability: "Unresolved drag, the fluid's side: momentum of the reactions".into(),
        reference: "Newton's second law: Δp = M g t + wall impulse + reaction impulse".into(),
        case: format!("water 0.12 m deep in a closed box 0.2 × 0.2 m with {members}, 100 steps"),
        resolution: "E-MPS, Δs = 0.02 m".into(),
        measure: "largest |momentum residual| over the axes / (M g t)".into(),
        value: worst / scale,
        bound: Some(1e-9),
        bound_source: "round-off, as conservation.rs's budget without reactions".into(),
        source: format!("fluid-solver/tests/unresolved_momentum.rs::{test}"),
        run_time_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    });
    assert_eq!(totals.unapplied_impulse, [0.0; 3], "every reaction found water");
    for c in 0..3 {
        // Σ f_k = F per step (normalised shares): round-off of 100 steps of ~50 terms.
        assert!(
            (totals.reaction_impulse[c] - given[c]).abs() < 1e-12,
            "axis {c}: reaction impulse"
        );
        let residual =
            p1[c] - mass * cfg.gravity[c] * t - totals.wall_impulse[c] - totals.reaction_impulse[c];
        // the same round-off bound as conservation.rs's budget without reactions
        assert!(
            residual.abs() < 1e-9 * scale,
            "axis {c}: momentum residual {residual} of {scale}"
        );
    }
}
