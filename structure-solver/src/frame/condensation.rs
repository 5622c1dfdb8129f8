//! Exact static condensation of internal nodes (member mid nodes) out of the effective matrix of
//! S2-14, node by node. A node is internal when it belongs to exactly two elements that join it to two
//! other distinct nodes (its outer nodes, e), none of which is internal, and none of its DOFs is fixed.
//! Ordering the two elements' matrix A (plus the node's own lumped-mass block) as (m, e),
//! `[A_mm A_me; A_em A_ee] [Δu_m; Δu_e] = [r_m; r_e]` gives, A being symmetric and with
//! `X = A_mm⁻¹ A_me`,
//!
//! - for the outer nodes: `(A_ee − A_meᵀ X) Δu_e = r_e − Xᵀ r_m` (a 12 × 12 block joining them),
//! - for the node itself: `Δu_m = A_mm⁻¹ r_m − X Δu_e`.
//!
//! This is Gaussian elimination of the node's 6 unknowns, so the condensed system has the same
//! solution as the full one up to round-off.

use super::assembly::NODE_DOFS;
use super::element::ELEMENT_DOFS;

/// A node condensed out of the global system.
#[derive(Debug, Clone)]
pub struct InternalNode {
    /// The node's index.
    pub node: usize,
    /// Its two elements.
    pub elements: [usize; 2],
    /// Its position (0 or 1) in each of them.
    pub ends: [usize; 2],
    /// The other ends of the two elements.
    pub outer: [usize; 2],
}

/// The internal nodes of a frame with these fixed DOFs and elements. Mid and fracture nodes (`loose`)
/// are taken before config nodes, so that in a chain of members the mid nodes are the ones condensed.
pub fn internal_nodes(
    fixed: &[[bool; NODE_DOFS]],
    loose: &[bool],
    element_nodes: &[[usize; 2]],
) -> Vec<InternalNode> {
    let mut touching: Vec<Vec<(usize, usize)>> = vec![Vec::new(); fixed.len()];
    for (e, pair) in element_nodes.iter().enumerate() {
        for (end, &v) in pair.iter().enumerate() {
            touching[v].push((e, end));
        }
    }
    let mut taken = vec![false; fixed.len()];
    let mut internal = Vec::new();
    let candidates = (0..fixed.len())
        .filter(|&v| loose[v])
        .chain((0..fixed.len()).filter(|&v| !loose[v]));
    for v in candidates {
        let [(e0, end0), (e1, end1)] = touching[v][..] else {
            continue;
        };
        let outer = [element_nodes[e0][1 - end0], element_nodes[e1][1 - end1]];
        let free = !fixed[v].iter().any(|&f| f);
        let neighbours_outer = !taken[outer[0]] && !taken[outer[1]];
        if free && neighbours_outer && outer[0] != outer[1] && !outer.contains(&v) {
            taken[v] = true;
            internal.push(InternalNode {
                node: v,
                elements: [e0, e1],
                ends: [end0, end1],
                outer,
            });
        }
    }
    internal
}

/// The kept elimination of one internal node: `A_mm⁻¹` and `X = A_mm⁻¹ A_me` (6 × 12, columns over
/// the first outer node's DOFs, then the second's).
#[derive(Debug, Clone, Default)]
pub struct NodeFactor {
    inverse: [[f64; NODE_DOFS]; NODE_DOFS],
    coupling: [[f64; ELEMENT_DOFS]; NODE_DOFS],
}

/// A 12 × 12 matrix block.
pub type Block = [[f64; ELEMENT_DOFS]; ELEMENT_DOFS];

