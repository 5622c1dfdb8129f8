//! ISPH dam break: the surge front of a column L × 2L against Koshizuka & Oka (1996) and Martin &
//! Moyce (1952, n² = 2, a = 2.25 in), as `dam_break.rs` does for E-MPS, with bounds at least as
//! tight as its (issue 12).

use crate::common;
use crate::front_common;
use crate::front_record;
use crate::isph_slab;

use front_record::FrontRecord;
use std::time::Instant;

#[test]
fn isph_surge_front_follows_the_experiments() {
    // CI size as the E-MPS test: Δs = L/10 = 0.0146 m, a slab 4 particles deep (800 fluid
    // particles); Δt = 1.6e-3 s (u Δt/Δs = 0.37 with the front speed u = 2√(g·2L), Ritter),
    // 2.7× E-MPS's 6e-4 s.
    let cfg = isph_slab::isph_slab();
    let started = Instant::now();
    let e = front_common::front_errors(&cfg, 0.006, 4);
    record_fronts(
        &e,
        "isph",
        "ISPH dam-break front",
        "ISPH (default: exact projection, support 2.0 Δs)",
        "isph_surge_front_follows_the_experiments",
        started,
    );
    front_common::assert_within_the_e_mps_bounds(&e, true);
}

/// The same with `pressure_gradient = "symmetric"` at a support of 2.0 Δs, same bounds.
#[test]
fn isph_symmetric_gradient_surge_front_follows_the_experiments() {
    let mut cfg = isph_slab::isph_slab();
    cfg.isph = Some(symmetric());
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let started = Instant::now();
    let e = front_common::front_errors(&cfg, 0.006, 4);
    record_fronts(
        &e,
        "isph-symmetric",
        "ISPH dam-break front, symmetric gradient",
        "ISPH, symmetric gradient at 2.0 Δs",
        "isph_symmetric_gradient_surge_front_follows_the_experiments",
        started,
    );
    front_common::assert_within_the_e_mps_bounds(&e, true);
}

/// The same with S2-8's gradient (`pressure_gradient = "corrected-difference"`) at its support
/// of 2.4 Δs, same bounds.
#[test]
fn isph_s2_8_gradient_surge_front_follows_the_experiments() {
    let mut cfg = isph_slab::isph_slab();
    cfg.isph = Some(s2_8());
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let started = Instant::now();
    let e = front_common::front_errors(&cfg, 0.006, 4);
    record_fronts(
        &e,
        "isph-s2-8",
        "ISPH dam-break front, S2-8 gradient",
        "ISPH, S2-8 gradient at 2.4 Δs",
        "isph_s2_8_gradient_surge_front_follows_the_experiments",
        started,
    );
    front_common::assert_within_the_e_mps_bounds(&e, true);
}

/// The same with particle shifting (`shifting = "lind"`, the default coefficient) on the
/// symmetric gradient at 2.0 Δs, same bounds.
#[test]
fn isph_shifting_surge_front_follows_the_experiments() {
    let mut cfg = isph_slab::isph_slab();
    cfg.isph = Some(shifting());
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let started = Instant::now();
    let e = front_common::front_errors(&cfg, 0.006, 4);
    record_fronts(
        &e,
        "isph-shifting",
        "ISPH dam-break front, symmetric gradient + shifting",
        "ISPH, symmetric gradient at 2.0 Δs with Lind shifting (A = 0.5)",
        "isph_shifting_surge_front_follows_the_experiments",
        started,
    );
    front_common::assert_within_the_e_mps_bounds(&e, true);
}

/// The symmetric gradient at a support of 2.0 Δs with `shifting = "lind"`.
fn shifting() -> schemas::case::fluid::IsphConfig {
    schemas::case::fluid::IsphConfig {
        shifting: schemas::case::fluid::Shifting::Lind,
        ..symmetric()
    }
}

