//! ISPH with a resolved body: a box held fixed, fully submerged in still water, feels the
//! buoyancy ρ g V within 5 % (issue 5's bound, as for E-MPS in `bodies_fixed_hydrostatic.rs`),
//! and its load and the fluid's reaction come from one pair law (action = −reaction).

use crate::bodies_common;

use bodies_common::tank_with_body;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{Aabb, FluidMethodName, IsphConfig, PressureGradient, Shifting};
use schemas::validation::{record, Record};
use std::sync::OnceLock;
use std::time::Instant;

/// The default, the exact projection of `pressure_gradient = "conservative"` at 2.0 Δs: the box
/// completes its water's kernel sums (`isph::body_completion`), which enter the projection; the
/// box at its lattice site reads ρgV (measured −0.00 %) and its water stays still (1.21e-3 m/s,
/// bound below; with the face law before, −0.09 % and 0.22 m/s at the box's bottom corner;
/// 30 Nov 2026).
#[test]
fn isph_submerged_fixed_box_feels_rho_g_v() {
    at_its_site(IsphConfig::default());
}

/// The same box held a quarter spacing (5 mm) above its lattice site, so the fluid–body gap is
/// 0.75 Δs below it and 1.25 Δs above: the load must not depend on the gap (issue 12; the
/// symmetric pair law gave 6.2 N for 9.0 N on the floating box held so). Measured −0.01 %, its
/// water at 1.4e-2 m/s at most (with the face law before, +4.81 % and 0.27 m/s; 30 Nov 2026).
#[test]
fn isph_box_load_does_not_depend_on_the_fluid_body_gap() {
    load_does_not_depend_on_the_gap(IsphConfig::default());
}

/// The symmetric gradient at a support of 2.0 Δs (`pressure_gradient = "symmetric"`): the
/// fluid's pair term with a body neighbour is the face law's share, so the load and the fluid's
/// reaction are one function; the box at its lattice site reads ρgV (measured −0.08 %).
#[test]
fn isph_symmetric_gradient_box_at_its_site_feels_rho_g_v() {
    at_its_site(symmetric());
}

/// The same box 5 mm above its site with the symmetric gradient: measured +0.86 %. (With the
/// symmetric pair term as the body's load too it read −14.7 %, −14.4 … −16.5 % in every 0.05 s
/// to 1 s: that term's zero-order part `2 p_i Σ_j V ∇W_ij` gives ρgV only with the fluid one
/// spacing from the body.)
#[test]
fn isph_symmetric_gradient_box_load_does_not_depend_on_the_fluid_body_gap() {
    load_does_not_depend_on_the_gap(symmetric());
}

/// S2-8's gradient at 2.4 Δs (`pressure_gradient = "corrected-difference"`, the seed's), the box
/// loaded by the face law: measured −0.00 % at its site, its water at 9.1e-4 m/s.
#[test]
fn isph_s2_8_gradient_box_at_its_site_feels_rho_g_v() {
    at_its_site(s2_8());
}

/// The same box 5 mm above its site with S2-8's gradient: measured +0.53 %.
#[test]
fn isph_s2_8_gradient_box_load_does_not_depend_on_the_fluid_body_gap() {
    load_does_not_depend_on_the_gap(s2_8());
}

fn s2_8() -> IsphConfig {
    IsphConfig {
        pressure_gradient: PressureGradient::CorrectedDifference,
        ..IsphConfig::default()
    }
}

/// The symmetric gradient with particle shifting (`shifting = "lind"`, the smoothest wall probe,
/// README): the water in the box's support is not shifted (`isph::shifting`); measured −0.26 %
/// (+4.05 % when it was shifted, as the rest).
#[test]
fn isph_shifting_box_at_its_site_feels_rho_g_v() {
    at_its_site(shifted());
}

/// The same 5 mm above its site: measured +0.45 % (+8.66 % when the water next to it was
/// shifted).
#[test]
fn isph_shifting_box_load_does_not_depend_on_the_fluid_body_gap() {
    load_does_not_depend_on_the_gap(shifted());
}

fn shifted() -> IsphConfig {
    IsphConfig {
        shifting: Shifting::Lind,
        ..symmetric()
    }
}

fn symmetric() -> IsphConfig {
    IsphConfig {
        influence_radius: Some(2.0),
        pressure_gradient: PressureGradient::Symmetric,
        ..IsphConfig::default()
    }
}