impl NodeFactor {
    /// Eliminates `node` given its two elements' matrices (global axes, in `node.elements` order) and
    /// its own 6 × 6 block; returns the factor and the condensed block `A_ee − A_meᵀ X` over the outer
    /// nodes, or `None` when `A_mm` is not positive definite.
    pub fn new(
        node: &InternalNode,
        matrices: [&Block; 2],
        own: &[[f64; 6]; 6],
    ) -> Option<(NodeFactor, Block)> {
        let mut a_mm = *own;
        let mut a_me = [[0.0; ELEMENT_DOFS]; NODE_DOFS];
        let mut a_ee = [[0.0; ELEMENT_DOFS]; ELEMENT_DOFS];
        for (t, (k, &end)) in matrices.iter().zip(&node.ends).enumerate() {
            let (m, o) = (NODE_DOFS * end, NODE_DOFS * (1 - end));
            for i in 0..NODE_DOFS {
                for j in 0..NODE_DOFS {
                    a_mm[i][j] += k[m + i][m + j];
                    a_me[i][NODE_DOFS * t + j] = k[m + i][o + j];
                    a_ee[NODE_DOFS * t + i][NODE_DOFS * t + j] = k[o + i][o + j];
                }
            }
        }
        let inverse = inverse_spd(&a_mm)?;
        let mut coupling = [[0.0; ELEMENT_DOFS]; NODE_DOFS];
        for (row, inv) in coupling.iter_mut().zip(&inverse) {
            for (&v, a_row) in inv.iter().zip(&a_me) {
                for (x, a) in row.iter_mut().zip(a_row) {
                    *x += v * a;
                }
            }
        }
        // A_ee − A_meᵀ X, accumulated over the node's DOFs k (rows of A_me and X)
        let mut condensed = a_ee;
        for (a_row, x_row) in a_me.iter().zip(&coupling) {
            for (s_row, &a) in condensed.iter_mut().zip(a_row) {
                for (s, x) in s_row.iter_mut().zip(x_row) {
                    *s -= a * x;
                }
            }
        }
        Some((NodeFactor { inverse, coupling }, condensed))
    }

    /// The node's part of the right-hand side `r_m`: returns `A_mm⁻¹ r_m` (kept for the recovery)
    /// and `Xᵀ r_m`, which the outer nodes' right-hand side loses.
    pub fn condense(&self, r_m: &[f64]) -> ([f64; NODE_DOFS], [f64; ELEMENT_DOFS]) {
        let mut own = [0.0; NODE_DOFS];
        for (y, row) in own.iter_mut().zip(&self.inverse) {
            *y = row.iter().zip(r_m).map(|(a, r)| a * r).sum();
        }
        let mut outer = [0.0; ELEMENT_DOFS];
        for (row, r) in self.coupling.iter().zip(r_m) {
            for (t, x) in outer.iter_mut().zip(row) {
                *t += x * r;
            }
        }
        (own, outer)
    }

    /// The node's increment `A_mm⁻¹ r_m − X Δu_e` from `own = A_mm⁻¹ r_m` and the outer nodes'
    /// increments `outer` (12).
    pub fn recover(&self, own: &[f64; NODE_DOFS], outer: &[f64; ELEMENT_DOFS]) -> [f64; NODE_DOFS] {
        let mut du = *own;
        for (d, row) in du.iter_mut().zip(&self.coupling) {
            *d -= row.iter().zip(outer).map(|(x, u)| x * u).sum::<f64>();
        }
        du
    }
}

/// Inverse of a symmetric positive definite 6 × 6 matrix through its Cholesky factor L
/// (`A⁻¹ = L⁻ᵀ L⁻¹`); `None` when a pivot is not positive.
fn inverse_spd(a: &[[f64; 6]; 6]) -> Option<[[f64; 6]; 6]> {
    let mut l = [[0.0; 6]; 6];
    for j in 0..6 {
        let pivot = a[j][j] - (0..j).map(|k| l[j][k] * l[j][k]).sum::<f64>();
        if pivot.is_nan() || pivot <= 0.0 {
            return None;
        }
        l[j][j] = pivot.sqrt();
        for i in j + 1..6 {
            l[i][j] = (a[i][j] - (0..j).map(|k| l[i][k] * l[j][k]).sum::<f64>()) / l[j][j];
        }
    }
    // W = L⁻¹, lower triangular
    let mut w = [[0.0; 6]; 6];
    for j in 0..6 {
        w[j][j] = 1.0 / l[j][j];
        for i in j + 1..6 {
            w[i][j] = -(j..i).map(|k| l[i][k] * w[k][j]).sum::<f64>() / l[i][i];
        }
    }
    let mut inverse = [[0.0; 6]; 6];
    for (i, row) in inverse.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = (i.max(j)..6).map(|k| w[k][i] * w[k][j]).sum();
        }
    }
    Some(inverse)
}