/// The CI dam break of `isph_surge_front_follows_the_experiments` run on past the impact, the
/// run-up and the return wave to t = 1.5 s (about 60 s in release): it stopped at t = 0.75 s
/// when a splash particle that had landed on the top of the 4-particle slab's side wall was
/// called inside the wall (`wall_top.rs`). The run-up on the far wall rises to z = 0.65 m, 0.21 m
/// above the walls' top, and in a slab 4 particles wide some of its splash falls over the side
/// walls: it is removed and counted. Measured: 6 of 800 by 0.9 s and none more to 1.5 s, within
/// the default `max_removed_fraction` of 1 % (E-MPS on the same slab loses none to t = 3 s).
/// While the walls held back water leaving them at the free surface (`isph::walls`), 22 left
/// by 1.0 s, and 36 by 1.5 s once the pressure gradient took in the dry wall particles.
#[test]
#[ignore]
fn isph_dam_break_runs_past_the_run_up() {
    let cfg = isph_slab::isph_slab();
    let mut solver = fluid_solver::FluidSolver::new(&cfg);
    for k in 1..=15 {
        solver
            .advance_to(0.1 * f64::from(k))
            .unwrap_or_else(|e| panic!("{e}"));
        println!("t = {:.1} s: {} removed", solver.time(), solver.removed());
    }
}

/// The same dam break held by a gate (a partition board 2 Δs thick at the column's face, full
/// height) that is removed at t = 0 (issue 12: gates with ISPH): the gate is built, removed, and
/// the front follows Koshizuka & Oka within the bound of `isph_surge_front_follows_the_experiments`
/// (0.33) and Martin & Moyce within that test's 0.05 (measured with the default 0.208 and 0.018,
/// as without the gate, 1 Dec 2026; with S2-8's gradient 0.218 and 0.026).
///
/// With S2-12's ∇λ surface normal the gated front gave 0.070 against Martin & Moyce (0.046
/// without the gate; KO 0.156 and 0.219; the cause was not found). With Marrone's normal
/// (`isph::free_surface`) the gated and the ungated runs agree to the digits printed.
#[test]
fn isph_dam_break_released_by_a_gate_follows_the_experiments() {
    let mut cfg = isph_slab::isph_slab();
    cfg.gate = vec![schemas::case::fluid::Aabb {
        min: [0.146, 0.0, 0.0],
        max: [0.146 + 2.0 * 0.0146, 0.0584, 0.438],
    }];
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let gated = fluid_solver::FluidSolver::new(&cfg);
    let gates = gated.particles().count(fluid_solver::Kind::Gate);
    assert_eq!(gates, 2 * 4 * 30, "the gate: 2 layers × 4 × 30 sites");
    let started = Instant::now();
    let e = front_common::front_errors(&cfg, 0.006, 4);
    record_fronts(
        &e,
        "isph-gate",
        "ISPH dam-break front, column released by a gate",
        "ISPH (default: exact projection), a gate 2 Δs thick removed at t = 0",
        "isph_dam_break_released_by_a_gate_follows_the_experiments",
        started,
    );
    front_common::assert_within_the_e_mps_bounds(&e, false);
}

/// The report's ISPH rung of `cases/dam-break-koshizuka` at Δs = L/10 (the case's tank, 5
/// particles wide, 1 000 fluid particles) at Δt = 4e-4 s through the impact on the far wall, to
/// t = 0.3 s (about 40 s in release): nothing feeds the fluid energy (still walls, gravity
/// conservative), so the mechanical energy `Σ ½|u|² + g z` over the fluid particles may only
/// fall. Bound: what it gains over the steps in which it grows stays below 1 % of its initial
/// value (measured with the default 0.00 J/kg, 1 Dec 2026; with S2-8's gradient 0.43 %, 6.2 of
/// 1 430 J/kg, with the divergence corrected in Marrone's band,
/// `isph::operators::DivergenceSum`, whose floor this test and the L/20 one below set; 0.08 %,
/// 1.1 J/kg, before; 10 %, 144 J/kg, while the PPE's negative pressures pulled on parting water,
/// `isph::step`; the detector's own allowance is 30 %).
#[test]
#[ignore]
fn isph_dam_break_gains_no_energy_through_the_impact() {
    let started = Instant::now();
    let (mut solver, g) = koshizuka_isph(Some(0.0146), 4e-4);
    let e0 = mechanical_energy(&solver, g);
    let (last, gained) = energy_gained_until(&mut solver, g, 0.3);
    println!(
        "energy {e0:.1} → {last:.1} J/kg over {} steps, gained {gained:.2} in the steps it grew",
        solver.steps()
    );
    schemas::validation::record(schemas::validation::Record {
        id: "isph-energy-through-the-impact-l10".into(),
        capability: "ISPH energy through a dam break's impact".into(),
        reference: "energy conservation: still walls, conservative gravity (the energy may only fall)".into(),
        case: "cases/dam-break-koshizuka (the case's tank, 5 particles wide), 0 … 0.3 s".into(),
        resolution: "ISPH (default: exact projection), Δs = L/10 = 0.0146 m (1 000 fluid), Δt = 4e-4 s"
            .into(),
        measure: "energy Σ ½|u|² + g z gained over the steps in which it grew / initial energy".into(),
        value: 100.0 * gained / e0,
        bound: Some(1.0),
        bound_source: "the test's: 1 % of the initial energy (the detector's own allowance is 30 %)".into(),
        unit: "%".into(),
        source: "fluid-solver/tests/isph_dam_break.rs::isph_dam_break_gains_no_energy_through_the_impact"
            .into(),
        run_time_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    });
    assert!(
        gained < 0.01 * e0,
        "the fluid gained {gained:.2} J/kg of {e0:.1} (bound 1 %)"
    );
}