/// The box 5 mm (Δs/4) above its lattice site and at it: each load within 5 % of ρgV
/// ([`submerged_box_load`]), and the two within 5 % of ρgV of each other, the same bound
/// (issue 5's), since the gap must not change the load at all (each alone within 5 % would let
/// them differ by 10 %).
fn load_does_not_depend_on_the_gap(settings: IsphConfig) {
    let started = Instant::now();
    let (at_site, buoyancy) = at_its_site(settings);
    let (off_site, _) = submerged_box_load(0.005, settings);
    let difference = (off_site - at_site) / buoyancy;
    println!(
        "load 5 mm off the site − at it: {:+.2} % of ρgV",
        100.0 * difference
    );
    let (method, test) = labels(settings);
    record(Record {
        id: format!("body-{method}-submerged-box-gap-dependence"),
        capability: "ISPH load on a held, submerged box: the fluid–body gap".into(),
        reference: "the same load at any gap (Archimedes: ρgV wherever the box sits)".into(),
        case: "a 12 cm cube held 0.16 m under still water 0.3 m deep, 5 mm (Δs/4) above its lattice site against at it".into(),
        resolution: "Δs = 0.02 m (box 6 particles across), Δt = 2e-3 s".into(),
        measure: "(vertical load off the site − at it), averaged over 0.05 … 0.2 s / ρgV".into(),
        value: 100.0 * difference,
        bound: Some(5.0),
        bound_source: "issue 5's bound on the load, as for E-MPS".into(),
        unit: "%".into(),
        source: format!("fluid-solver/tests/isph_bodies.rs::{}", test[1]),
        run_time_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    });
    assert!(
        difference.abs() < 0.05,
        "the load moved by {:+.2} % of ρgV with the gap (bound 5 %)",
        100.0 * difference
    );
}

/// [`submerged_box_load`] at the lattice site, run once per setting whichever of its at-site
/// test and its gap test asks first (the other waits for it): the same scene twice cost 12 s of
/// CI.
fn at_its_site(settings: IsphConfig) -> (f64, f64) {
    static LOADS: [OnceLock<(f64, f64)>; 4] = [const { OnceLock::new() }; 4];
    let slot = match labels(settings).0 {
        "isph" => 0,
        "isph-s2-8" => 1,
        "isph-shifting" => 2,
        _ => 3,
    };
    *LOADS[slot].get_or_init(|| submerged_box_load(0.0, settings))
}

/// The record id's method tag and the (at the site, off it) tests' names of `settings`.
fn labels(settings: IsphConfig) -> (&'static str, [&'static str; 2]) {
    match (settings.pressure_gradient, settings.shifting) {
        (PressureGradient::Conservative, _) => (
            "isph",
            [
                "isph_submerged_fixed_box_feels_rho_g_v",
                "isph_box_load_does_not_depend_on_the_fluid_body_gap",
            ],
        ),
        (PressureGradient::CorrectedDifference, _) => (
            "isph-s2-8",
            [
                "isph_s2_8_gradient_box_at_its_site_feels_rho_g_v",
                "isph_s2_8_gradient_box_load_does_not_depend_on_the_fluid_body_gap",
            ],
        ),
        (_, Shifting::Lind) => (
            "isph-shifting",
            [
                "isph_shifting_box_at_its_site_feels_rho_g_v",
                "isph_shifting_box_load_does_not_depend_on_the_fluid_body_gap",
            ],
        ),
        _ => (
            "isph-symmetric",
            [
                "isph_symmetric_gradient_box_at_its_site_feels_rho_g_v",
                "isph_symmetric_gradient_box_load_does_not_depend_on_the_fluid_body_gap",
            ],
        ),
    }
}

/// The setting's name and description in the records.
fn names(settings: IsphConfig) -> (&'static str, &'static str) {
    match (settings.pressure_gradient, settings.shifting) {
        (PressureGradient::Conservative, _) => (
            "ISPH",
            "the default: symmetric gradient with its exact projection at 2.0 Δs",
        ),
        (PressureGradient::CorrectedDifference, _) => {
            ("ISPH (S2-8 gradient)", "S2-8 gradient, support 2.4 Δs")
        }
        (_, Shifting::Lind) => (
            "ISPH (symmetric gradient + shifting)",
            "symmetric gradient at 2.0 Δs with Lind shifting",
        ),
        _ => ("ISPH (symmetric gradient)", "symmetric gradient at 2.0 Δs"),
    }
}

