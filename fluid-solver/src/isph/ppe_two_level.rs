//! Conjugate gradients on the PPE ([`super::ppe`]) preconditioned by a two-level method: Jacobi
//! and an exact coarse-grid correction on aggregates of neighbouring unknowns, combined either
//! additively (`ppe_solver = "additive-two-level-pcg"`, the default) or multiplicatively as a
//! V(1,1) cycle (`ppe_solver = "two-level-pcg"`).
//!
//! The method is unsmoothed (plain) aggregation as in Saad 2003, §13.2 – 13.5 (the two-grid
//! cycle and its Galerkin coarse operator) and Notay 2010 (Electron. Trans. Numer. Anal. 37,
//! "An aggregation-based algebraic multigrid method": piecewise-constant prolongation as the
//! preconditioner of a Krylov method), with geometric aggregates instead of Notay's pairwise
//! matching: the unknowns of each block of [`AGGREGATE_CELLS`]³ neighbour-search cells form one
//! aggregate ([`aggregate_by_cells`]), so an aggregate is a compact group of about
//! (c × [`AGGREGATE_CELLS`])³ particles whatever the shape of the water, c the cell edge in
//! spacings ([`super::neighbour_list::cell_edge`]: 1.2 at S2's support, 110 particles). P is the n × n_c
//! matrix with `P_iI = 1` when unknown i lies in aggregate I; the coarse matrix
//! `A_c = Pᵀ A P` (Saad 2003, eq. 13.36) is summed every step from the stored upper triangle and
//! factorised by faer's sparse Cholesky (AMD ordering, symbolic and numeric every step, sequential).
//!
//! The additive form ([`Form::Additive`]) is `M⁻¹ = D⁻¹ + P A_c⁻¹ Pᵀ`, the "AD" preconditioner
//! of Tang, Nabben, Vuik & Erlangga 2009 (J. Sci. Comput. 39, "Comparison of two-level
//! preconditioners derived from deflation, domain decomposition and multigrid methods"), i.e.
//! two-level additive Schwarz with one unknown per subdomain: `z = D⁻¹ r + P A_c⁻¹ Pᵀ r`. It is
//! symmetric positive definite as the sum of D⁻¹ (SPD) and `P A_c⁻¹ Pᵀ` (semidefinite), and costs
//! no product with A beyond CG's own. It needs about 1.8× the iterations of the cycle below
//! but a third of its products with A, and the solve is memory-bound on them: at S2's scale
//! 22.9 iterations and 94 ms per solve against 12.6 and 121 ms, through the L/20 impact 31.0
//! against 17.3 iterations and 13.9 against 18.7 ms (docs/notes/isph-ppe-preconditioner.md).
//!
//! The multiplicative form ([`Form::Multiplicative`]) is the two-grid cycle V(1,1) (Saad 2003,
//! Alg. 13.2 with one pre- and one post-smoothing step), applied to r from z = 0:
//!
//! 1. `z = ω D⁻¹ r` (pre-smoothing),
//! 2. `z += P A_c⁻¹ Pᵀ (r − A z)` (coarse correction),
//! 3. `z += ω D⁻¹ (r − A z)` (post-smoothing, the same smoother).
//!
//! Its error propagator is `E = (I − ωD⁻¹A)(I − P A_c⁻¹ Pᵀ A)(I − ωD⁻¹A)`, so `M⁻¹ = (I − E)A⁻¹`.
//! Symmetry: `(I − ωD⁻¹A)` and `(I − P A_c⁻¹ PᵀA)` are self-adjoint in the A inner product and
//! the product `S C S` of self-adjoint factors in mirrored order is self-adjoint too, so `M⁻¹` is
//! symmetric. Positive definiteness: `C` is an A-orthogonal projector (`‖C‖_A ≤ 1`) and the
//! smoother contracts in the A norm when `2D/ω − A` is positive definite, i.e. when
//! `λ_max(D⁻¹A) < 2/ω`; by Gershgorin `λ_max(D⁻¹A) ≤ 2` for the PPE (diagonal
//! `A_ii = Σ_j F_ij ≥ Σ_{j unknown} |A_ij|`), so ω = [`OMEGA`] < 1 makes `‖E‖_A < 1` and
//! `M⁻¹ = (I − E)A⁻¹` positive definite: preconditioned CG applies (Saad 2003, Alg. 9.1).
//! Each iteration costs three products with A (CG's and two in the cycle), one coarse solve and
//! the vector updates: fewer iterations than the additive form, each dearer.
//!
//! Contract as the other solvers: warm start from `x`, `|b − A x| ≤ tol |b|` or [`PpeFailure`],
//! iterations reported; every reduction is summed per fixed chunk or aggregate in a fixed order
//! and the coarse factorisation and solve are sequential, so a run is bit-reproducible whatever
//! the thread count. A coarse matrix that is not numerically positive definite (water with no
//! free-surface neighbour anywhere, where A is singular too) is solved by Jacobi-PCG instead.