/// The L/20 rung of `cases/dam-break-koshizuka` (the case as written: Δs = 0.0073 m, the tank 10
/// particles wide, 8 000 fluid particles) with ISPH's default at Δt = 6e-4 s, before the surge
/// reaches the far wall: the energy `Σ ½|u|² + g z` gained over the steps in which it grows from
/// t = 0.10 to 0.16 s (about 20 s in release). Nothing feeds it, so it may only fall; bound 1 %
/// of the initial energy, the bound of `isph_dam_break_gains_no_energy_through_the_impact`.
#[test]
#[ignore]
fn isph_dam_break_gains_no_energy_before_the_impact_at_l_20() {
    let settings = schemas::case::fluid::IsphConfig::default();
    assert_gains_no_energy_before_the_impact("default", None, 6e-4, settings);
}

/// The CI twin of the test above: the same window at Δs = L/10 (the case's tank, 1 000 fluid
/// particles) and Δt = 1.2e-3 s (about 1 s in release).
#[test]
fn isph_dam_break_gains_no_energy_before_the_impact() {
    let settings = schemas::case::fluid::IsphConfig::default();
    assert_gains_no_energy_before_the_impact("default", Some(0.0146), 1.2e-3, settings);
}

/// The L/20 test with S2-8's gradient (`"corrected-difference"`), run in CI: at L/10 its
/// uncorrected divergence gained only 10.9 of 1 431 J/kg (0.76 %, within the bound; now 2.81),
/// so only this spacing tells its two divergences apart.
///
/// Measured with S2-8's corrected difference-form gradient and the divergence corrected as it
/// in Marrone's band (`isph::operators::DivergenceSum`): 11 446 J/kg at the start, 11 379 at
/// 0.10 s, 11 388 at 0.16 s, 40.1 J/kg gained (0.35 %; 38.6 before a short landing step took
/// a whole step's pressure, `IsphStep::short_step`). With the divergence uncorrected
/// (before 25 Nov 2026): 11 385 at 0.10 s, 11 605 at 0.16 s, 220.4 J/kg gained (1.9 %), the
/// pressure's work where D and the gradient disagree (the operator's doc). With the uncorrected
/// symmetric gradient `Σ_j V (p_i + p_j) ∇W_ij` (walls at p_i + Δp_ij), which conserves momentum
/// pairwise: 11 306 → 11 081 J/kg, nothing gained.
#[test]
fn isph_s2_8_gradient_dam_break_gains_no_energy_before_the_impact_at_l_20() {
    assert_gains_no_energy_before_the_impact("S2-8", None, 6e-4, s2_8());
}

/// The same with `pressure_gradient = "symmetric"` at a support of 2.0 Δs (about 20 s in
/// release), whose pair terms are antisymmetric: within the bound. Measured 94.0 J/kg (59.9
/// before the short landing step took a whole step's pressure). The sum of the rises moves with
/// the step's length more than that: 48.8 / 94.0 / 53.2 / 67.5 J/kg at Δt = 5.9 / 6.0 / 6.1 /
/// 6.2e-4 s (S2-8's gradient: 35.7 / 40.1 / 33.7 / 27.7), each landing on 0.10 s with a short step.
#[test]
#[ignore]
fn isph_symmetric_gradient_dam_break_gains_no_energy_before_the_impact_at_l_20() {
    assert_gains_no_energy_before_the_impact("symmetric", None, 6e-4, symmetric());
}

