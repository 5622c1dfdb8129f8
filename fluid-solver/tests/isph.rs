//! ISPH (issue 12): hydrostatics, free-surface detection, the PPE fault, the time-step check and
//! bit-identical checkpoints for both methods.

use crate::common;
use crate::isph_slab;

use fluid_solver::isph::free_surface::{self, SURFACE};
use fluid_solver::isph::kernel::Wendland;
use fluid_solver::isph::neighbour_list::NeighbourList;
use fluid_solver::isph::operators;
use fluid_solver::method::MethodState;
use fluid_solver::neighbour_search::CellGrid;
use fluid_solver::particles::Particles;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{FluidConfig, FluidMethodName, IsphConfig, PpeSolver, PressureGradient, Shifting};
use schemas::validation::{record, Record};
use std::time::Instant;

/// The hydrostatic tank at CI size with ISPH: Δs = 0.02 m, water H = 0.3 m in a 0.2 × 0.2 m
/// tank (1500 fluid particles), Δt = 2e-3 s (u Δt/Δs = 0.34, u = 2√(gH)).
fn isph_tank() -> FluidConfig {
    let (_, mut cfg) = common::load_case("hydrostatic-tank");
    cfg.method = FluidMethodName::Isph;
    cfg.isph = Some(IsphConfig::default());
    cfg.spacing = 0.02;
    cfg.tank.max = [0.2, 0.2, 0.4];
    cfg.block[0].max = [0.2, 0.2, 0.3];
    cfg.time_step = 2.0e-3;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}

/// [`isph_tank`] with `pressure_gradient = "symmetric"` at a support of 2.0 Δs.
fn isph_tank_symmetric() -> FluidConfig {
    let mut cfg = isph_tank();
    cfg.isph = Some(IsphConfig {
        influence_radius: Some(2.0),
        pressure_gradient: PressureGradient::Symmetric,
        ..IsphConfig::default()
    });
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}

/// [`isph_tank`] with S2-8's gradient (`pressure_gradient = "corrected-difference"`) at its
/// support of 2.4 Δs.
fn isph_tank_s2_8() -> FluidConfig {
    let mut cfg = isph_tank();
    cfg.isph = Some(IsphConfig {
        pressure_gradient: PressureGradient::CorrectedDifference,
        ..IsphConfig::default()
    });
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}

/// [`isph_tank_symmetric`] with `shifting = "lind"` (the default coefficient).
fn isph_tank_shifting() -> FluidConfig {
    let mut cfg = isph_tank_symmetric();
    cfg.isph = cfg.isph.map(|s| IsphConfig {
        shifting: Shifting::Lind,
        ..s
    });
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}

fn surface_flags(solver: &FluidSolver) -> &[u8] {
    match solver.method_state() {
        MethodState::Isph(s) => &s.surface,
        MethodState::Emps => panic!("not an ISPH solver"),
    }
}

/// ISPH's default settings: the exact projection at 2.0 Δs.
#[test]
fn isph_pressure_is_rho_g_h_and_the_water_stays_still() {
    tank_holds_at_0_2_s(&isph_tank());
}

/// The same with the symmetric gradient at a support of 2.0 Δs (same bounds).
#[test]
fn isph_symmetric_gradient_holds_the_tank() {
    tank_holds_at_0_2_s(&isph_tank_symmetric());
}

/// The same with S2-8's gradient at 2.4 Δs (same bounds; < 1 s).
#[test]
fn isph_s2_8_gradient_holds_the_tank() {
    tank_holds_at_0_2_s(&isph_tank_s2_8());
}

/// The same with particle shifting on the symmetric gradient at 2.0 Δs (same bounds; < 1 s).
#[test]
fn isph_shifting_holds_the_tank() {
    tank_holds_at_0_2_s(&isph_tank_shifting());
}