use super::ppe::{dot, jacobi, pcg, PpeFailure, PpeReport, PpeSystem, CHUNK};
use crate::neighbours::neighbour_search::CellGrid;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, Mat, Par, Side};
use rayon::prelude::*;

/// Neighbour-search cells per edge of an aggregate (measured: docs/notes/isph-ppe-preconditioner.md).
pub const AGGREGATE_CELLS: usize = 4;

/// Damping ω of the multiplicative cycle's Jacobi smoother: below 1 for positive definiteness
/// (module doc).
pub const OMEGA: f64 = 2.0 / 3.0;

/// How the Jacobi part and the coarse correction are combined (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Form {
    /// `M⁻¹ = D⁻¹ + P A_c⁻¹ Pᵀ`.
    Additive,
    /// The V(1,1) cycle with damped Jacobi.
    Multiplicative,
}

/// Numbers the unknowns' aggregates: the blocks of [`AGGREGATE_CELLS`]³ cells of `grid`, in the
/// order the unknowns first meet them (the particles must be sorted by `grid`).
pub fn aggregate_by_cells(grid: &CellGrid, ppe: &mut PpeSystem) {
    let (_, _, dims) = grid.geometry();
    let k = AGGREGATE_CELLS;
    let blocks = dims.map(|d| d.div_ceil(k));
    let mut id = vec![u32::MAX; blocks[0] * blocks[1] * blocks[2]];
    let mut count = 0;
    ppe.aggregate.clear();
    for &i in &ppe.particle {
        let c = grid.cell(i as usize) as usize;
        let (x, y, z) = (c % dims[0], (c / dims[0]) % dims[1], c / (dims[0] * dims[1]));
        let b = &mut id[x / k + blocks[0] * (y / k + blocks[1] * (z / k))];
        if *b == u32::MAX {
            *b = count;
            count += 1;
        }
        ppe.aggregate.push(*b);
    }
}

/// Solves `A x = b` by CG with the two-level preconditioner of `form` (module doc), from the warm
/// start `x`; `a.aggregate` must number the unknowns' aggregates from 0 ([`aggregate_by_cells`]).
pub fn solve(
    a: &PpeSystem,
    form: Form,
    x: &mut [f64],
    tol: f64,
    max_iterations: u32,
) -> Result<PpeReport, PpeFailure> {
    assert_eq!(a.aggregate.len(), a.len(), "two-level PCG without aggregates");
    let Some(mut cycle) = Cycle::new(a, form) else {
        return a.solve(schemas::case::fluid::PpeSolver::JacobiPcg, x, tol, max_iterations);
    };
    let span = cycle.span;
    a.preconditioned_cg(span, x, tol, max_iterations, |r, z| match form {
        Form::Additive => cycle.additive(a, r, z),
        Form::Multiplicative => cycle.multiplicative(a, r, z),
    })
}

/// Solves `B x = a.rhs` for another operator B (`apply(d, out)` sets `out = B d`) by CG
/// preconditioned by the two-level method of `form` built on the matrix A of `a` (for a B
/// spectrally close to A: [`super::exact_projection`]); Jacobi on A's diagonal if A's coarse
/// matrix is not positive definite.
pub fn solve_operator(
    a: &PpeSystem,
    form: Form,
    x: &mut [f64],
    tol: f64,
    max_iterations: u32,
    apply: impl FnMut(&[f64], &mut [f64]),
) -> Result<PpeReport, PpeFailure> {
    assert_eq!(a.aggregate.len(), a.len(), "two-level PCG without aggregates");
    match Cycle::new(a, form) {
        Some(mut cycle) => pcg(&a.rhs, x, tol, max_iterations, apply, |r, z| match form {
            Form::Additive => cycle.additive(a, r, z),
            Form::Multiplicative => cycle.multiplicative(a, r, z),
        }),
        None => pcg(&a.rhs, x, tol, max_iterations, apply, jacobi(&a.diag)),
    }
}