/// Runs the scene with the box's centre `offset` above its lattice site and checks the load;
/// returns the mean vertical load and ρgV [N].
fn submerged_box_load(offset: f64, settings: IsphConfig) -> (f64, f64) {
    // The E-MPS test's scene: Δs = 0.02 m, a 12 cm box centred 0.16 m below the surface, 4
    // particles of water around it; ISPH with Δt = 2e-3 s.
    let body = Aabb {
        min: [0.08, 0.08, 0.08],
        max: [0.20, 0.20, 0.20],
    };
    let water = Aabb {
        min: [0.0; 3],
        max: [0.28, 0.28, 0.3],
    };
    let mut cfg = tank_with_body([0.28, 0.28, 0.4], 0.02, 8.0e-4, water, body);
    cfg.method = FluidMethodName::Isph;
    cfg.isph = Some(settings);
    cfg.sound_speed = None;
    cfg.time_step = 2.0e-3;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let started = Instant::now();
    let mut solver = FluidSolver::new(&cfg);
    if offset != 0.0 {
        solver
            .set_body_motion(&[0.14, 0.14, 0.14 + offset, 1.0, 0.0, 0.0, 0.0], &[0.0; 6], 0.0)
            .unwrap_or_else(|e| panic!("{e}"));
    }
    let volume: f64 = (0..3).map(|a| body.max[a] - body.min[a]).product();
    let buoyancy = cfg.density * cfg.gravity_magnitude() * volume;
    // No acoustic transient: average the loads over steps 25 … 100 (0.05 … 0.2 s).
    solver.advance_to(0.05).unwrap_or_else(|e| panic!("{e}"));
    let (mut mean, mut worst_balance, mut steps) = ([0.0; 6], 0.0f64, 0);
    let mut fastest = 0.0f64;
    while let Some(dt) = solver.next_step_towards(0.2) {
        solver.step(dt).unwrap_or_else(|e| panic!("{e}"));
        let (loads, reaction) = (solver.body_loads(), solver.body_reactions());
        for (l, r) in loads.iter().zip(&reaction) {
            worst_balance = worst_balance.max((l + r).abs());
        }
        mean.iter_mut().zip(&loads).for_each(|(m, l)| *m += l);
        steps += 1;
        let p = solver.particles();
        for i in (0..p.len()).filter(|&i| p.kind_of(i) == Kind::Fluid) {
            let v = p.velocity(i);
            fastest = fastest.max((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt());
        }
    }
    mean.iter_mut().for_each(|v| *v /= f64::from(steps));
    let error = mean[2] / buoyancy - 1.0;
    println!(
        "box {offset} m above its site, ISPH ({:?}, support {} Δs, shifting {:?}) mean load over {steps} steps: F = [{:.4}, {:.4}, {:.4}] N; ρgV = {buoyancy:.4} N; error {:+.2} %; worst |load + reaction| {worst_balance:.2e}; fastest fluid particle {fastest:.2e} m/s",
        settings.pressure_gradient, settings.support(), settings.shifting, mean[0], mean[1], mean[2], 100.0 * error
    );
    let (method, test) = labels(settings);
    let (name, settings_text) = names(settings);
    let (place, test) = match offset == 0.0 {
        true => ("at-its-site", test[0]),
        false => ("off-its-site", test[1]),
    };
    record(Record {
        id: format!("body-{method}-submerged-box-load-{place}"),
        capability: format!("{name} load on a held, submerged box"),
        reference: "buoyancy ρgV (Archimedes)".into(),
        case: match offset == 0.0 {
            true => "a 12 cm cube held 0.16 m under still water 0.3 m deep, at its lattice site".into(),
            false => format!(
                "a 12 cm cube held 0.16 m under still water 0.3 m deep, {offset} m (Δs/4) above its lattice site"
            ),
        },
        resolution: format!("ISPH, {settings_text}, Δs = 0.02 m (box 6 particles across), Δt = 2e-3 s"),
        measure: "vertical load averaged over 0.05 … 0.2 s / ρgV − 1".into(),
        value: 100.0 * error,
        bound: Some(5.0),
        bound_source: "issue 5's bound, as for E-MPS".into(),
        unit: "%".into(),
        source: format!("fluid-solver/tests/isph_bodies.rs::{test}"),
        run_time_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    });
    assert!(
        error.abs() < 0.05,
        "vertical force {} N vs ρgV = {buoyancy} N (bound 5 %)",
        mean[2]
    );
    for (a, f) in mean.iter().take(2).enumerate() {
        assert!(f.abs() < 0.02 * buoyancy, "sideways force {a}: {f}");
    }
    assert!(
        worst_balance < 1e-9 * buoyancy,
        "action = −reaction: {worst_balance}"
    );
    // The hydrostatic tank's bound (issue 12): nothing moves faster than 1e-3 √(gH), H = 0.3 m
    // the water's depth; for the box at its lattice site (the water starts in equilibrium) with
    // the exact projection, the default: measured 1.21e-3 m/s, and with S2-8's gradient 9.1e-4
    // m/s. Reported, not bounded: the box 5 mm off its site, where the water first rearranges
    // round it (2.6e-2 m/s at most over 0.05 … 0.2 s with S2-8's gradient, 1.4e-2 with the exact
    // projection; 8.9e-2 before the faces' normals at convex solids, `isph::walls`), and the
    // symmetric gradient, whose water at the box's edges moves at up to 0.2 m/s at the site and
    // 0.44 m/s off it (measured 25 Nov 2026; open, README).
    let still = 1e-3 * (cfg.gravity_magnitude() * water.max[2]).sqrt();
    let still_at_site = matches!(
        settings.pressure_gradient,
        PressureGradient::CorrectedDifference | PressureGradient::Conservative
    );
    if still_at_site && offset == 0.0 {
        assert!(
            fastest < still,
            "a fluid particle moves at {fastest:.3e} m/s beside the held box (bound {still:.3e})"
        );
    }
    (mean[2], buoyancy)
}
