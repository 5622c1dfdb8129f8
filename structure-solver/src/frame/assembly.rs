//! Sparse assembly of the (condensed) effective stiffness and its Cholesky factorisation with faer.
//! The matrix is a sum of 12 × 12 blocks joining node pairs (elements, or members whose mid node is
//! condensed out, see `condensation.rs`) and 6 × 6 node blocks. The symbolic factorisation is made
//! once per connectivity (it changes only when a member fractures); a refactorisation only scatters
//! new values into the fixed pattern and redoes the numeric part, into the kept factor's storage and
//! with a kept workspace (no allocation per step).

use super::element::ELEMENT_DOFS;
use super::supernodal_solve;
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymbolicCholeskyRaw,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side};
use std::sync::Arc;

/// Marks an entry that is not stored (a fixed DOF, or the upper triangle).
const NOT_STORED: u32 = u32::MAX;

/// Degrees of freedom per node.
pub const NODE_DOFS: usize = 6;

/// The lower triangle of the system matrix over the free DOFs, where each element and node block
/// lands in it, and the reusable symbolic factorisation.
#[derive(Clone)]
pub struct SparseSystem {
    /// Equation number of each global DOF (`6 node + k`), or `None` for fixed or unused DOFs.
    equation: Vec<Option<usize>>,
    pattern: SymbolicSparseColMat<usize>,
    symbolic: Option<Arc<SymbolicCholesky<usize>>>,
    /// Per block, the value slot of each of its 12 × 12 entries (row-major).
    block_slots: Vec<[u32; ELEMENT_DOFS * ELEMENT_DOFS]>,
    /// Per node, the value slot of each entry of its 6 × 6 diagonal block (row-major).
    node_slots: Vec<[u32; NODE_DOFS * NODE_DOFS]>,
    /// Matrix values, in the pattern's order.
    values: Vec<f64>,
    /// Values of the last numeric factor L, in the symbolic factorisation's layout.
    factor: Vec<f64>,
    /// Whether `factor` holds the factor of `values`.
    factored: bool,
    workspace: Workspace,
    /// The right-hand side in the factor's order, and room for one supernode's gathered values.
    permuted: Vec<f64>,
    gathered: Vec<f64>,
    /// Reciprocals of the supernodal factor's diagonal.
    inverse_diagonal: Vec<f64>,
}

/// Scratch memory of the numeric factorisation and the solve, kept between steps.
struct Workspace {
    requirement: StackReq,
    buffer: MemBuffer,
}

impl Workspace {
    fn new(requirement: StackReq) -> Workspace {
        Workspace {
            requirement,
            buffer: MemBuffer::new(requirement),
        }
    }
}

impl Clone for Workspace {
    /// Scratch contents are never read before being written: a clone only needs the same size.
    fn clone(&self) -> Workspace {
        Workspace::new(self.requirement)
    }
}

/// The numeric factorisation runs on one thread: a frame's factor is mostly small supernodes, and
/// with rayon's pool (2 cores) it was no faster at 11 000 DOFs (10–17 ms either way) while its
/// barriers kept the other core spinning.
const FACTORIZATION_PARALLELISM: Par = Par::Seq;
/// One right-hand side: the triangular solves are memory bound and faster on one thread.
const SOLVE_PARALLELISM: Par = Par::Seq;