/// The hydrostatic tank's two validation records (pressure, stillness) for the ISPH settings of
/// `cfg` at time `t` of the 0.2 s test or (`long`) of the 1 s one, with their values and the
/// run's wall time.
fn record_tank(cfg: &FluidConfig, long: bool, t: f64, pressure: f64, fastest: f64, run_time_s: f64) {
    let settings = cfg.isph.unwrap_or_default();
    let (method, name, test) = match (settings.pressure_gradient, settings.shifting) {
        (PressureGradient::Conservative, _) => (
            "isph",
            "ISPH (default: exact projection)",
            [
                "isph_pressure_is_rho_g_h_and_the_water_stays_still",
                "isph_tank_stays_still_for_one_second",
            ],
        ),
        (PressureGradient::CorrectedDifference, _) => (
            "isph-s2-8",
            "ISPH (S2-8 gradient)",
            [
                "isph_s2_8_gradient_holds_the_tank",
                "isph_s2_8_gradient_tank_stays_still_for_one_second",
            ],
        ),
        (_, Shifting::Lind) => (
            "isph-shifting",
            "ISPH (symmetric gradient + shifting)",
            [
                "isph_shifting_holds_the_tank",
                "isph_shifting_tank_stays_still_for_one_second",
            ],
        ),
        _ => (
            "isph-symmetric",
            "ISPH (symmetric gradient)",
            [
                "isph_symmetric_gradient_holds_the_tank",
                "isph_symmetric_gradient_tank_stays_still_for_one_second",
            ],
        ),
    };
    let (tag, test) = match long {
        true => ("1s", test[1]),
        false => ("0-2s", test[0]),
    };
    let row = Record {
        case: format!("the hydrostatic tank: water 0.3 m deep in a 0.2 × 0.2 m tank, at t = {t} s"),
        resolution: format!("{name}, Δs = 0.02 m (1 500 fluid), Δt = 2e-3 s"),
        source: format!("fluid-solver/tests/isph.rs::{test}"),
        run_time_s,
        ..Default::default()
    };
    record(Record {
        id: format!("{method}-hydrostatic-pressure-{tag}"),
        capability: format!("{name} hydrostatic tank: pressure"),
        reference: "ρ g h (closed form), depth from p = 0 half a spacing above the surface particles".into(),
        measure: "worst |p / ρgh − 1| over fluid particles ≥ 3 Δs deep".into(),
        value: 100.0 * pressure,
        bound: Some(1.0),
        bound_source: "issue 12's bound".into(),
        unit: "%".into(),
        ..row.clone()
    });
    record(Record {
        id: format!("{method}-hydrostatic-still-water-{tag}"),
        capability: format!("{name} hydrostatic tank: still water"),
        reference: "water at rest (velocity 0)".into(),
        measure: "fastest fluid particle / √(gH), H = 0.3 m".into(),
        value: fastest / (cfg.gravity_magnitude() * 0.3).sqrt(),
        bound: Some(1e-3),
        bound_source: "issue 12's bound".into(),
        ..row
    });
}

fn tank_holds_at_0_2_s(cfg: &FluidConfig) {
    let cfg = cfg.clone();
    let (ds, h) = (cfg.spacing, 0.3);
    let rho_g = cfg.density * cfg.gravity_magnitude();
    let started = Instant::now();
    let mut solver = FluidSolver::new(&cfg);
    let fluid = solver.particles().count(Kind::Fluid);
    // The projection has no acoustic transient to wait for: 0.1 s (50 steps), then the floor force
    // averaged over the next 0.1 s (printed only). The same tank run for 1 s:
    // `isph_tank_stays_still_for_one_second`.
    solver.advance_to(0.1).unwrap_or_else(|e| panic!("{e}"));
    let before = solver.totals().wall_impulse[2];
    solver.advance_to(0.2).unwrap_or_else(|e| panic!("{e}"));
    let wall_force = (solver.totals().wall_impulse[2] - before) / 0.1;
    let weight = fluid as f64 * solver.particle_mass() * cfg.gravity_magnitude();
    let p = solver.particles();
    let surface = surface_flags(&solver);
    let ids: Vec<usize> = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid.code())
        .collect();
    // p = 0 holds half a spacing above the surface particles (the top of the water block):
    // depth is measured from there.
    let tops: Vec<f64> = ids
        .iter()
        .filter(|&&i| surface[i] == SURFACE)
        .map(|&i| p.z[i])
        .collect();
    let z_s = tops.iter().sum::<f64>() / tops.len() as f64 + 0.5 * ds;
    let bound = 1e-3 * (cfg.gravity_magnitude() * h).sqrt();
    let (mut fastest, mut worst): (f64, f64) = (0.0, 0.0);
    for &i in &ids {
        let v = p.velocity(i);
        fastest = fastest.max((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt());
        let depth = z_s - p.z[i];
        if depth >= 3.0 * ds {
            worst = worst.max((p.pressure[i] / (rho_g * depth) - 1.0).abs());
        }
    }
    println!(
        "{} surface particles at z = {z_s:.4} m; worst interior pressure error {:.3} %; fastest {fastest:.2e} m/s (bound {bound:.2e}); floor {wall_force:.3} N, weight {weight:.3} N",
        tops.len(),
        100.0 * worst
    );
    record_tank(&cfg, false, 0.2, worst, fastest, started.elapsed().as_secs_f64());
    assert_eq!(tops.len(), 100, "the top layer (10 × 10) is the free surface");
    // Bounds of issue 12: 1 % of ρ g h, 1e-3 √(gH); the floor carries the weight within 1 %.
    assert!(
        worst < 0.01,
        "pressure differs from rho g h by {:.3} %",
        100.0 * worst
    );
    assert!(
        fastest < bound,
        "a particle moves at {fastest} m/s (bound {bound})"
    );
}

