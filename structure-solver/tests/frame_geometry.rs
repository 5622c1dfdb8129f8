//! `geometry = "linear"` (first order) against `"corotational"` (the default): a cantilever under a
//! large tip load, PL²/EI = 5.

use crate::frame_common;

use frame_common::{beam, steel, support, ALL};
use schemas::case::frame::Geometry;
use schemas::validation::{record, Record};
use std::time::Instant;
use structure_solver::frame::{Equilibrium, Frame};

/// 3 m, 10 members, 0.1 × 0.1 m elastic steel (E = 200 GPa, ν = 0.3, never yielding).
const LENGTH: f64 = 3.0;
const SIDE: f64 = 0.1;
const E: f64 = 200e9;

/// Tip deflection / L of the elastica at PL²/EI = 5 (Bisshopp & Drucker 1945: 0.714; the value of
/// `frame_equilibrium.rs`, by shooting with RK4).
const ELASTICA_TIP_DEFLECTION: f64 = 0.713_79;

/// Tip displacement (x, z) of the cantilever under the tip load `p` (z), ramped over 20 quasi-static
/// iterated steps (Δt = 1 s ≫ T1) and held for 60 more (Newmark's spectral radius 0.5 per step
/// leaves 1e-18 of any transient).
fn tip_displacement(geometry: Geometry, p: f64) -> (f64, f64) {
    let mut material = steel();
    material.yield_stress = 1e15;
    let mut cfg = beam(LENGTH, 10, SIDE, SIDE, material);
    cfg.support.push(support(1, &ALL));
    cfg.geometry = geometry;
    let mut frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid test config");
    frame
        .set_equilibrium(Equilibrium::Iterate { tolerance: 1e-12 })
        .expect("tolerance");
    let tip = frame.node_index(11).expect("tip");
    let x0 = frame.node_positions();
    for n in 1..=80 {
        let mut loads = vec![0.0; 6 * frame.node_count()];
        loads[6 * tip + 2] = p * (n.min(20) as f64 / 20.0);
        frame.step(1.0, &loads).expect("static step");
    }
    let x = frame.node_positions();
    (x[3 * tip] - x0[3 * tip], x[3 * tip + 2] - x0[3 * tip + 2])
}

/// First order: the closed form PL³/3EI + PL/(κGA), κ = 5/6, however large the load (here 1.67 L),
/// and no shortening, to 1e-8 relative: one member is exact for the cantilever (`frame_static.rs`;
/// K⁻¹f here gives the closed form to 9 digits), and an iterated step counts as converged once its
/// unbalanced force is below the round-off floor 100 ε max|x| max EA/L = 8.9e-3 N
/// (`stepping::ROUND_OFF_MULTIPLE`), which over the tip stiffness 3EI/L³ = 1.85e5 N/m is
/// 4.8e-8 m = 1e-8 of the deflection (measured: 1.66e-9).
/// Co-rotational (default): the elastica within 1 % (as `frame_equilibrium.rs`: the chords of 10
/// members over a 70° arc and the shear deflection, 0.1 % here).
#[test]
fn linear_geometry_gives_the_closed_form_and_corotational_the_elastica() {
    let ei = E * SIDE.powi(4) / 12.0;
    let p = 5.0 * ei / (LENGTH * LENGTH);
    let ga = E / (2.0 * 1.3) * 5.0 / 6.0 * SIDE * SIDE;
    let closed_form = p * LENGTH.powi(3) / (3.0 * ei) + p * LENGTH / ga;
    let started = Instant::now();
    let (ux, uz) = tip_displacement(Geometry::Linear, p);
    let run_time_s = started.elapsed().as_secs_f64();
    println!(
        "linear: tip {uz:.9} m, closed form {closed_form:.9} m ({:+.2e}), ux {ux:.2e} m",
        uz / closed_form - 1.0
    );
    let cantilever = |id: &str,
                      reference: &str,
                      resolution: &str,
                      value: f64,
                      bound: f64,
                      bound_source: &str| {
        Record {
            id: format!("asi-gauss-{id}"),
            capability: "ASI-Gauss cantilever under a large tip load".into(),
            reference: reference.into(),
            case: "elastic steel cantilever 3 m, 0.1 × 0.1 m, tip load PL²/EI = 5".into(),
            resolution: resolution.into(),
            measure: "|tip deflection / reference − 1|".into(),
            value,
            bound: Some(bound),
            bound_source: bound_source.into(),
            source: "structure-solver/tests/frame_geometry.rs::linear_geometry_gives_the_closed_form_and_corotational_the_elastica"
                .into(),
            run_time_s,
            ..Default::default()
        }
    };
    record(cantilever(
        "linear-geometry-closed-form",
        "closed form PL³/3EI + PL/κGA, κ = 5/6",
        "10 members, geometry = \"linear\", 20 + 60 iterated quasi-static steps",
        (uz / closed_form - 1.0).abs(),
        1e-8,
        "one member is exact; the iterated step's round-off floor over the tip stiffness is 1e-8 of the deflection",
    ));
    assert!(
        (uz / closed_form - 1.0).abs() < 1e-8,
        "linear: {uz} m against {closed_form} m"
    );
    assert!(
        ux.abs() < 1e-9 * LENGTH,
        "linear: the tip moved {ux} m along the beam"
    );
    let started = Instant::now();
    let (ux, uz) = tip_displacement(Geometry::Corotational, p);
    let run_time_s = started.elapsed().as_secs_f64();
    println!(
        "corotational: tip {:.5} L, elastica {ELASTICA_TIP_DEFLECTION} L ({:+.2} %), ux {:.4} L",
        uz / LENGTH,
        100.0 * (uz / LENGTH / ELASTICA_TIP_DEFLECTION - 1.0),
        ux / LENGTH
    );
    record(Record {
        run_time_s,
        ..cantilever(
            "corotational-elastica",
            "elastica tip deflection 0.71379 L (Bisshopp & Drucker 1945: 0.714; shooting with RK4)",
            "10 members, geometry = \"corotational\", 20 + 60 iterated quasi-static steps",
            (uz / LENGTH / ELASTICA_TIP_DEFLECTION - 1.0).abs(),
            0.01,
            "as frame_equilibrium.rs: the chords of 10 members over a 70° arc and the shear deflection",
        )
    });
    assert!((uz / LENGTH / ELASTICA_TIP_DEFLECTION - 1.0).abs() < 0.01);
}
