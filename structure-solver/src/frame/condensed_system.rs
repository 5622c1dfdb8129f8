//! The effective matrix of S2-14 with the internal nodes (member mid nodes) condensed out
//! (`condensation.rs`): the sparse system over the other nodes, whose factor is kept, and the
//! eliminations of the internal nodes, made with it (node by node in parallel). A solve condenses the
//! right-hand side, solves the sparse system and recovers the internal nodes: about 150 multiply-adds
//! per node, done on one thread (measured on the benchmark's 7 × 7 × 7 grid, 1 344 internal nodes:
//! elastic steps took 0.85 ms of CPU instead of 0.95 ms with rayon tasks). Members whose tangent
//! changed (a hinge formed or closed) can be re-condensed alone; the sparse system is then solved with
//! the kept factor as preconditioner (`preconditioned_cg.rs`).

use super::assembly::{SparseSystem, NODE_DOFS};
use super::condensation::{internal_nodes, Block, InternalNode, NodeFactor};
use super::preconditioned_cg::{self, Iterated};
use super::PARALLEL_CHUNK;
use rayon::prelude::*;

/// Relative difference of time steps below which a factor made for one serves the other. A window
/// split into equal steps gives steps that differ in their last bits (`t0 + span (k + 1)/n − t`); the
/// mass term `M/(βΔt²)` then differs by 2e-9 at most, far below what the stale-matrix criterion
/// allows (`factor_age.rs`, 5 %). Comparing exactly made such runs refactorise at most steps.
pub const SAME_TIME_STEP: f64 = 1e-9;

/// Whether `made` is a time step equal to `dt` up to [`SAME_TIME_STEP`].
fn same_time_step(made: Option<f64>, dt: f64) -> bool {
    made.is_some_and(|made| (dt - made).abs() <= SAME_TIME_STEP * made)
}

/// A node's 6 × 6 block (its lumped mass and rotary inertia term).
pub type NodeBlock = [[f64; NODE_DOFS]; NODE_DOFS];

/// The condensed effective system and its kept factor.
#[derive(Clone)]
pub struct CondensedSystem {
    sparse: SparseSystem,
    internal: Vec<InternalNode>,
    /// Kept elimination of each internal node (made with the sparse factor).
    factors: Vec<NodeFactor>,
    /// Where each element's matrix goes.
    placement: Vec<Placement>,
    /// The matrix last added to each sparse block (block i: internal node i's condensed block).
    blocks: Vec<Block>,
    /// Whether blocks were re-condensed since the factorisation (the factor is then a preconditioner).
    modified: bool,
    /// Whether each node is internal.
    is_internal: Vec<bool>,
    /// The time step the kept factor was made for; `None` when there is none.
    factor_time_step: Option<f64>,
    /// The time step whose mass term the assembled values hold (kept when only the factor is
    /// dropped); `None` when they must be assembled again.
    values_time_step: Option<f64>,
    /// Right-hand side and solution over the sparse system's unknowns.
    reduced: Vec<f64>,
}

/// Where an element's matrix goes.
#[derive(Clone, Copy)]
enum Placement {
    /// Into this sparse block.
    Block(usize),
    /// Into the condensed block of this internal node.
    Internal(usize),
}

impl CondensedSystem {
    /// The system of a frame whose nodes have these `fixed` DOFs, are mid or fracture nodes where
    /// `loose` (they are condensed first), and are joined by elements `element_nodes`.
    pub fn new(
        fixed: &[[bool; NODE_DOFS]],
        loose: &[bool],
        element_nodes: &[[usize; 2]],
    ) -> Result<CondensedSystem, String> {
        let internal = internal_nodes(fixed, loose, element_nodes);
        let mut is_internal = vec![false; fixed.len()];
        let mut placement = vec![None; element_nodes.len()];
        let mut block_nodes: Vec<[usize; 2]> = Vec::with_capacity(element_nodes.len());
        for (i, n) in internal.iter().enumerate() {
            is_internal[n.node] = true;
            for e in n.elements {
                placement[e] = Some(Placement::Internal(i));
            }
            block_nodes.push(n.outer);
        }
        let placement = placement
            .iter()
            .zip(element_nodes)
            .map(|(p, &pair)| {
                p.unwrap_or_else(|| {
                    block_nodes.push(pair);
                    Placement::Block(block_nodes.len() - 1)
                })
            })
            .collect();
        let sparse = SparseSystem::new(fixed.len(), fixed, &block_nodes)?;
        Ok(CondensedSystem {
            reduced: vec![0.0; sparse.unknowns()],
            sparse,
            factors: vec![NodeFactor::default(); internal.len()],
            internal,
            placement,
            blocks: vec![[[0.0; 2 * NODE_DOFS]; 2 * NODE_DOFS]; block_nodes.len()],
            modified: false,
            is_internal,
            factor_time_step: None,
            values_time_step: None,
        })
    }