/// The tank of `isph_pressure_is_rho_g_h_and_the_water_stays_still` for 1 s (500 steps, about
/// 5 s in release; that test is its CI twin at 0.2 s). At 2.4 Δs (refused by the case check;
/// measured by hand) the exact projection's edge columns ran away as the symmetric gradient's:
/// 4.97 % of ρgh and 0.16 m/s at 0.5 s (28 Nov 2026): the projection does not see a sliding
/// column. Bounds of issue 12: 1 % of ρgh, 1e-3 √(gH).
#[test]
#[ignore]
fn isph_tank_stays_still_for_one_second() {
    tank_stays_still_for_one_second(&isph_tank());
}

/// The same with the symmetric gradient at a support of 2.0 Δs (about 20 s in release).
#[test]
#[ignore]
fn isph_symmetric_gradient_tank_stays_still_for_one_second() {
    tank_stays_still_for_one_second(&isph_tank_symmetric());
}

/// The same with S2-8's gradient at 2.4 Δs (about 20 s in release).
#[test]
#[ignore]
fn isph_s2_8_gradient_tank_stays_still_for_one_second() {
    tank_stays_still_for_one_second(&isph_tank_s2_8());
}

/// The same with particle shifting on the symmetric gradient at 2.0 Δs (about 5 s in release).
#[test]
#[ignore]
fn isph_shifting_tank_stays_still_for_one_second() {
    tank_stays_still_for_one_second(&isph_tank_shifting());
}

fn tank_stays_still_for_one_second(cfg: &FluidConfig) {
    let cfg = cfg.clone();
    let rho_g = cfg.density * cfg.gravity_magnitude();
    let started = Instant::now();
    let mut solver = FluidSolver::new(&cfg);
    for t in [0.25, 0.5, 0.75, 1.0] {
        solver.advance_to(t).unwrap_or_else(|e| panic!("{e}"));
        let p = solver.particles();
        let surface = surface_flags(&solver);
        let ids: Vec<usize> = (0..p.len())
            .filter(|&i| p.kind[i] == Kind::Fluid.code())
            .collect();
        let tops: Vec<f64> = ids
            .iter()
            .filter(|&&i| surface[i] == SURFACE)
            .map(|&i| p.z[i])
            .collect();
        let z_s = tops.iter().sum::<f64>() / tops.len() as f64 + 0.5 * cfg.spacing;
        let (mut fastest, mut worst): (f64, f64) = (0.0, 0.0);
        for &i in &ids {
            fastest = fastest.max(p.velocity(i).iter().map(|v| v * v).sum::<f64>().sqrt());
            let depth = z_s - p.z[i];
            if depth >= 3.0 * cfg.spacing {
                worst = worst.max((p.pressure[i] / (rho_g * depth) - 1.0).abs());
            }
        }
        println!(
            "t = {t:.2} s: worst interior pressure error {:.3} %, fastest {fastest:.2e} m/s",
            100.0 * worst
        );
        record_tank(&cfg, true, t, worst, fastest, started.elapsed().as_secs_f64());
        assert!(
            worst < 0.01,
            "t = {t}: pressure differs from rho g h by {:.3} %",
            100.0 * worst
        );
        assert!(
            fastest < 1e-3 * (cfg.gravity_magnitude() * 0.3).sqrt(),
            "t = {t}: fastest {fastest} m/s"
        );
    }
}