/// The two-grid cycle of one system: aggregates, the factorised coarse matrix and scratch.
struct Cycle {
    /// Chunk length of [`PpeSystem::apply_with`].
    span: usize,
    /// `ω / A_ii` (multiplicative form) or `1 / A_ii` (additive).
    smoother: Vec<f64>,
    /// Unknowns of aggregate I: `members[first[I] .. first[I + 1]]`, ascending.
    first: Vec<usize>,
    members: Vec<u32>,
    symbolic: SymbolicCholesky<usize>,
    /// Values of the Cholesky factor of `A_c`.
    factor: Vec<f64>,
    /// Coarse right-hand side and solution.
    coarse: Mat<f64>,
    stack: MemBuffer,
    /// `A z` and the residual of the cycle.
    az: Vec<f64>,
}

impl Cycle {
    /// Sums `A_c = Pᵀ A P` and factorises it; `None` if it is not numerically positive definite.
    fn new(a: &PpeSystem, form: Form) -> Option<Cycle> {
        let n = a.len();
        let nc = a.aggregate.par_iter().max().map_or(0, |&m| m as usize + 1);
        // Members of each aggregate by a counting sort (ascending within each).
        let mut first = vec![0usize; nc + 1];
        for &g in &a.aggregate {
            first[g as usize + 1] += 1;
        }
        for g in 0..nc {
            first[g + 1] += first[g];
        }
        let mut members = vec![0u32; n];
        let mut next = first.clone();
        for (i, &g) in a.aggregate.iter().enumerate() {
            members[next[g as usize]] = i as u32;
            next[g as usize] += 1;
        }
        // Row I of the stored part: `(A_c)_II` and `U_IJ = Σ_{i∈I, j∈J, j>i} A_ij` for J ≠ I;
        // `(A_c)_IJ = U_IJ + U_JI` (A symmetric).
        // `slot[J]` is J's place in the row being summed (u32::MAX: none yet), one table per task.
        let rows: Vec<(f64, Vec<(u32, f64)>)> = (0..nc)
            .into_par_iter()
            .with_min_len(64)
            .map_init(
                || vec![u32::MAX; nc],
                |slot, g| {
                    let (mut diag, mut within, mut out) = (0.0, 0.0, Vec::<(u32, f64)>::new());
                    for &i in &members[first[g]..first[g + 1]] {
                        let i = i as usize;
                        diag += a.diag[i];
                        let (s, e) = (a.start[i] as usize, a.start[i + 1] as usize);
                        for (&c, &v) in a.col[s..e].iter().zip(&a.val[s..e]) {
                            let h = a.aggregate[c as usize];
                            let v = f64::from(v);
                            if h as usize == g {
                                within += v;
                            } else if slot[h as usize] == u32::MAX {
                                slot[h as usize] = out.len() as u32;
                                out.push((h, v));
                            } else {
                                out[slot[h as usize] as usize].1 += v;
                            }
                        }
                    }
                    out.iter().for_each(|e| slot[e.0 as usize] = u32::MAX);
                    (diag + 2.0 * within, out)
                },
            )
            .collect();
        // Lower triangle in compressed columns: column I holds the diagonal, then rows J > I.
        let mut col_ptr = vec![0usize; nc + 1];
        for (g, (_, out)) in rows.iter().enumerate() {
            col_ptr[g + 1] += 1;
            for &(h, _) in out {
                col_ptr[g.min(h as usize) + 1] += 1;
            }
        }
        for g in 0..nc {
            col_ptr[g + 1] += col_ptr[g];
        }
        let mut entries = vec![(0usize, 0.0f64); col_ptr[nc]];
        let mut next = col_ptr.clone();
        for (g, (d, _)) in rows.iter().enumerate() {
            entries[next[g]] = (g, *d);
            next[g] += 1;
        }
        for (g, (_, out)) in rows.iter().enumerate() {
            for &(h, v) in out {
                let (c, r) = (g.min(h as usize), g.max(h as usize));
                entries[next[c]] = (r, v);
                next[c] += 1;
            }
        }
        // Sort each column by row and add the pairs (U_IJ, U_JI): two terms, so the sum does not
        // depend on their order.
        let mut ptr = vec![0usize; nc + 1];
        let (mut row_idx, mut values) = (
            Vec::with_capacity(entries.len()),
            Vec::with_capacity(entries.len()),
        );
        for c in 0..nc {
            let column = &mut entries[col_ptr[c]..col_ptr[c + 1]];
            column.sort_unstable_by_key(|e| e.0);
            for &(r, v) in column.iter() {
                if row_idx.len() > ptr[c] && row_idx.last() == Some(&r) {
                    *values.last_mut()? += v;
                } else {
                    row_idx.push(r);
                    values.push(v);
                }
            }
            ptr[c + 1] = row_idx.len();
        }
        let pattern = SymbolicSparseColMatRef::new_checked(nc, nc, &ptr, None, &row_idx);
        // The factorisation is sequential: the other core takes the product's span and the
        // smoother meanwhile (about 4 ms of each at S2's scale, 1 547 coarse unknowns).
        let factorise = || {
            let symbolic =
                factorize_symbolic_cholesky(pattern, Side::Lower, SymmetricOrdering::Amd, Default::default())
                    .ok()?;
            let mut factor = vec![0.0; symbolic.len_val()];
            let mut scratch =
                MemBuffer::new(symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()));
            symbolic
                .factorize_numeric_llt(
                    &mut factor,
                    SparseColMatRef::new(pattern, &values),
                    Side::Lower,
                    Default::default(),
                    Par::Seq,
                    MemStack::new(&mut scratch),
                    Default::default(),
                )
                .ok()?;
            Some((symbolic, factor))
        };
        let side = || {
            let omega = if form == Form::Additive { 1.0 } else { OMEGA };
            (a.span(), a.diag.par_iter().map(|d| omega / d).collect())
        };
        let (factorised, (span, smoother)) = rayon::join(factorise, side);
        let (symbolic, factor) = factorised?;
        let stack = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
        Some(Cycle {
            span,
            smoother,
            first,
            members,
            symbolic,
            factor,
            coarse: Mat::zeros(nc, 1),
            stack,
            az: vec![0.0; n],
        })
    }

    /// `z = S r`, S the smoother's diagonal ([`Cycle::smoother`]).
    fn smooth(&self, r: &[f64], z: &mut [f64]) {
        z.par_iter_mut()
            .zip(r)
            .zip(&self.smoother)
            .with_min_len(CHUNK)
            .for_each(|((z, r), s)| *z = s * r);
    }

    /// `z = M⁻¹ r` of the additive form: `z = D⁻¹ r + P A_c⁻¹ Pᵀ r`; returns `r·z` (as [`dot`]).
    /// One pass writes z and sums `r·z` per chunk as [`dot`] does (so the same bits).
    fn additive(&mut self, a: &PpeSystem, r: &[f64], z: &mut [f64]) -> f64 {
        self.coarse_solve(|i| r[i]);
        let coarse = self.coarse.col(0);
        let parts: Vec<f64> = z
            .par_chunks_mut(CHUNK)
            .zip(r.par_chunks(CHUNK))
            .zip(self.smoother.par_chunks(CHUNK).zip(a.aggregate.par_chunks(CHUNK)))
            .map(|((z, r), (s, g))| {
                let mut rz = 0.0;
                for (((z, r), s), &g) in z.iter_mut().zip(r).zip(s).zip(g) {
                    *z = s * r + coarse[g as usize];
                    rz += r * *z;
                }
                rz
            })
            .collect();
        parts.iter().sum()
    }

    /// `z = M⁻¹ r` by the V(1,1) cycle of the module doc; returns `r·z` (as [`dot`]).
    fn multiplicative(&mut self, a: &PpeSystem, r: &[f64], z: &mut [f64]) -> f64 {
        self.smooth(r, z);
        a.apply_with(self.span, z, &mut self.az);
        let az = std::mem::take(&mut self.az);
        self.coarse_solve(|i| r[i] - az[i]);
        self.az = az;
        let coarse = self.coarse.col(0);
        z.par_iter_mut()
            .zip(&a.aggregate)
            .with_min_len(CHUNK)
            .for_each(|(z, &g)| *z += coarse[g as usize]);
        a.apply_with(self.span, z, &mut self.az);
        z.par_iter_mut()
            .zip(r)
            .zip(self.az.par_iter().zip(&self.smoother))
            .with_min_len(CHUNK)
            .for_each(|((z, r), (az, s))| *z += s * (r - az));
        dot(r, z)
    }

    /// `A_c⁻¹ Pᵀ e` into [`Cycle::coarse`] for the fine vector `e(i)`: restricted aggregate by
    /// aggregate in member order, solved with the factor (the caller prolongates: `P` adds
    /// `coarse[aggregate[i]]` to unknown i).
    fn coarse_solve(&mut self, e: impl Fn(usize) -> f64 + Sync) {
        let restricted: Vec<f64> = (0..self.first.len() - 1)
            .into_par_iter()
            .map(|g| {
                self.members[self.first[g]..self.first[g + 1]]
                    .iter()
                    .map(|&i| e(i as usize))
                    .sum()
            })
            .collect();
        restricted
            .iter()
            .enumerate()
            .for_each(|(g, v)| self.coarse[(g, 0)] = *v);
        LltRef::new(&self.symbolic, &self.factor).solve_in_place_with_conj(
            Conj::No,
            self.coarse.as_mut(),
            Par::Seq,
            MemStack::new(&mut self.stack),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::isph::ppe::tests::{block_aggregates, distance, laplacian};
    use schemas::case::fluid::PpeSolver;

    /// The 7-point Laplacian of an m³ grid as the PPE of a tank: Neumann (no flux) on the bottom
    /// and the four sides, Dirichlet (p = 0 beyond) only on the top face, so the smallest
    /// eigenvalue is about m⁻² of the largest, as in a tank whose free surface is its top.
    fn open_top(m: usize) -> PpeSystem {
        let mut s = laplacian(m);
        for (i, d) in s.diag.iter_mut().enumerate() {
            let (x, y, z) = (i % m, (i / m) % m, i / (m * m));
            let inside = |c: usize| usize::from(c > 0) + usize::from(c + 1 < m);
            *d = (inside(x) + inside(y) + inside(z)) as f64 + if z + 1 == m { 1.0 } else { 0.0 };
        }
        s
    }

    /// (iterations, solution) of `solver` from x = 0 to `tol`.
    fn solved(a: &PpeSystem, solver: PpeSolver, tol: f64) -> (u32, Vec<f64>) {
        let mut x = vec![0.0; a.len()];
        let report = a.solve(solver, &mut x, tol, 5000).unwrap();
        assert!(
            report.residual <= tol && a.relative_residual(&x) <= 1.01 * tol,
            "{solver:?}: {report:?}"
        );
        (report.iterations, x)
    }

    /// Both forms of the two-level solver.
    const FORMS: [PpeSolver; 2] = [PpeSolver::TwoLevelPcg, PpeSolver::AdditiveTwoLevelPcg];

    #[test]
    fn two_level_iterations_grow_slower_than_jacobi_and_it_agrees_with_cholesky() {
        let tol = 1e-8;
        for solver in FORMS {
            let mut counts = Vec::new();
            for m in [12, 24] {
                let mut a = open_top(m);
                a.aggregate = block_aggregates(m, AGGREGATE_CELLS);
                let (jacobi, _) = solved(&a, PpeSolver::JacobiPcg, tol);
                let (two_level, x) = solved(&a, solver, tol);
                let (_, reference) = solved(&a, PpeSolver::FaerCholesky, tol);
                // |x − x*| ≤ κ(A) tol |x*| with κ(A) ≤ 12/λ_min, λ_min ≥ 2(1 − cos(π/(2m+1)))
                // (the 1D Dirichlet–Neumann chain along z): 1.2e3 at m = 24.
                let kappa = 12.0 / (2.0 * (1.0 - (std::f64::consts::PI / (2 * m + 1) as f64).cos()));
                let norm = reference.iter().map(|v| v * v).sum::<f64>().sqrt();
                let err = distance(&x, &reference);
                assert!(err <= kappa * tol * norm, "{solver:?}, m = {m}: error {err:e}");
                println!("m = {m}: Jacobi-PCG {jacobi} iterations, {solver:?} {two_level}");
                counts.push((jacobi, two_level));
            }
            let (small, large) = (counts[0], counts[1]);
            assert!(large.1 < large.0, "{solver:?}: {counts:?}");
            // Jacobi's count grows as √κ ∝ m; the two-level one's must grow by a smaller factor.
            assert!(
                f64::from(large.1) / f64::from(small.1) < f64::from(large.0) / f64::from(small.0),
                "{solver:?}: {counts:?}"
            );
        }
    }

    #[test]
    fn two_level_is_independent_of_the_thread_count_and_warm_starts() {
        let m = 20;
        let mut a = open_top(m);
        a.aggregate = block_aggregates(m, AGGREGATE_CELLS);
        for solver in FORMS {
            let run = |threads| {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                pool.install(|| solved(&a, solver, 1e-6))
            };
            let (one, two) = (run(1), run(2));
            assert_eq!(one.0, two.0);
            assert!(one.1.iter().zip(&two.1).all(|(a, b)| a.to_bits() == b.to_bits()));
            // From the solution it stops at once; from a solution 1e-3 off, in fewer iterations
            // than from 0.
            let mut x = one.1.clone();
            assert_eq!(a.solve(solver, &mut x, 1e-6, 100).unwrap().iterations, 0);
            let mut x: Vec<f64> = one
                .1
                .iter()
                .enumerate()
                .map(|(i, v)| v * (1.0 + 1e-3 * (i as f64).sin()))
                .collect();
            let warm = a.solve(solver, &mut x, 1e-6, 100).unwrap();
            assert!(
                warm.iterations < one.0,
                "{solver:?}: {warm:?} against {} from 0",
                one.0
            );
        }
    }
}
