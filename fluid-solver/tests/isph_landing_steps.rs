//! ISPH's steps shorter than the case's Δt (`fluid_solver::isph::step_length::pressure_step`): a
//! step that lands on an output, probe or window time after whole steps takes the pressure of a
//! step as long as the one whose pressure the step before took, and its share of the velocity
//! change; steps that are all short (intervals closer than Δt, the advective cut) are whole steps
//! of their own length.

use crate::isph_step_length::block_in_a_tank;

use fluid_solver::isph::step_length::pressure_step;
use fluid_solver::{FluidSolver, Kind};

#[test]
fn a_step_takes_its_own_pressure_unless_it_is_shorter_than_the_one_before_it() {
    let dt = 1e-3;
    let at = |step: f64, last: Option<f64>| pressure_step(step, dt, false, last);
    // a whole step, and the first step of a run, whatever its length
    assert_eq!(at(dt, Some(dt)), dt);
    assert_eq!(at(1e-4, None), 1e-4);
    // a landing remainder after whole steps shares the whole step's pressure
    assert_eq!(at(1e-7, Some(dt)), dt);
    assert_eq!(at(0.3 * dt, Some(dt)), dt);
    // steps closer than Δt, each as long as the one before it or longer: whole
    assert_eq!(at(0.4 * dt, Some(0.4 * dt)), 0.4 * dt);
    assert_eq!(at(0.8 * dt, Some(0.4 * dt)), 0.8 * dt);
    let rounded = 0.4 * dt * (1.0 - 1e-15);
    assert_eq!(at(rounded, Some(0.4 * dt)), rounded);
    // shorter than the step whose pressure the step before took: that step's
    assert_eq!(at(0.2 * dt, Some(0.4 * dt)), 0.4 * dt);
    // a step the advective limit cut shares Δt's pressure, first or not; a landing step after
    // a cut shares it too
    assert_eq!(pressure_step(0.5 * dt, dt, true, None), dt);
    assert_eq!(pressure_step(0.5 * dt, dt, true, Some(0.5 * dt)), dt);
    assert_eq!(at(0.2 * dt, Some(dt)), dt);
}

/// The dam break of [`block_in_a_tank`] at `time_step`.
fn dam_break(time_step: f64) -> FluidSolver {
    let mut cfg = block_in_a_tank();
    cfg.time_step = time_step;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    FluidSolver::new(&cfg)
}

/// The fluid's positions after `solver` landed on every multiple of `interval` to `end`.
fn landed_every(mut solver: FluidSolver, interval: f64, end: u32) -> Vec<[f64; 3]> {
    for k in 1..=end {
        solver
            .advance_to(f64::from(k) * interval)
            .unwrap_or_else(|e| panic!("{e}"));
    }
    let p = solver.particles();
    let mut fluid: Vec<(u32, [f64; 3])> = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid.code())
        .map(|i| (p.id[i], [p.x[i], p.y[i], p.z[i]]))
        .collect();
    fluid.sort_by_key(|f| f.0);
    fluid.into_iter().map(|f| f.1).collect()
}

/// The largest distance between the same particles of two runs.
fn farthest(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(a, b)| (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, schemas::validation::max_or_nan)
}

/// Landing every Δt/3 (outputs or probes three times a step) steps the dam break as its case
/// at Δt/3 does, 90 steps to 0.054 s: the steps are whole steps of their own length (before, each
/// took a third of a whole step's velocity change and left two thirds of the divergence it
/// measured: the MARIN CI twin at Δt = 3.4e-3 s with probes every 1.2e-3 s read P1 +71 % of the
/// experiment, +8 % at Δt = 1.2e-3 s). The two runs differ only where the case's Δt still
/// enters: the pressure at t = 0 is the projection of a step of Δt (the first step starts from it;
/// 1.4 Pa apart of 790), which leaves the first step's velocities 1.6e-5 m/s apart; the particles
/// carry that on (1.4e-8 m after one step, 3.3e-7 m after 30, 9.8e-7 m after 90, the same at PPE
/// tolerances 1e-6 … 1e-12). Bound: Δs/1000, ten times that; with the rule before (every step
/// a third of a whole one) the runs end 2.0e-3 m apart.
#[test]
fn landing_closer_than_the_time_step_steps_as_the_case_at_that_interval() {
    let dt = 1.8e-3;
    let third = dt / 3.0;
    let closer = landed_every(dam_break(dt), third, 90);
    let at_third = landed_every(dam_break(third), third, 90);
    let off = farthest(&closer, &at_third);
    println!("landing every Δt/3 against the case at Δt/3: {off:.3e} m");
    assert!(
        off < 1e-5,
        "{off:e} m apart: each step must be a whole step of its own length"
    );
}