/// Runs the detection of `isph::free_surface` on given particles (all fluid, no walls).
fn detect(p: &mut Particles, ds: f64, lo: [f64; 3], hi: [f64; 3]) -> Vec<u8> {
    let k = Wendland::new(ds, 2.4);
    let mut grid = CellGrid::new(lo, hi, ds);
    grid.sort(p, &mut Vec::new());
    let mut list = NeighbourList::default();
    list.build(&grid, p, &k);
    let (mut fill, mut takes_part, mut lambda, mut flags) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    operators::density_ratio(&k, &list, p, &mut fill);
    free_surface::fill_flags(p, &fill, &mut takes_part);
    free_surface::lambda_min(&k, &list, p, &takes_part, &mut lambda);
    free_surface::detect(&k, &list, p, &takes_part, &lambda, &mut flags);
    flags
}

/// (missed surface particles, interior particles marked, surface particles) on a lattice: a
/// particle with one of its six face neighbours missing is on the surface and must be found; a
/// particle with all 26 neighbours (faces, edges, corners) present is interior and must not be
/// marked. Particles exposed only across an edge or a corner (a sphere's staircase) may go
/// either way.
fn count_errors(p: &Particles, flags: &[u8], ds: f64) -> (usize, usize, usize) {
    // Sites in half spacings (the slab sits on half-integer sites, the sphere on integer ones).
    let key = |r: [f64; 3]| r.map(|c| (2.0 * c / ds).round() as i64);
    let sites: std::collections::HashSet<[i64; 3]> = (0..p.len()).map(|i| key(p.position(i))).collect();
    let missing =
        |s: [i64; 3], d: [i64; 3]| !sites.contains(&[s[0] + 2 * d[0], s[1] + 2 * d[1], s[2] + 2 * d[2]]);
    let (mut missed, mut false_interior, mut exposed) = (0, 0, 0);
    for (i, &flag) in flags.iter().enumerate() {
        let s = key(p.position(i));
        let offsets = (0..27i64)
            .filter(|&c| c != 13)
            .map(|c| [c % 3 - 1, (c / 3) % 3 - 1, c / 9 - 1]);
        let face_open = offsets
            .clone()
            .filter(|d| d.iter().map(|v| v.abs()).sum::<i64>() == 1)
            .any(|d| missing(s, d));
        let enclosed = !offsets.clone().any(|d| missing(s, d));
        let marked = flag == SURFACE;
        exposed += usize::from(face_open);
        missed += usize::from(face_open && !marked);
        false_interior += usize::from(enclosed && marked);
    }
    (missed, false_interior, exposed)
}

#[test]
fn free_surface_of_a_slab_and_a_sphere() {
    let ds = 0.01;
    // A slab 16 × 16 × 6 particles: every particle on its six faces is surface.
    let mut slab = Particles::default();
    for i in 0..16 {
        for j in 0..16 {
            for l in 0..6 {
                slab.push(
                    [
                        (i as f64 + 0.5) * ds,
                        (j as f64 + 0.5) * ds,
                        (l as f64 + 0.5) * ds,
                    ],
                    Kind::Fluid,
                );
            }
        }
    }
    let flags = detect(&mut slab, ds, [-0.05; 3], [0.21, 0.21, 0.11]);
    let (missed, wrong, exposed) = count_errors(&slab, &flags, ds);
    println!("slab: {exposed} surface particles, {missed} missed, {wrong} interior marked");
    assert_eq!(
        (missed, wrong),
        (0, 0),
        "slab: every surface particle found, no interior one marked"
    );
    // A sphere of radius 8 Δs on the lattice.
    let mut ball = Particles::default();
    for i in -8i32..=8 {
        for j in -8i32..=8 {
            for l in -8i32..=8 {
                if i * i + j * j + l * l <= 64 {
                    ball.push(
                        [f64::from(i) * ds, f64::from(j) * ds, f64::from(l) * ds],
                        Kind::Fluid,
                    );
                }
            }
        }
    }
    let flags = detect(&mut ball, ds, [-0.12; 3], [0.12; 3]);
    let (missed, wrong, exposed) = count_errors(&ball, &flags, ds);
    println!("sphere: {exposed} surface particles, {missed} missed, {wrong} interior marked");
    assert_eq!(
        (missed, wrong),
        (0, 0),
        "sphere: every surface particle found, no interior one marked"
    );
}