    /// Whether global DOF `dof` (`6 node + k`) is an unknown (not fixed, on a node with elements).
    pub fn is_unknown(&self, dof: usize) -> bool {
        self.is_internal[dof / NODE_DOFS] || self.sparse.equation(dof).is_some()
    }

    /// Sets the matrix to the elements' matrices (`stiffness(e)`, global axes) plus the nodes' own
    /// blocks, with the internal nodes condensed out (in parallel, each node with its two elements).
    pub fn assemble(
        &mut self,
        stiffness: &(dyn Fn(usize) -> Block + Sync),
        node_blocks: &[NodeBlock],
    ) -> Result<(), String> {
        self.factor_time_step = None;
        self.values_time_step = None;
        self.modified = false;
        let count = self.internal.len();
        self.internal
            .par_iter()
            .zip(self.factors.par_iter_mut())
            .zip(self.blocks[..count].par_iter_mut())
            .with_min_len(PARALLEL_CHUNK)
            .try_for_each(|((n, factor), block)| {
                let k = n.elements.map(stiffness);
                let (f, b) = NodeFactor::new(n, [&k[0], &k[1]], &node_blocks[n.node])
                    .ok_or_else(|| not_positive_definite(&format!("at node {}", n.node)))?;
                (*factor, *block) = (f, b);
                Ok::<(), String>(())
            })?;
        for (e, placement) in self.placement.iter().enumerate() {
            if let Placement::Block(b) = *placement {
                self.blocks[b] = stiffness(e);
            }
        }
        self.sparse.clear();
        for (b, block) in self.blocks.iter().enumerate() {
            self.sparse.add_block(b, block);
        }
        for (v, block) in node_blocks.iter().enumerate() {
            if !self.is_internal[v] {
                self.sparse.add_node(v, block);
            }
        }
        Ok(())
    }

    /// `changed` elements and the other element of each internal node among their ends: the elements
    /// whose matrices [`CondensedSystem::update`] needs.
    pub fn with_partners(&self, changed: &[usize]) -> Vec<usize> {
        let mut elements: Vec<usize> = changed
            .iter()
            .flat_map(|&e| match self.placement[e] {
                Placement::Block(_) => [e, e],
                Placement::Internal(i) => self.internal[i].elements,
            })
            .collect();
        elements.sort_unstable();
        elements.dedup();
        elements
    }

    /// Replaces the matrices of `elements` (which must hold both elements of each internal node they
    /// touch, see [`CondensedSystem::with_partners`]) by `matrices`, re-condensing their internal
    /// nodes, whose own blocks are the sums of their elements' `end_blocks` (each element's lumped
    /// mass term given to each of its ends). The kept factor stays as it was: solves then iterate
    /// with it as preconditioner.
    pub fn update(
        &mut self,
        elements: &[usize],
        matrices: &[Block],
        end_blocks: &[NodeBlock],
    ) -> Result<(), String> {
        let of = |e: usize| elements.binary_search(&e).ok();
        let mut touched: Vec<usize> = Vec::new();
        for (&e, k) in elements.iter().zip(matrices) {
            match self.placement[e] {
                Placement::Block(b) => self.replace_block(b, k),
                Placement::Internal(i) => touched.push(i),
            }
        }
        touched.sort_unstable();
        touched.dedup();
        for i in touched {
            let n = &self.internal[i];
            let [Some(a), Some(b)] = n.elements.map(of) else {
                return Err(
                    "internal error: an internal node was re-condensed without both of its elements".into(),
                );
            };
            let mut own = end_blocks[a];
            for (row, add) in own.iter_mut().zip(&end_blocks[b]) {
                for (x, y) in row.iter_mut().zip(add) {
                    *x += y;
                }
            }
            let Some((factor, block)) = NodeFactor::new(n, [&matrices[a], &matrices[b]], &own) else {
                return Err(not_positive_definite(&format!("at node {}", n.node)));
            };
            self.factors[i] = factor;
            self.replace_block(i, &block);
        }
        Ok(())
    }

    /// Puts `k` in place of sparse block `b`'s last matrix.
    fn replace_block(&mut self, b: usize, k: &Block) {
        let mut change = *k;
        for (row, old) in change.iter_mut().zip(&self.blocks[b]) {
            for (x, y) in row.iter_mut().zip(old) {
                *x -= y;
            }
        }
        self.sparse.add_block(b, &change);
        self.blocks[b] = *k;
        self.modified = true;
    }