impl SparseSystem {
    /// Builds the pattern for 12 × 12 blocks joining the node pairs `block_nodes`; a DOF is an
    /// unknown when its node belongs to a block and `fixed` does not hold it.
    pub fn new(
        node_count: usize,
        fixed: &[[bool; NODE_DOFS]],
        block_nodes: &[[usize; 2]],
    ) -> Result<Self, String> {
        let mut used = vec![false; node_count];
        for &[a, b] in block_nodes {
            used[a] = true;
            used[b] = true;
        }
        let mut equation = vec![None; node_count * NODE_DOFS];
        let mut n = 0;
        for node in 0..node_count {
            for k in 0..NODE_DOFS {
                if used[node] && !fixed[node][k] {
                    equation[node * NODE_DOFS + k] = Some(n);
                    n += 1;
                }
            }
        }
        let dofs = |nodes: &[usize]| -> Vec<Option<usize>> {
            nodes
                .iter()
                .flat_map(|&v| (0..NODE_DOFS).map(move |k| v * NODE_DOFS + k))
                .map(|g| equation[g])
                .collect()
        };
        let mut columns: Vec<Vec<usize>> = vec![Vec::new(); n];
        for &[a, b] in block_nodes {
            let eq = dofs(&[a, b]);
            for &c in eq.iter().flatten() {
                columns[c].extend(eq.iter().flatten().filter(|&&r| r >= c));
            }
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for col in &mut columns {
            col.sort_unstable();
            col.dedup();
            row_idx.extend_from_slice(col);
            col_ptr.push(row_idx.len());
        }
        if row_idx.len() >= NOT_STORED as usize {
            return Err(format!(
                "the frame's matrix has {} entries, more than this solver indexes",
                row_idx.len()
            ));
        }
        let pattern = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let symbolic = if n > 0 {
            let symbolic = factorize_symbolic_cholesky(
                pattern.as_ref(),
                Side::Lower,
                Default::default(),
                Default::default(),
            )
            .map_err(|e| format!("symbolic Cholesky factorisation failed: {e:?}"))?;
            Some(Arc::new(symbolic))
        } else {
            None
        };
        let workspace = Workspace::new(symbolic.as_ref().map_or(StackReq::EMPTY, |s| {
            StackReq::any_of(&[
                s.factorize_numeric_llt_scratch::<f64>(FACTORIZATION_PARALLELISM, Default::default()),
                s.solve_in_place_scratch::<f64>(1, SOLVE_PARALLELISM),
            ])
        }));
        let factor = vec![0.0; symbolic.as_ref().map_or(0, |s| s.len_val())];
        let slot = |r: Option<usize>, c: Option<usize>| -> u32 {
            match (r, c) {
                (Some(r), Some(c)) if r >= c => {
                    let start = pattern.col_ptr()[c];
                    let rows = &pattern.row_idx()[start..pattern.col_ptr()[c + 1]];
                    rows.binary_search(&r).map_or(NOT_STORED, |i| (start + i) as u32)
                }
                _ => NOT_STORED,
            }
        };
        let block_slots = block_nodes
            .iter()
            .map(|&[a, b]| {
                let eq = dofs(&[a, b]);
                let mut s = [NOT_STORED; ELEMENT_DOFS * ELEMENT_DOFS];
                for i in 0..ELEMENT_DOFS {
                    for j in 0..ELEMENT_DOFS {
                        s[i * ELEMENT_DOFS + j] = slot(eq[i], eq[j]);
                    }
                }
                s
            })
            .collect();
        let node_slots = (0..node_count)
            .map(|v| {
                let eq = dofs(&[v]);
                let mut s = [NOT_STORED; NODE_DOFS * NODE_DOFS];
                for i in 0..NODE_DOFS {
                    for j in 0..NODE_DOFS {
                        s[i * NODE_DOFS + j] = slot(eq[i], eq[j]);
                    }
                }
                s
            })
            .collect();
        let nnz = pattern.row_idx().len();
        Ok(SparseSystem {
            equation,
            pattern,
            symbolic,
            block_slots,
            node_slots,
            values: vec![0.0; nnz],
            factor,
            factored: false,
            workspace,
            permuted: vec![0.0; n],
            gathered: Vec::new(),
            inverse_diagonal: Vec::new(),
        })
    }

    /// Number of unknowns.
    pub fn unknowns(&self) -> usize {
        self.pattern.nrows()
    }

    /// Equation number of global DOF `dof`, if it is an unknown.
    pub fn equation(&self, dof: usize) -> Option<usize> {
        self.equation[dof]
    }

    /// Sets every value to zero.
    pub fn clear(&mut self) {
        self.values.iter_mut().for_each(|v| *v = 0.0);
    }

    /// Adds the 12 × 12 matrix of block `b` (only its lower-triangle entries land).
    pub fn add_block(&mut self, b: usize, k: &[[f64; ELEMENT_DOFS]; ELEMENT_DOFS]) {
        let slots = &self.block_slots[b];
        for (i, row) in k.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                let s = slots[i * ELEMENT_DOFS + j];
                if s != NOT_STORED {
                    self.values[s as usize] += v;
                }
            }
        }
    }

    /// Adds a 6 × 6 block on node `v`'s diagonal.
    pub fn add_node(&mut self, v: usize, m: &[[f64; NODE_DOFS]; NODE_DOFS]) {
        let slots = &self.node_slots[v];
        for (i, row) in m.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                let s = slots[i * NODE_DOFS + j];
                if s != NOT_STORED {
                    self.values[s as usize] += x;
                }
            }
        }
    }

    /// `y = A x`, A the symmetric matrix whose lower triangle is stored. Each column's rows are
    /// sorted and begin with its diagonal (see [`SparseSystem::new`]), which is taken first.
    pub fn multiply(&self, x: &[f64], y: &mut [f64]) {
        y.iter_mut().for_each(|v| *v = 0.0);
        let (col_ptr, row_idx) = (self.pattern.col_ptr(), self.pattern.row_idx());
        for (c, &xc) in x.iter().enumerate() {
            let (rows, values) = (
                &row_idx[col_ptr[c]..col_ptr[c + 1]],
                &self.values[col_ptr[c]..col_ptr[c + 1]],
            );
            debug_assert_eq!(rows.first(), Some(&c));
            let mut column = 0.0 + values[0] * xc;
            for (&r, &v) in rows[1..].iter().zip(&values[1..]) {
                y[r] += v * xc;
                column += v * x[r];
            }
            y[c] += column;
        }
    }

    /// Factorises the current values (numeric part only, on the kept symbolic factorisation) and keeps
    /// the factor; the error is faer's report (the matrix is not positive definite).
    pub fn factorize(&mut self) -> Result<(), String> {
        self.factored = false;
        let Some(symbolic) = &self.symbolic else {
            self.factored = true;
            return Ok(());
        };
        let matrix = SparseColMatRef::new(self.pattern.as_ref(), &self.values);
        symbolic
            .factorize_numeric_llt(
                &mut self.factor,
                matrix,
                Side::Lower,
                Default::default(),
                FACTORIZATION_PARALLELISM,
                MemStack::new(&mut self.workspace.buffer),
                Default::default(),
            )
            .map_err(|e| format!("{e:?}"))?;
        if let SymbolicCholeskyRaw::Supernodal(supernodal) = symbolic.raw() {
            supernodal_solve::inverse_diagonal(supernodal, &self.factor, &mut self.inverse_diagonal);
        }
        self.factored = true;
        Ok(())
    }

    /// Solves in place with the kept factor.
    pub fn solve_factored(&mut self, rhs: &mut [f64]) -> Result<(), String> {
        let Some(symbolic) = &self.symbolic else {
            return Ok(());
        };
        if !self.factored {
            return Err("internal error: the frame's system was solved before it was factorised".into());
        }
        match (symbolic.raw(), symbolic.perm()) {
            (SymbolicCholeskyRaw::Supernodal(supernodal), Some(perm)) => {
                let (forward, inverse) = perm.arrays();
                for (p, &f) in self.permuted.iter_mut().zip(forward) {
                    *p = rhs[f];
                }
                supernodal_solve::solve_in_place(
                    supernodal,
                    &self.factor,
                    &self.inverse_diagonal,
                    &mut self.permuted,
                    &mut self.gathered,
                );
                for (r, &i) in rhs.iter_mut().zip(inverse) {
                    *r = self.permuted[i];
                }
            }
            _ => {
                let n = rhs.len();
                LltRef::new(symbolic, &self.factor).solve_in_place_with_conj(
                    Conj::No,
                    MatMut::from_column_major_slice_mut(rhs, n, 1),
                    SOLVE_PARALLELISM,
                    MemStack::new(&mut self.workspace.buffer),
                );
            }
        }
        Ok(())
    }
}