/// The CI twin of the test above: the same window at Δs = L/10 (the case's tank, 1 000 fluid
/// particles) and Δt = 1.2e-3 s (about 1 s in release). Measured: 0.00 J/kg gained (S2-8's
/// gradient gains 10.9 of 1 431 J/kg here, 0.76 %).
#[test]
fn isph_symmetric_gradient_dam_break_gains_no_energy_before_the_impact() {
    assert_gains_no_energy_before_the_impact("symmetric", Some(0.0146), 1.2e-3, symmetric());
}

/// The same with particle shifting on the symmetric gradient at 2.0 Δs (about 20 s in release).
#[test]
#[ignore]
fn isph_shifting_dam_break_gains_no_energy_before_the_impact_at_l_20() {
    assert_gains_no_energy_before_the_impact("shifting", None, 6e-4, shifting());
}

/// The CI twin of the test above, at Δs = L/10 as the symmetric one's (measured 0.00 J/kg
/// gained).
#[test]
fn isph_shifting_dam_break_gains_no_energy_before_the_impact() {
    assert_gains_no_energy_before_the_impact("shifting", Some(0.0146), 1.2e-3, shifting());
}

/// `pressure_gradient = "corrected-difference"` (S2-8) at its support of 2.4 Δs.
fn s2_8() -> schemas::case::fluid::IsphConfig {
    schemas::case::fluid::IsphConfig {
        pressure_gradient: schemas::case::fluid::PressureGradient::CorrectedDifference,
        ..schemas::case::fluid::IsphConfig::default()
    }
}

/// `pressure_gradient = "symmetric"` at a support of 2.0 Δs.
fn symmetric() -> schemas::case::fluid::IsphConfig {
    schemas::case::fluid::IsphConfig {
        influence_radius: Some(2.0),
        pressure_gradient: schemas::case::fluid::PressureGradient::Symmetric,
        ..schemas::case::fluid::IsphConfig::default()
    }
}

/// `cases/dam-break-koshizuka` with ISPH (`settings`, spacing and Δt as for
/// [`koshizuka_isph_with`]): the energy gained over the steps in which it grows from t = 0.10 to
/// 0.16 s, before the surge reaches the far wall, stays below 1 % of the initial energy.
fn assert_gains_no_energy_before_the_impact(
    label: &str,
    spacing: Option<f64>,
    dt: f64,
    settings: schemas::case::fluid::IsphConfig,
) {
    let started = Instant::now();
    let (mut solver, g) = koshizuka_isph_with(spacing, dt, settings);
    let e0 = mechanical_energy(&solver, g);
    solver.advance_to(0.1).unwrap_or_else(|e| panic!("{e}"));
    let e1 = mechanical_energy(&solver, g);
    let (last, gained) = energy_gained_until(&mut solver, g, 0.16);
    println!(
        "{label}: energy {e0:.1} at t = 0, {e1:.1} at 0.10 s, {last:.1} J/kg at 0.16 s; gained {gained:.2} in the steps it grew"
    );
    let (test, method, gradient) = match label {
        "default" => (
            "isph_dam_break_gains_no_energy_before_the_impact",
            "isph",
            "the default: symmetric gradient with its exact projection at 2.0 Δs",
        ),
        "S2-8" => (
            "isph_s2_8_gradient_dam_break_gains_no_energy_before_the_impact",
            "isph-s2-8",
            "S2-8 gradient",
        ),
        "symmetric" => (
            "isph_symmetric_gradient_dam_break_gains_no_energy_before_the_impact",
            "isph-symmetric",
            "symmetric gradient at 2.0 Δs",
        ),
        _ => (
            "isph_shifting_dam_break_gains_no_energy_before_the_impact",
            "isph-shifting",
            "symmetric gradient at 2.0 Δs with Lind shifting",
        ),
    };
    let (scale, ds, suffix) = match spacing {
        Some(_) => ("l10", "L/10 = 0.0146 m (1 000 fluid)", ""),
        None => ("l20", "L/20 = 0.0073 m (8 000 fluid)", "_at_l_20"),
    };
    schemas::validation::record(schemas::validation::Record {
        id: format!("{method}-energy-before-the-impact-{scale}"),
        capability: "ISPH energy in a dam break before the impact".into(),
        reference: "energy conservation: still walls, conservative gravity (the energy may only fall)".into(),
        case: "cases/dam-break-koshizuka (the case's tank), 0.10 … 0.16 s".into(),
        resolution: format!("ISPH, {gradient}, Δs = {ds}, Δt = {dt} s"),
        measure: "energy Σ ½|u|² + g z gained over the steps in which it grew / initial energy".into(),
        value: 100.0 * gained / e0,
        bound: Some(1.0),
        bound_source: "the test's: 1 % of the initial energy".into(),
        unit: "%".into(),
        source: format!("fluid-solver/tests/isph_dam_break.rs::{test}{suffix}"),
        run_time_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    });
    assert!(
        gained < 0.01 * e0,
        "the fluid gained {gained:.2} J/kg of {e0:.1} (bound 1 %)"
    );
}

