//! The energy-balance check (`frame/energy_check.rs`): the frame benchmark's 3 × 3 × 3 building,
//! σy = 20 MPa, 20 kN sideways on every node, hinges forming and closing from step 19 at Δt = 1 ms.
//! One solve per step at 1 ms loses the balance (its hinges chatter) and warns; the same building
//! iterated at 1 ms, or with one solve per step at 0.5 ms, balances and does not.

use crate::frame_common;

use frame_common::{building, energy_share, sideways_loads};
use schemas::validation::largest;
use structure_solver::frame::energy_check::ENERGY_WARNING_SHARE;
use structure_solver::frame::{Equilibrium, Frame};

/// Runs the building for `duration` s at `dt`; returns the frame and the worst |residual| / scale,
/// the scale as in the check: max(|W|, T + U, D_p + D_d + D_alg) (at rest when recording starts).
fn building_run(dt: f64, equilibrium: Equilibrium, duration: f64) -> (Frame, f64) {
    let mut cfg = building(3, 2e7);
    cfg.time_step = dt;
    let mut frame = Frame::from_config(&cfg, "structure.b.frame").expect("valid test config");
    frame.set_equilibrium(equilibrium).expect("equilibrium");
    frame.record_energy(true);
    frame.record_hinge_events(true);
    let loads = sideways_loads(frame.node_count(), 2e4);
    let mut worst: f64 = 0.0;
    let steps = (duration / dt).round() as usize;
    for _ in 0..steps {
        frame.step(dt, &loads).expect("stable step");
        let row = frame.energy().expect("recorded");
        worst = largest([worst, energy_share(&row)], 0.0);
    }
    let row = frame.energy().expect("recorded");
    println!(
        "Δt = {dt} {equilibrium:?}: W {:.3e} J, T {:.3e}, D_p {:.3e}, residual {:.3e} (worst {worst:.2e} of the \
         scale), {} hinge events; warning: {:?}",
        row.external,
        row.kinetic,
        row.plastic,
        row.residual,
        frame.hinge_events().len(),
        frame.energy_warning()
    );
    (frame, worst)
}

/// Measured: the residual passes 1 % of the energy scale at step 52 (t = 0.052 s) and ends at −3.9e6 J
/// against W = 2.0e5 J at 0.12 s, with 7 545 hinge events (356 iterated). 60 steps, 0.2 s.
#[test]
fn one_solve_steps_with_chattering_hinges_warn() {
    let (frame, _) = building_run(1e-3, Equilibrium::OneSolve, 0.06);
    let w = frame.energy_warning().expect("the balance is lost");
    for part in [
        "energy balance is lost at t = 0.05",
        "equilibrium_tolerance",
        "time_step",
        "hinges formed or closed",
        "undoing the change",
    ] {
        assert!(w.contains(part), "`{part}` in: {w}");
    }
}

/// Measured worst |residual| / scale over 0.12 s: 1.7e-5 iterated, 6.7e-4 with one solve at 0.5 ms
/// (5.5e-4 at 0.25 ms); the test's bound is a tenth of the threshold. About 1 s together.
#[test]
fn accurate_building_runs_do_not_warn() {
    for (dt, equilibrium) in [
        (1e-3, Equilibrium::Iterate { tolerance: 1e-6 }),
        (5e-4, Equilibrium::OneSolve),
    ] {
        let (frame, worst) = building_run(dt, equilibrium, 0.12);
        assert!(
            frame.energy_warning().is_none(),
            "Δt = {dt}: {:?}",
            frame.energy_warning()
        );
        assert!(
            worst < 0.1 * ENERGY_WARNING_SHARE,
            "Δt = {dt}: worst share {worst:e}"
        );
    }
}
