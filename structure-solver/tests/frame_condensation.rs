//! The condensed system (member mid nodes eliminated, `condensation.rs`) solves the same linear
//! system as the full one: in a plastic, displaced state of a small 3D frame, the static solve
//! through the condensed system agrees with a dense solve of the full tangent stiffness (nothing
//! condensed, from `dense_matrices`) to round-off.

use crate::frame_common;

use frame_common::{rectangle, steel, support, ALL};
use schemas::case::frame::{FrameConfig, MemberConfig, NodeConfig};
use structure_solver::frame::Frame;

/// A 2 × 1-bay, 2-storey frame of 3 m bays; the base nodes on x = 0 are clamped, the others pinned.
fn frame() -> FrameConfig {
    let id = |i: usize, j: usize, k: usize| (k * 6 + j * 3 + i) as u32 + 1;
    let mut node = Vec::new();
    let mut member = Vec::new();
    let mut supports = Vec::new();
    for k in 0..3 {
        for j in 0..2 {
            for i in 0..3 {
                node.push(NodeConfig {
                    id: id(i, j, k),
                    position: [3.0 * i as f64, 3.0 * j as f64, 3.0 * k as f64],
                });
                if k == 0 {
                    let fixed: &[&str] = if i == 0 { &ALL } else { &ALL[..3] };
                    supports.push(support(id(i, j, k), fixed));
                }
                let mut add = |to: u32| {
                    member.push(MemberConfig {
                        nodes: [id(i, j, k), to],
                        section: "rect".into(),
                        orientation: None,
                    })
                };
                if i < 2 && k > 0 {
                    add(id(i + 1, j, k));
                }
                if j < 1 && k > 0 {
                    add(id(i, j + 1, k));
                }
                if k < 2 {
                    add(id(i, j, k + 1));
                }
            }
        }
    }
    let mut material = steel();
    material.yield_stress = 5e7;
    FrameConfig {
        time_step: 1e-3,
        gravity: [0.0, 0.0, -9.81],
        material,
        section: vec![rectangle("rect", 0.2, 0.2)],
        node,
        member,
        support: supports,
        contact: None,
        wall: Vec::new(),
        equilibrium_tolerance: None,
        damping: None,
        geometry: Default::default(),
    }
}

/// Tolerance: a backward-stable solve has a relative forward error of about κ(K) ε, whatever the
/// elimination order; the two solves may differ by twice that: the tolerance is 10 times that, 20 κ ε.
#[test]
fn condensed_static_solve_matches_the_full_dense_system() {
    let cfg = frame();
    let mut frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid test config");
    let n = frame.node_count();
    // lateral loads on the joints and vertical loads on the mid nodes (which are condensed out)
    let mut loads = vec![0.0; 6 * n];
    for v in 0..cfg.node.len() {
        loads[6 * v] = 4e4;
        loads[6 * v + 1] = 1e4;
    }
    for v in cfg.node.len()..n {
        loads[6 * v + 2] = -2e4;
        loads[6 * v + 3] = 1e3;
    }
    let mut steps = 0;
    while frame.hinge_nodes().len() < 2 && steps < 2000 {
        frame.step(frame.time_step(), &loads).expect("stable step");
        steps += 1;
    }
    let hinges = frame.hinge_nodes().len();
    assert!(
        hinges >= 2,
        "the test needs a plastic state: {hinges} hinge nodes after {steps} steps"
    );

    // K u = F + M g − R is linear in F: the difference of two condensed solves with and without a
    // probe load P is K⁻¹ P, which the dense, uncondensed K must reproduce
    let mut probe = vec![0.0; 6 * n];
    for (g, p) in probe.iter_mut().enumerate() {
        *p = 1e4 * ((g as f64) * 0.37).sin();
    }
    let with_probe = frame.linear_static_displacements(&probe).expect("static solve");
    let without = frame
        .linear_static_displacements(&vec![0.0; 6 * n])
        .expect("static solve");
    let condensed: Vec<f64> = with_probe.iter().zip(&without).map(|(a, b)| a - b).collect();

    let dense = frame.dense_matrices();
    let pick =
        |x: &[f64]| nalgebra::DVector::from_iterator(dense.dofs.len(), dense.dofs.iter().map(|&g| x[g]));
    let eigen = dense.stiffness.clone().symmetric_eigenvalues();
    let condition = eigen.amax() / eigen.iter().fold(f64::INFINITY, |m, x| m.min(x.abs()));
    let full = dense
        .stiffness
        .clone()
        .cholesky()
        .expect("the tangent stiffness is positive definite")
        .solve(&pick(&probe));
    let scale = pick(&with_probe).norm() + pick(&without).norm();
    let error = (&full - pick(&condensed)).norm() / scale;
    let tolerance = 20.0 * condition * f64::EPSILON;
    println!(
        "{hinges} hinge nodes after {steps} steps; κ(K) = {condition:.2e}; relative difference {error:.2e} \
         (|K⁻¹P| / scale = {:.2e})",
        full.norm() / scale
    );
    assert!(
        error < tolerance,
        "condensed and full solves differ by {error:e} (tolerance {tolerance:e})"
    );
    // and every DOF that is not an unknown stays zero
    let unknown: std::collections::BTreeSet<usize> = dense.dofs.iter().copied().collect();
    assert!((0..6 * n)
        .filter(|g| !unknown.contains(g))
        .all(|g| with_probe[g] == 0.0));
}