    /// Factorises the current values (as assembled, with the blocks re-condensed since) and keeps the
    /// factor; factor and values are labelled with the time step `dt` whose mass term they hold.
    pub fn factorize(&mut self, dt: f64) -> Result<(), String> {
        self.factor_time_step = None;
        self.sparse.factorize().map_err(|e| not_positive_definite(&e))?;
        self.factor_time_step = Some(dt);
        self.values_time_step = Some(dt);
        self.modified = false;
        Ok(())
    }

    /// Whether a factor made for time step `dt` is kept: one made for a step that differs from `dt`
    /// only by rounding ([`SAME_TIME_STEP`]) counts.
    pub fn has_factor_for(&self, dt: f64) -> bool {
        same_time_step(self.factor_time_step, dt)
    }

    /// Whether the values hold the mass term of time step `dt`, so that refactorising them (after
    /// re-condensing what changed) needs no new assembly.
    pub fn has_values_for(&self, dt: f64) -> bool {
        same_time_step(self.values_time_step, dt)
    }

    /// Forgets the kept factor; the values stay for a refactorisation.
    pub fn drop_factor(&mut self) {
        self.factor_time_step = None;
    }

    /// Forgets the kept factor and the values: the next factorisation assembles them anew.
    pub fn drop_values(&mut self) {
        self.factor_time_step = None;
        self.values_time_step = None;
    }

    /// Solves in place: `x` holds the right-hand side over all global DOFs (6 per node), then the
    /// solution (zero where a DOF is not an unknown). Directly with the kept factor, or, when blocks
    /// were re-condensed since, by conjugate gradients preconditioned with it in at most
    /// `max_iterations` products (the solution is then only good if the outcome says converged), down
    /// to a residual of `enough` or the relative tolerance ([`preconditioned_cg::solve`]).
    pub fn solve(&mut self, x: &mut [f64], max_iterations: usize, enough: f64) -> Result<Iterated, String> {
        if self.factor_time_step.is_none() {
            return Err("internal error: the frame's system was solved before it was factorised".into());
        }
        let parts: Vec<([f64; NODE_DOFS], [f64; 2 * NODE_DOFS])> = self
            .internal
            .iter()
            .zip(&self.factors)
            .map(|(n, f)| f.condense(&x[NODE_DOFS * n.node..NODE_DOFS * (n.node + 1)]))
            .collect();
        for (g, r) in x.iter().enumerate() {
            if let Some(eq) = self.sparse.equation(g) {
                self.reduced[eq] = *r;
            }
        }
        for (n, (_, outer)) in self.internal.iter().zip(&parts) {
            for (k, t) in outer.iter().enumerate() {
                if let Some(eq) = self
                    .sparse
                    .equation(NODE_DOFS * n.outer[k / NODE_DOFS] + k % NODE_DOFS)
                {
                    self.reduced[eq] -= t;
                }
            }
        }
        let outcome = if self.modified {
            preconditioned_cg::solve(&mut self.sparse, &mut self.reduced, max_iterations, enough)?
        } else {
            self.sparse.solve_factored(&mut self.reduced)?;
            Iterated {
                iterations: 0,
                converged: true,
            }
        };
        for (g, u) in x.iter_mut().enumerate() {
            *u = self.sparse.equation(g).map_or(0.0, |eq| self.reduced[eq]);
        }
        let recovered: Vec<[f64; NODE_DOFS]> = self
            .internal
            .iter()
            .zip(&self.factors)
            .zip(&parts)
            .map(|((n, f), (own, _))| {
                let mut outer = [0.0; 2 * NODE_DOFS];
                for (k, u) in outer.iter_mut().enumerate() {
                    *u = x[NODE_DOFS * n.outer[k / NODE_DOFS] + k % NODE_DOFS];
                }
                f.recover(own, &outer)
            })
            .collect();
        for (n, du) in self.internal.iter().zip(recovered) {
            x[NODE_DOFS * n.node..NODE_DOFS * (n.node + 1)].copy_from_slice(&du);
        }
        Ok(outcome)
    }
}

/// The error of a matrix that is not positive definite, with `detail` (where, or faer's report).
fn not_positive_definite(detail: &str) -> String {
    format!(
        "the frame's system matrix is not positive definite ({detail}): a part of the frame is free to move \
         without resistance (a mechanism or a missing support) or the state is corrupt"
    )
}
