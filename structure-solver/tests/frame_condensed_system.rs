//! Tests of `structure_solver::frame::condensed_system`.

use crate::frame_condensation::test_element_matrix;
use structure_solver::frame::assembly::NODE_DOFS;
use structure_solver::frame::condensation::Block;
use structure_solver::frame::condensed_system::*;

/// Re-condensing changed elements and solving by conjugate gradients with the old factor gives
/// the solution of a fresh factorisation of the changed matrix, to the iteration's tolerance (the
/// matrices' condition number is below 1e3: 1e-6 relative); factorising the updated values
/// without a new assembly gives it to round-off (1e-12 relative).
#[test]
fn updated_members_solve_like_a_fresh_factorisation() {
    // config nodes 0 (clamped), 1, 2, 5; mid nodes 3 (0–1), 4 (1–2), 6 (1–5) and 7 (2–5, one DOF
    // held, so its elements stay in the sparse system)
    let elements = [[0, 3], [3, 1], [1, 4], [4, 2], [1, 6], [6, 5], [2, 7], [7, 5]];
    let mut fixed = [[false; NODE_DOFS]; 8];
    fixed[0] = [true; NODE_DOFS];
    fixed[7][2] = true;
    let loose = [false, false, false, true, true, false, true, true];
    let old: Vec<Block> = (0..elements.len() as u64).map(test_element_matrix).collect();
    // each element gives each of its ends a diagonal mass block
    let end_blocks: Vec<NodeBlock> = (0..elements.len())
        .map(|e| {
            let mut b = [[0.0; NODE_DOFS]; NODE_DOFS];
            for (i, row) in b.iter_mut().enumerate() {
                row[i] = 0.5 + 0.1 * (e + i) as f64;
            }
            b
        })
        .collect();
    let mut node_blocks = vec![[[0.0; NODE_DOFS]; NODE_DOFS]; fixed.len()];
    for (pair, b) in elements.iter().zip(&end_blocks) {
        for &v in pair {
            for (row, add) in node_blocks[v].iter_mut().zip(b) {
                for (x, y) in row.iter_mut().zip(add) {
                    *x += y;
                }
            }
        }
    }
    let mut kept = CondensedSystem::new(&fixed, &loose, &elements).expect("system");
    kept.assemble(&|e| old[e], &node_blocks).expect("assembled");
    kept.factorize(1.0).expect("positive definite");

    // element 1 (of internal node 3) and element 6 (a sparse block of its own) change
    let changed = kept.with_partners(&[1, 6]);
    assert_eq!(changed, vec![0, 1, 6]);
    let mut new = old.clone();
    new[1] = test_element_matrix(101);
    new[6] = test_element_matrix(106);
    let matrices: Vec<Block> = changed.iter().map(|&e| new[e]).collect();
    let ends: Vec<NodeBlock> = changed.iter().map(|&e| end_blocks[e]).collect();
    kept.update(&changed, &matrices, &ends).expect("re-condensed");

    let mut fresh = CondensedSystem::new(&fixed, &loose, &elements).expect("system");
    fresh.assemble(&|e| new[e], &node_blocks).expect("assembled");
    fresh.factorize(1.0).expect("positive definite");

    let rhs: Vec<f64> = (0..NODE_DOFS * fixed.len())
        .map(|g| (g as f64 * 0.61).cos())
        .collect();
    let mut iterated = rhs.clone();
    let outcome = kept.solve(&mut iterated, 50, 0.0).expect("solved");
    assert!(
        outcome.converged && outcome.iterations > 1,
        "{} products",
        outcome.iterations
    );
    // a caller content with a residual of 1e-3 of the right-hand side's gets it in fewer products
    let mut coarse = rhs.clone();
    let enough = 1e-3 * rhs.iter().map(|x| x * x).sum::<f64>().sqrt();
    let coarse_outcome = kept.solve(&mut coarse, 50, enough).expect("solved");
    assert!(
        coarse_outcome.converged && coarse_outcome.iterations < outcome.iterations,
        "{} products to 1e-3, {} to the tolerance",
        coarse_outcome.iterations,
        outcome.iterations
    );
    let mut direct = rhs;
    let fresh_outcome = fresh.solve(&mut direct, 0, 0.0).expect("solved");
    assert_eq!(fresh_outcome.iterations, 0, "a fresh factor solves directly");
    let scale = direct.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let error = iterated
        .iter()
        .zip(&direct)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    println!(
        "{} products; error {:.1e} of {scale:.2e}",
        outcome.iterations, error
    );
    assert!(error < 1e-6 * scale, "error {error:e} of {scale:e}");
    // the updated values factorised as they are (no new assembly) solve like the fresh factor,
    // to round-off
    kept.drop_factor();
    assert!(kept.has_values_for(1.0) && !kept.has_factor_for(1.0));
    kept.factorize(1.0).expect("positive definite");
    let mut refactored: Vec<f64> = (0..NODE_DOFS * fixed.len())
        .map(|g| (g as f64 * 0.61).cos())
        .collect();
    let refactored_outcome = kept.solve(&mut refactored, 0, 0.0).expect("solved");
    assert_eq!(refactored_outcome.iterations, 0, "the new factor solves directly");
    let error = refactored
        .iter()
        .zip(&direct)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(error < 1e-12 * scale, "error {error:e} of {scale:e}");
    kept.drop_values();
    assert!(!kept.has_values_for(1.0));
    // and without the update the kept factor would have given a different answer
    let mut stale = CondensedSystem::new(&fixed, &loose, &elements).expect("system");
    stale.assemble(&|e| old[e], &node_blocks).expect("assembled");
    stale.factorize(1.0).expect("positive definite");
    let mut wrong: Vec<f64> = (0..NODE_DOFS * fixed.len())
        .map(|g| (g as f64 * 0.61).cos())
        .collect();
    stale.solve(&mut wrong, 0, 0.0).expect("solved");
    let difference = wrong
        .iter()
        .zip(&direct)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(difference > 1e-3 * scale);
}