/// `cases/dam-break-koshizuka` with ISPH at time step `dt` (and particle spacing `spacing`, or
/// the case's), with the case's gravity magnitude [m/s²].
fn koshizuka_isph(spacing: Option<f64>, dt: f64) -> (fluid_solver::FluidSolver, f64) {
    koshizuka_isph_with(spacing, dt, schemas::case::fluid::IsphConfig::default())
}

/// [`koshizuka_isph`] with the ISPH settings `settings`.
fn koshizuka_isph_with(
    spacing: Option<f64>,
    dt: f64,
    settings: schemas::case::fluid::IsphConfig,
) -> (fluid_solver::FluidSolver, f64) {
    let (_, mut cfg) = common::load_case("dam-break-koshizuka");
    cfg.method = schemas::case::fluid::FluidMethodName::Isph;
    cfg.isph = Some(settings);
    cfg.sound_speed = None;
    if let Some(spacing) = spacing {
        cfg.spacing = spacing;
    }
    cfg.time_step = dt;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    (fluid_solver::FluidSolver::new(&cfg), cfg.gravity_magnitude())
}

/// The fluid's mechanical energy per unit mass summed over its particles, `Σ ½|u|² + g z` [J/kg].
fn mechanical_energy(s: &fluid_solver::FluidSolver, g: f64) -> f64 {
    let p = s.particles();
    (0..p.len())
        .filter(|&i| p.kind_of(i) == fluid_solver::Kind::Fluid)
        .map(|i| 0.5 * (p.vx[i].powi(2) + p.vy[i].powi(2) + p.vz[i].powi(2)) + g * p.z[i])
        .sum()
}

/// Steps to `t_end`; returns the energy there and the sum of its rises over the steps in which it grew.
fn energy_gained_until(solver: &mut fluid_solver::FluidSolver, g: f64, t_end: f64) -> (f64, f64) {
    let (mut last, mut gained) = (mechanical_energy(solver, g), 0.0);
    while let Some(dt) = solver.next_step_towards(t_end) {
        solver.step(dt).unwrap_or_else(|e| panic!("{e}"));
        let e = mechanical_energy(solver, g);
        gained += (e - last).max(0.0);
        last = e;
    }
    (last, gained)
}

/// Records a CI front run of this file (the slab at Δs = L/10, Δt = 1.6e-3 s) under the E-MPS
/// test's bounds.
fn record_fronts(
    e: &front_common::FrontErrors,
    method: &str,
    capability: &str,
    settings: &str,
    test: &str,
    started: Instant,
) {
    front_record::record(
        e,
        &FrontRecord {
            method,
            scale: "l10",
            capability,
            resolution: &format!(
                "{settings}, Δs = L/10 = 0.0146 m, slab 4 particles deep (800 fluid), Δt = 1.6e-3 s"
            ),
            source: &format!("fluid-solver/tests/isph_dam_break.rs::{test}"),
            bounds: [0.33, 0.05],
            bound_source: "the E-MPS test's at this resolution (dam_break.rs)",
            run_time_s: started.elapsed().as_secs_f64(),
            machine: String::new(),
        },
    );
}