#[test]
fn a_ppe_that_misses_its_tolerance_stops_the_run_with_the_diagnostic() {
    let mut cfg = isph_tank();
    cfg.isph = Some(IsphConfig {
        ppe_tolerance: 1e-12,
        ppe_max_iterations: 2,
        ..IsphConfig::default()
    });
    let mut solver = FluidSolver::new(&cfg);
    let err = solver
        .step(cfg.time_step)
        .expect_err("two CG iterations cannot reach 1e-12");
    let text = err.to_string();
    println!("{text}");
    assert_eq!(err.step, 1);
    assert_eq!(err.quantity, "pressure Poisson equation");
    assert!(
        text.contains("residual") && text.contains("after 2 iterations"),
        "{text}"
    );
}

#[test]
fn a_time_step_beyond_the_advective_limit_is_refused() {
    let mut cfg = isph_tank();
    cfg.time_step = 5.0e-3; // u Δt/Δs = 0.86 > 0.4, u = 2√(gH) = 3.43 m/s
    let err = cfg.validate("fluid.water").expect_err("must be refused");
    let text = format!("{err:?}");
    assert!(
        text.contains("advective Courant") && text.contains("time_step ≤ 2.333e-3"),
        "{text}"
    );
}

/// Saves at step 10, runs 10 more, restores and runs the same 10 again: the particles must be
/// bit-identical.
fn continuation_is_bit_identical(cfg: &FluidConfig) {
    let mut solver = FluidSolver::new(cfg);
    for _ in 0..10 {
        solver.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
    }
    let saved = solver.save_state();
    for _ in 0..10 {
        solver.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
    }
    let first = solver.particles().clone();
    solver.restore_state(&saved);
    for _ in 0..10 {
        solver.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
    }
    assert!(
        solver.particles() == &first,
        "the continuation after restore differs"
    );
}

#[test]
fn a_restored_checkpoint_continues_bit_identically_with_either_method() {
    let (_, mut dam) = common::load_case("dam-break-koshizuka");
    dam.spacing = 0.0146;
    dam.tank.max = [0.584, 0.0584, 0.438];
    dam.block[0].max = [0.146, 0.0584, 0.292];
    dam.time_step = 6.0e-4;
    dam.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    continuation_is_bit_identical(&dam);
    dam.method = FluidMethodName::Isph;
    dam.sound_speed = None;
    dam.time_step = 1.6e-3;
    dam.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    continuation_is_bit_identical(&dam);
    dam.isph = Some(IsphConfig {
        ppe_solver: PpeSolver::FaerCholesky,
        ..IsphConfig::default()
    });
    continuation_is_bit_identical(&dam);
}

