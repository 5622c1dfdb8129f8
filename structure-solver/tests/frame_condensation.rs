//! The condensed system (member mid nodes eliminated, `condensation.rs`) solves the same linear
//! system as the full one: in a plastic, displaced state of a small 3D frame, the static solve
//! through the condensed system agrees with a dense solve of the full tangent stiffness (nothing
//! condensed, from `dense_matrices`) to round-off.

use crate::frame_common;
use nalgebra::{DMatrix, DVector};
use structure_solver::frame::condensation::*;
use structure_solver::frame::element::ELEMENT_DOFS;

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

/// Three nodes a – m – b, elements [a, m] and [b, m] (m at the second end of both): the condensed
/// solve agrees with the dense solve of the full 18 × 18 system to round-off (1e-12 relative,
/// the matrix's condition number being about 1e2).
#[test]
fn condensed_solve_matches_the_full_system() {
    let (a, m, b) = (0, 1, 2);
    let node = InternalNode {
        node: m,
        elements: [0, 1],
        ends: [1, 1],
        outer: [a, b],
    };
    let k = [test_element_matrix(1), test_element_matrix(2)];
    let mut own = [[0.0; 6]; 6];
    for (i, row) in own.iter_mut().enumerate() {
        row[i] = 1.0 + i as f64;
    }
    // full system: the elements, the node's own block and a mass term on the outer nodes
    let mut full = DMatrix::<f64>::zeros(18, 18);
    for (pair, k) in [[a, m], [b, m]].iter().zip(&k) {
        for (i, row) in k.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                full[(6 * pair[i / 6] + i % 6, 6 * pair[j / 6] + j % 6)] += x;
            }
        }
    }
    for i in 0..6 {
        full[(6 * m + i, 6 * m + i)] += own[i][i];
        full[(6 * a + i, 6 * a + i)] += 0.5;
        full[(6 * b + i, 6 * b + i)] += 0.5;
    }
    let r = DVector::from_fn(18, |i, _| (i as f64 * 0.7).sin());
    let exact = full.clone().cholesky().expect("positive definite").solve(&r);

    let (factor, condensed) = NodeFactor::new(&node, [&k[0], &k[1]], &own).expect("positive definite");
    let mut reduced = DMatrix::<f64>::zeros(12, 12);
    for i in 0..12 {
        for j in 0..12 {
            reduced[(i, j)] = condensed[i][j];
        }
        reduced[(i, i)] += 0.5;
    }
    let (own_part, outer_part) = factor.condense(&r.as_slice()[6 * m..6 * m + 6]);
    let mut rhs = DVector::zeros(12);
    for i in 0..6 {
        rhs[i] = r[6 * a + i] - outer_part[i];
        rhs[6 + i] = r[6 * b + i] - outer_part[6 + i];
    }
    let outer = reduced.cholesky().expect("positive definite").solve(&rhs);
    let mut outer_du = [0.0; 12];
    outer_du.copy_from_slice(outer.as_slice());
    let du_m = factor.recover(&own_part, &outer_du);
    let scale = exact.amax();
    for i in 0..6 {
        assert!((outer[i] - exact[6 * a + i]).abs() < 1e-12 * scale);
        assert!((outer[6 + i] - exact[6 * b + i]).abs() < 1e-12 * scale);
        assert!((du_m[i] - exact[6 * m + i]).abs() < 1e-12 * scale, "{i}");
    }
}

/// Mid nodes are condensed before config nodes, never two neighbours, never a node with a fixed
/// DOF or with other than two elements.
#[test]
fn mid_nodes_of_a_chain_are_the_internal_ones() {
    // config nodes 0 – 1 – 2 (0 fixed in x), mid nodes 3 and 4 of members 0–1 and 1–2; node 5 hangs
    // off node 2 by one element
    let elements = [[0, 3], [3, 1], [1, 4], [4, 2], [2, 5]];
    let mut fixed = [[false; 6]; 6];
    fixed[0][0] = true;
    let loose = [false, false, false, true, true, false];
    let internal: Vec<usize> = internal_nodes(&fixed, &loose, &elements)
        .iter()
        .map(|n| n.node)
        .collect();
    assert_eq!(internal, vec![3, 4]);
    fixed[3][5] = true;
    let internal: Vec<usize> = internal_nodes(&fixed, &loose, &elements)
        .iter()
        .map(|n| n.node)
        .collect();
    // 3 is held; config node 1 has two elements but its neighbour 4 was taken first
    assert_eq!(internal, vec![4]);
}

/// A symmetric positive semi-definite 12 × 12 matrix of rank 8 from a deterministic pseudo-random
/// sequence started at `seed`, for the tests of the condensation and of the condensed system.
pub fn test_element_matrix(seed: u64) -> Block {
    let mut state = seed;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let g: Vec<[f64; 8]> = (0..ELEMENT_DOFS).map(|_| [0; 8].map(|_| next())).collect();
    let mut k = [[0.0; ELEMENT_DOFS]; ELEMENT_DOFS];
    for (i, row) in k.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = g[i].iter().zip(&g[j]).map(|(a, b)| a * b).sum();
        }
    }
    k
}