/// Free-surface detection on a dam-break snapshot (issue 12): the CI ISPH dam break
/// (`isph_dam_break.rs`: Δs = L/10, a slab 4 particles deep, 800 fluid particles) at t = 0.15 s,
/// the surge running along the floor, against a geometric truth found by brute force over 400
/// directions d (a Fibonacci sphere), every other particle (fluid, walls, dummies) counting as
/// occupied space:
/// - a fluid particle MUST be on the surface when, along some d, a ball of radius 1.5 Δs centred
///   2 Δs away (from 0.5 Δs to 3.5 Δs from it) is empty: a hole larger than a particle opens
///   within the kernel's support (2.4 Δs), as next to any flat or curved free surface;
/// - it MUST NOT be marked when, along every d, a ball of radius 0.9 Δs centred 1.5 Δs away
///   holds a particle: 0.9 Δs is just above the largest distance from a point to the nearest
///   site of a simple cubic lattice (√3/2 Δs), so a lattice-like neighbourhood fills it in every
///   direction and no gap of a particle's size lies next to it;
/// - the others (a one-particle gap, a dent) may go either way; they are counted.
///
/// Asserted: no interior particle marked, and no surface particle missed away from the solids
/// (farther than 1.5 Δs from every wall particle), both by the geometric definition above.
/// Within 1.5 Δs of a solid the detector's own rule differs from that definition by design (wall
/// particles up to about 1 Δs above the water count as wet, below), so misses there are counted
/// and printed, not bounded.
///
/// Measured: 103 surface particles, 449 interior, 248 either way; 0 interior marked; 0 missed
/// away from solids, 9 of the 61 within 1.5 Δs of a solid. The contact count moves with any
/// change of the flow, these are marginal cases: 6 of 104 (4 at a solid)
/// before the divergence was corrected as the gradient in Marrone's band
/// (`isph::operators::DivergenceSum`), 2 of 102 before the walls stopped pushing surface
/// particles before contact. With
/// S2-12's ∇λ normal, walls held back water leaving them at the free surface and the gradient
/// blind to dry walls, it missed 12 of 124 (8 within 1.5 Δs of a solid, 4 in the toe);
/// `isph::free_surface` says why it uses Marrone's normal. Where it still misses: at the
/// waterline against a side wall, whose particles up to about 1 Δs above the water still count
/// as wet (`free_surface::WET_FILL`), the normal tilts away from the wall and the umbrella's 45°
/// cone can hold the neighbour beside the particle.
#[test]
fn free_surface_of_a_dam_break_snapshot() {
    let cfg = isph_slab::isph_slab();
    let ds = cfg.spacing;
    let mut solver = FluidSolver::new(&cfg);
    solver.advance_to(0.15).unwrap_or_else(|e| panic!("{e}"));
    // The flags of the last step were found at its start: recompute them on the present
    // positions with the solver's own detector, on all particles (walls included).
    let mut p = solver.particles().clone();
    let k = Wendland::new(ds, 2.4);
    let d = solver.domain();
    let mut grid = CellGrid::new(d.lo, [d.hi[0], d.hi[1], 1.0], ds);
    grid.sort(&mut p, &mut Vec::new());
    let flags = {
        let mut list = NeighbourList::default();
        list.build(&grid, &p, &k);
        let (mut fill, mut takes_part, mut lambda, mut flags) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        operators::density_ratio(&k, &list, &p, &mut fill);
        free_surface::fill_flags(&p, &fill, &mut takes_part);
        free_surface::lambda_min(&k, &list, &p, &takes_part, &mut lambda);
        free_surface::detect(&k, &list, &p, &takes_part, &lambda, &mut flags);
        flags
    };
    let directions: Vec<[f64; 3]> = (0..400)
        .map(|k| {
            let z = 1.0 - (2.0 * f64::from(k) + 1.0) / 400.0;
            let r = (1.0 - z * z).sqrt();
            let phi = f64::from(k) * std::f64::consts::PI * (3.0 - 5f64.sqrt());
            [r * phi.cos(), r * phi.sin(), z]
        })
        .collect();
    let occupied = |i: usize, c: [f64; 3], radius: f64| {
        let mut any = false;
        grid.for_each_near_point(&p, c, radius, |j, _| any |= j != i);
        any
    };
    let (mut surface, mut interior, mut missed, mut wrong, mut either) = (0, 0, 0, 0, 0);
    let (mut contact_surface, mut contact_missed) = (0, 0);
    for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid.code()) {
        let x = p.position(i);
        let at = |d: &[f64; 3], a: f64| [x[0] + a * d[0], x[1] + a * d[1], x[2] + a * d[2]];
        let open = directions.iter().any(|d| !occupied(i, at(d, 2.0 * ds), 1.5 * ds));
        let enclosed = directions.iter().all(|d| occupied(i, at(d, 1.5 * ds), 0.9 * ds));
        let marked = flags[i] == SURFACE;
        let mut at_contact = false;
        grid.for_each_near_point(&p, x, 1.5 * ds, |j, _| {
            at_contact |= p.kind[j] != Kind::Fluid.code()
        });
        surface += usize::from(open);
        interior += usize::from(enclosed);
        either += usize::from(!open && !enclosed);
        missed += usize::from(open && !marked && !at_contact);
        if open && at_contact {
            contact_surface += 1;
            contact_missed += usize::from(!marked);
        }
        wrong += usize::from(enclosed && marked);
    }
    println!(
        "dam break at t = 0.15 s: {surface} surface particles (geometric), {missed} missed away from solids, {contact_missed} of {contact_surface} missed within 1.5 Δs of a solid; {interior} interior, {wrong} marked; {either} either way; {} marked in all",
        flags.iter().zip(&p.kind).filter(|(f, k)| **f == SURFACE && **k == Kind::Fluid.code()).count()
    );
    assert!(surface > 100 && interior > 100, "the snapshot has both");
    assert_eq!(wrong, 0, "no interior particle marked");
    assert_eq!(missed, 0, "no surface particle missed away from the solids");
}

/// A step that lands on an output, probe or coupling-window time can be as short as 1e-9 Δt.
/// The CI dam break (`isph_slab`) to t = 0.15 s, then from the same state one step of Δt and one
/// of 1e-4 Δt. Bounds: the short step changes no particle's velocity by more than twice what the
/// whole step does, and its pressures are the whole step's (RMS difference within 1 % of the
/// RMS pressure). Measured: 7.1e-2 m/s for Δt, 6.5e-2 for 1e-4 Δt (what is left is the collision
/// stage's, whose kicks do not shrink with the step); pressures RMS 1 282 Pa, difference 0.0 Pa.
/// A short step takes the pressure of a whole one (`IsphStep::short_step`); before that the
/// projection removed within the short step the divergence the last step left (about 1 1/s
/// here, `isph_divergence.rs`), and its pressures differed by an RMS 5.6 MPa, ∝ 1/Δt, which
/// outputs and probes landing on that step wrote. With S2-5's α_d/Δt² at the short step's Δt,
/// the density relaxation's velocity α_d(1 − ρ̂/ρ0)Δs/Δt grew as 1/Δt (`isph::step`, module
/// doc): the short step threw a particle to 38 m/s and the detector stopped the run.
#[test]
fn a_short_landing_step_changes_the_flow_as_little_as_a_whole_one() {
    let cfg = isph_slab::isph_slab();
    let mut solver = FluidSolver::new(&cfg);
    solver.advance_to(0.15).unwrap_or_else(|e| panic!("{e}"));
    let velocities = |s: &FluidSolver| fluid_by_id(s, |p, i| p.velocity(i));
    let pressures = |s: &FluidSolver| fluid_by_id(s, |p, i| p.pressure[i]);
    let before = velocities(&solver);
    let saved = solver.save_state();
    let change = |fraction: f64, solver: &mut FluidSolver| {
        solver.restore_state(&saved);
        solver
            .step(fraction * cfg.time_step)
            .unwrap_or_else(|e| panic!("a step of {fraction} Δt: {e}"));
        let dv = before
            .iter()
            .zip(&velocities(solver))
            .map(|(a, b)| ((0..3).map(|k| (b.1[k] - a.1[k]).powi(2)).sum::<f64>()).sqrt())
            .fold(0.0, schemas::validation::max_or_nan);
        (dv, pressures(solver))
    };
    let (whole, p_whole) = change(1.0, &mut solver);
    let (short, p_short) = change(1e-4, &mut solver);
    let rms = |v: &mut dyn Iterator<Item = f64>| {
        let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x * x, n + 1));
        (s / n.max(1) as f64).sqrt()
    };
    let p_rms = rms(&mut p_whole.iter().map(|e| e.1));
    let dp_rms = rms(&mut p_whole.iter().zip(&p_short).map(|(a, b)| b.1 - a.1));
    println!(
        "pressure: RMS {p_rms:.1} Pa after a whole step, RMS difference of the short step's {dp_rms:.1} Pa"
    );
    assert!(
        dp_rms <= 0.01 * p_rms,
        "the short step's pressures differ from a whole step's by an RMS {dp_rms:.3e} Pa (RMS pressure {p_rms:.1} Pa, bound 1 %)"
    );
    println!("largest velocity change: a step of Δt {whole:.3e} m/s, of 1e-4 Δt {short:.3e} m/s");
    assert!(
        short <= 2.0 * whole,
        "a step of 1e-4 Δt changed a velocity by {short:.3e} m/s, a whole step by {whole:.3e} (bound twice that)"
    );
}

/// `read(particles, i)` of every fluid particle with its id, in id order (the arrays are
/// reordered every step).
fn fluid_by_id<T>(
    s: &FluidSolver,
    read: impl Fn(&fluid_solver::particles::Particles, usize) -> T,
) -> Vec<(u32, T)> {
    let p = s.particles();
    let mut v: Vec<(u32, T)> = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid.code())
        .map(|i| (p.id[i], read(p, i)))
        .collect();
    v.sort_by_key(|e| e.0);
    v
}
