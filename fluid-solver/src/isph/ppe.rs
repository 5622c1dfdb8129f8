//! The pressure Poisson equation of the projection (S2-5), assembled on the neighbour list and
//! solved every step.
//!
//! With S2-9's Laplacian `⟨∇²p⟩_i = Σ_j F_ij (p_j − p_i)`, `F_ij = −2 V W'(r)/r ≥ 0`, the rows of
//! the fluid particles that are not on the free surface form `A p = b` with
//! `A_ii = Σ_{fluid j} F_ij`, `A_ij = −F_ij` (j another unknown), surface neighbours entering as
//! p = 0 (Dirichlet) and wall neighbours as known pressure differences (Neumann, see
//! [`super::walls`]), which the step puts into b. A is symmetric (equal volumes) and, with at
//! least one surface neighbour per connected body of water, positive definite: conjugate
//! gradients apply. A pocket of water enclosed by solids has none; after a failed solve the step
//! finds such pockets ([`PpeSystem::enclosed_pockets`]) and ties their level ([`PpeSystem::tie`]).
//!
//! The solve is memory-bound (about 55 entries per row against a few vector values), so only the
//! strict upper triangle is stored, in f32: 4 bytes of value and 4 of column per pair of
//! unknowns instead of 2 × 12. The product `A x` ([`PpeSystem::apply`]) reads each stored entry
//! once for both of its rows, in two phases over chunks at least the matrix's bandwidth long
//! (the unknowns are in cell order, so a row's columns lie within a few layers of cells): the
//! even chunks in parallel, then the odd ones, each writing only its own and the next chunk.
//!
//! Four solvers ([`schemas::case::fluid::PpeSolver`]): a Jacobi-preconditioned CG over the rows
//! in rayon, warm-started from the last step's pressure (its dot products summed in fixed chunks,
//! so a run is bit-reproducible); the same CG preconditioned by symmetric Gauss–Seidel within
//! fixed blocks of [`CHUNK`] rows (block Jacobi between blocks, so the blocks run in parallel and
//! the result does not depend on the thread count); faer's sparse Cholesky factorisation of
//! A; and CG with a two-level (aggregation) preconditioner, in [`super::ppe_two_level`]. All must
//! reach `|b − A p| ≤ tol |b|`, else the step fails with [`PpeFailure`].

use super::ppe_two_level::Form;
use rayon::prelude::*;
use schemas::case::fluid::PpeSolver;

/// Row of a particle that is not an unknown.
pub const NOT_AN_UNKNOWN: u32 = u32::MAX;

/// Fixed chunk of the reductions (independent of the thread count, for reproducible sums).
pub(super) const CHUNK: usize = 4096;

/// The assembled system `A p = b` over the unknowns.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PpeSystem {
    /// Particle index of each unknown.
    pub particle: Vec<u32>,
    /// Unknown number of each particle, or [`NOT_AN_UNKNOWN`].
    pub row_of: Vec<u32>,
    /// Strict upper triangle (columns > r) of row r: `col[start[r] .. start[r + 1]]`, values
    /// `−F` in `val`, in f32 (module doc); the diagonal, right-hand side and vectors are f64.
    pub start: Vec<u32>,
    pub col: Vec<u32>,
    pub val: Vec<f32>,
    pub diag: Vec<f64>,
    pub rhs: Vec<f64>,
    /// Aggregate of each unknown for [`super::ppe_two_level`] (filled only for that solver).
    pub aggregate: Vec<u32>,
    /// Whether each row has a Dirichlet neighbour (a surface particle): a connected set of rows
    /// with none is a pocket of water enclosed by solids ([`PpeSystem::enclosed_pockets`]).
    pub anchored: Vec<bool>,
}

/// A PPE that did not reach its tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PpeFailure {
    pub iterations: u32,
    /// `|b − A p| / |b|` at the stop.
    pub residual: f64,
    pub unknowns: usize,
}

/// How a solve went.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PpeReport {
    pub iterations: u32,
    pub residual: f64,
    pub unknowns: usize,
}

impl PpeSystem {
    /// Number of unknowns.
    pub fn len(&self) -> usize {
        self.particle.len()
    }

    /// True without unknowns.
    pub fn is_empty(&self) -> bool {
        self.particle.is_empty()
    }

    /// `out = A x` from the upper triangle (module doc): for each row r of a chunk,
    /// `out_r += A_rr x_r + Σ_{c>r} A_rc x_c` and `out_c += A_rc x_r`, the even chunks in parallel
    /// and then the odd ones. Each task writes only its chunk and the next (`span` is at least the
    /// bandwidth, [`PpeSystem::span`]), and every sum is taken in a fixed order, so the result
    /// does not depend on the thread count.
    pub fn apply(&self, x: &[f64], out: &mut [f64]) {
        self.apply_with(self.span(), x, out);
    }

    /// [`PpeSystem::apply`] with the chunk length `span`.
    pub(super) fn apply_with(&self, span: usize, x: &[f64], out: &mut [f64]) {
        let n = self.len();
        for phase in 0..2 {
            let offset = phase * span;
            if offset >= n {
                break;
            }
            out[offset..]
                .par_chunks_mut(2 * span)
                .enumerate()
                .for_each(|(m, o)| {
                    if phase == 0 {
                        o.iter_mut().for_each(|v| *v = 0.0);
                    }
                    let base = offset + 2 * m * span;
                    for r in base..(base + span).min(n) {
                        let xr = x[r];
                        let mut sum = self.diag[r] * xr;
                        let (s, e) = (self.start[r] as usize, self.start[r + 1] as usize);
                        for (&c, &v) in self.col[s..e].iter().zip(&self.val[s..e]) {
                            let (c, v) = (c as usize, f64::from(v));
                            sum += v * x[c];
                            o[c - base] += v * xr;
                        }
                        o[r - base] += sum;
                    }
                });
        }
    }

    /// The chunk length of [`PpeSystem::apply`]: the bandwidth `max (c − r)` rounded up to a
    /// multiple of [`CHUNK`] (at least one).
    pub(super) fn span(&self) -> usize {
        let band = (0..self.len())
            .into_par_iter()
            .with_min_len(CHUNK)
            .map(|r| {
                let (s, e) = (self.start[r] as usize, self.start[r + 1] as usize);
                self.col[s..e].iter().map(|&c| c as usize - r).max().unwrap_or(0)
            })
            .max()
            .unwrap_or(0);
        (band + 1).div_ceil(CHUNK) * CHUNK
    }

    /// Solves with `solver`, starting from `x` (the warm start); `x` holds the solution.
    pub fn solve(
        &self,
        solver: PpeSolver,
        x: &mut [f64],
        tol: f64,
        max_iterations: u32,
    ) -> Result<PpeReport, PpeFailure> {
        match solver {
            PpeSolver::JacobiPcg => self.jacobi_pcg(x, tol, max_iterations),
            PpeSolver::FaerCholesky => self.faer_cholesky(x, tol),
            PpeSolver::SgsPcg => self.sgs_pcg(x, tol, max_iterations),
            PpeSolver::TwoLevelPcg => {
                super::ppe_two_level::solve(self, Form::Multiplicative, x, tol, max_iterations)
            }
            PpeSolver::AdditiveTwoLevelPcg => {
                super::ppe_two_level::solve(self, Form::Additive, x, tol, max_iterations)
            }
        }
    }

    /// One row (the lowest) of each pocket: a set of unknowns connected through A's entries none
    /// of which has a Dirichlet neighbour. A pocket's rows sum to zero (water enclosed by walls
    /// and bodies: a pure Neumann problem), so A is singular there and CG diverges unless b sums
    /// to zero over it. Union–find over the stored entries, run only after a failed solve.
    pub fn enclosed_pockets(&self) -> Vec<usize> {
        let n = self.len();
        let mut parent: Vec<usize> = (0..n).collect();
        fn root(parent: &mut [usize], mut r: usize) -> usize {
            while parent[r] != r {
                parent[r] = parent[parent[r]];
                r = parent[r];
            }
            r
        }
        for r in 0..n {
            for &c in &self.col[self.start[r] as usize..self.start[r + 1] as usize] {
                let (a, b) = (root(&mut parent, r), root(&mut parent, c as usize));
                // the lower row becomes the root, so a pocket is named by its lowest row
                parent[a.max(b)] = a.min(b);
            }
        }
        let mut anchored = vec![false; n];
        for r in 0..n {
            let top = root(&mut parent, r);
            anchored[top] |= self.anchored.get(r).copied().unwrap_or(true);
        }
        (0..n).filter(|&r| parent[r] == r && !anchored[r]).collect()
    }

    /// Ties each row in `rows` to `level[k]` by a penalty as strong as its diagonal,
    /// A_rr += A_rr and b_r += A_rr level: a pocket's system becomes positive definite, and the
    /// pocket's pressure level, which nothing else sets in incompressible flow, follows the tied
    /// value (the step passes the last step's pressure).
    pub fn tie(&mut self, rows: &[usize], level: &[f64]) {
        for (&r, &l) in rows.iter().zip(level) {
            let d = self.diag[r];
            self.diag[r] += d;
            self.rhs[r] += d * l;
        }
    }

    /// `|b − A x| / |b|` (0 when b = 0 and x solves it).
    pub fn relative_residual(&self, x: &[f64]) -> f64 {
        let mut ax = vec![0.0; self.len()];
        self.apply(x, &mut ax);
        let r2 = dot_fn(self.len(), |i| (self.rhs[i] - ax[i]).powi(2));
        let b2 = dot(&self.rhs, &self.rhs);
        if b2 > 0.0 {
            (r2 / b2).sqrt()
        } else {
            r2.sqrt()
        }
    }

    /// Jacobi-preconditioned conjugate gradient (Saad 2003, Alg. 9.1), per iteration: `Ad` (the
    /// two phases of [`PpeSystem::apply`], the only passes over the matrix) and `d·Ad`; the
    /// updates of x and r with `r·z` and `r·r` (z = D⁻¹r is not stored); the new direction
    /// `d = z + βd`. Each reduction is summed per fixed chunk in the order of the unfused
    /// algorithm, so the result is bit-identical to it.
    fn jacobi_pcg(&self, x: &mut [f64], tol: f64, max_iterations: u32) -> Result<PpeReport, PpeFailure> {
        let n = self.len();
        let b2 = dot(&self.rhs, &self.rhs);
        if b2 == 0.0 {
            x.iter_mut().for_each(|v| *v = 0.0);
            return Ok(PpeReport {
                iterations: 0,
                residual: 0.0,
                unknowns: n,
            });
        }
        let target2 = tol * tol * b2;
        let span = self.span();
        let mut r = vec![0.0; n];
        self.apply_with(span, x, &mut r);
        r.par_iter_mut().zip(&self.rhs).for_each(|(r, b)| *r = b - *r);
        let inv_d: Vec<f64> = self.diag.par_iter().map(|d| 1.0 / d).collect();
        let mut d: Vec<f64> = r.par_iter().zip(&inv_d).map(|(r, d)| r * d).collect();
        let mut ad = vec![0.0; n];
        let mut rz = dot(&r, &d);
        let mut r2 = dot(&r, &r);
        let mut k = 0;
        while r2 > target2 {
            if k == max_iterations || !r2.is_finite() {
                return Err(PpeFailure {
                    iterations: k,
                    residual: (r2 / b2).sqrt(),
                    unknowns: n,
                });
            }
            self.apply_with(span, &d, &mut ad);
            let alpha = rz / dot(&d, &ad);
            let (rz_new, r2_new) = update_chunks(x, &mut r, &d, &ad, &inv_d, alpha);
            let beta = rz_new / rz;
            rz = rz_new;
            d.par_chunks_mut(CHUNK)
                .zip(r.par_chunks(CHUNK))
                .zip(inv_d.par_chunks(CHUNK))
                .for_each(|((d, r), inv_d)| {
                    for ((d, r), i) in d.iter_mut().zip(r).zip(inv_d) {
                        *d = r * i + beta * *d;
                    }
                });
            r2 = r2_new;
            k += 1;
        }
        Ok(PpeReport {
            iterations: k,
            residual: (r2 / b2).sqrt(),
            unknowns: n,
        })
    }

    /// CG preconditioned by block symmetric Gauss–Seidel (Saad 2003, Alg. 9.1 with
    /// `M = (D + L) D⁻¹ (D + U)` restricted to each block of [`CHUNK`] rows, L and U the block's
    /// strictly lower and upper parts of A; symmetric positive definite as A is).
    fn sgs_pcg(&self, x: &mut [f64], tol: f64, max_iterations: u32) -> Result<PpeReport, PpeFailure> {
        let span = self.span();
        self.preconditioned_cg(span, x, tol, max_iterations, |r, z| self.block_sgs(r, z))
    }

    /// [`pcg`] on this matrix: `span` is the chunk length of [`PpeSystem::apply_with`].
    pub(super) fn preconditioned_cg(
        &self,
        span: usize,
        x: &mut [f64],
        tol: f64,
        max_iterations: u32,
        precondition: impl FnMut(&[f64], &mut [f64]) -> f64,
    ) -> Result<PpeReport, PpeFailure> {
        pcg(
            &self.rhs,
            x,
            tol,
            max_iterations,
            |d, ad| self.apply_with(span, d, ad),
            precondition,
        )
    }

    /// `z = M⁻¹ r` for the block symmetric Gauss–Seidel M of [`PpeSystem::sgs_pcg`] (a forward
    /// then a backward sweep in each block, the blocks in parallel); returns `r·z` summed per
    /// block.
    fn block_sgs(&self, r: &[f64], z: &mut [f64]) -> f64 {
        let parts: Vec<f64> = z
            .par_chunks_mut(CHUNK)
            .enumerate()
            .map(|(b, z)| {
                let (b0, b1) = (b * CHUNK, b * CHUNK + z.len());
                let entries = |i: usize| {
                    let (s, e) = (self.start[i] as usize, self.start[i + 1] as usize);
                    self.col[s..e].iter().zip(&self.val[s..e])
                };
                // Forward sweep `(D + L) y = r` column by column from the upper triangle: z
                // holds r minus the terms of the rows already solved.
                z.copy_from_slice(&r[b0..b1]);
                for i in b0..b1 {
                    let zi = z[i - b0] / self.diag[i];
                    z[i - b0] = zi;
                    for (&c, &v) in entries(i) {
                        let c = c as usize;
                        if c < b1 {
                            z[c - b0] -= f64::from(v) * zi;
                        }
                    }
                }
                // Backward sweep `(D + U) z = D y`.
                for i in (b0..b1).rev() {
                    let mut s = 0.0;
                    for (&c, &v) in entries(i) {
                        let c = c as usize;
                        if c < b1 {
                            s += f64::from(v) * z[c - b0];
                        }
                    }
                    z[i - b0] -= s / self.diag[i];
                }
                r[b0..b1].iter().zip(z.iter()).map(|(r, z)| r * z).sum::<f64>()
            })
            .collect();
        parts.iter().sum()
    }

    /// faer's sparse Cholesky of A (AMD ordering), factorised afresh every step.
    fn faer_cholesky(&self, x: &mut [f64], tol: f64) -> Result<PpeReport, PpeFailure> {
        use faer::linalg::solvers::Solve;
        use faer::sparse::{SparseColMat, Triplet};
        let n = self.len();
        let fail = |residual| PpeFailure {
            iterations: 1,
            residual,
            unknowns: n,
        };
        if n == 0 {
            return Ok(PpeReport::default());
        }
        let mut triplets = Vec::with_capacity(self.col.len() / 2 + n);
        for r in 0..n {
            triplets.push(Triplet::new(r, r, self.diag[r]));
            let (s, e) = (self.start[r] as usize, self.start[r + 1] as usize);
            for (&c, &v) in self.col[s..e].iter().zip(&self.val[s..e]) {
                if (c as usize) > r {
                    triplets.push(Triplet::new(c as usize, r, f64::from(v)));
                }
            }
        }
        let a =
            SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets).map_err(|_| fail(f64::NAN))?;
        let llt = a.sp_cholesky(faer::Side::Lower).map_err(|_| fail(f64::NAN))?;
        let mut sol = faer::Mat::<f64>::from_fn(n, 1, |i, _| self.rhs[i]);
        llt.solve_in_place(&mut sol);
        x.iter_mut().enumerate().for_each(|(i, v)| *v = sol[(i, 0)]);
        let residual = self.relative_residual(x);
        if residual <= tol {
            Ok(PpeReport {
                iterations: 1,
                residual,
                unknowns: n,
            })
        } else {
            Err(fail(residual))
        }
    }
}

/// Preconditioned conjugate gradient (Saad 2003, Alg. 9.1) on `A x = rhs` from the warm start
/// `x`, with `apply(d, out)` setting `out = A d` and `precondition(r, z)` setting `z = M⁻¹ r` and
/// returning `r·z`. Per iteration: `Ad` and `d·Ad`; the updates of x and r with `r·r` summed per
/// fixed chunk; the preconditioner; the new direction `d = z + βd`. Stops at
/// `|rhs − A x| ≤ tol |rhs|`, or fails after `max_iterations` with the residual.
pub(super) fn pcg(
    rhs: &[f64],
    x: &mut [f64],
    tol: f64,
    max_iterations: u32,
    mut apply: impl FnMut(&[f64], &mut [f64]),
    mut precondition: impl FnMut(&[f64], &mut [f64]) -> f64,
) -> Result<PpeReport, PpeFailure> {
    let n = rhs.len();
    let b2 = dot(rhs, rhs);
    if b2 == 0.0 {
        x.iter_mut().for_each(|v| *v = 0.0);
        return Ok(PpeReport {
            iterations: 0,
            residual: 0.0,
            unknowns: n,
        });
    }
    let target2 = tol * tol * b2;
    let mut r = vec![0.0; n];
    apply(x, &mut r);
    r.par_iter_mut().zip(rhs).for_each(|(r, b)| *r = b - *r);
    let mut z = vec![0.0; n];
    let mut rz = precondition(&r, &mut z);
    let mut d = z.clone();
    let mut ad = vec![0.0; n];
    let mut r2 = dot(&r, &r);
    let mut k = 0;
    while r2 > target2 {
        if k == max_iterations || !r2.is_finite() {
            return Err(PpeFailure {
                iterations: k,
                residual: (r2 / b2).sqrt(),
                unknowns: n,
            });
        }
        apply(&d, &mut ad);
        let alpha = rz / dot(&d, &ad);
        let parts: Vec<f64> = x
            .par_chunks_mut(CHUNK)
            .zip(r.par_chunks_mut(CHUNK))
            .zip(d.par_chunks(CHUNK).zip(ad.par_chunks(CHUNK)))
            .map(|((x, r), (d, ad))| {
                for (x, d) in x.iter_mut().zip(d) {
                    *x += alpha * d;
                }
                for (r, a) in r.iter_mut().zip(ad) {
                    *r -= alpha * a;
                }
                r.iter().map(|r| r * r).sum::<f64>()
            })
            .collect();
        r2 = parts.iter().sum();
        let rz_new = precondition(&r, &mut z);
        let beta = rz_new / rz;
        rz = rz_new;
        d.par_iter_mut()
            .zip(&z)
            .with_min_len(CHUNK)
            .for_each(|(d, z)| *d = z + beta * *d);
        k += 1;
    }
    Ok(PpeReport {
        iterations: k,
        residual: (r2 / b2).sqrt(),
        unknowns: n,
    })
}

/// The Jacobi preconditioner of a matrix with diagonal `diag` for [`pcg`]: `z = D⁻¹ r`, returns
/// `r·z` (summed as [`dot`]).
pub(super) fn jacobi(diag: &[f64]) -> impl FnMut(&[f64], &mut [f64]) -> f64 {
    let inv_d: Vec<f64> = diag.par_iter().map(|d| 1.0 / d).collect();
    move |r, z| {
        z.par_iter_mut()
            .zip(r)
            .zip(&inv_d)
            .with_min_len(CHUNK)
            .for_each(|((z, r), d)| *z = r * d);
        dot(r, z)
    }
}

/// `Σ a_i b_i`, summed in fixed chunks (reproducible).
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let parts: Vec<f64> = a
        .par_chunks(CHUNK)
        .zip(b.par_chunks(CHUNK))
        .map(|(a, b)| a.iter().zip(b).map(|(x, y)| x * y).sum())
        .collect();
    parts.iter().sum()
}

/// One PCG update per fixed chunk: `x += αd`, `r −= α Ad`; returns (`r·D⁻¹r`, `r·r`), each
/// summed per chunk as [`dot`].
fn update_chunks(
    x: &mut [f64],
    r: &mut [f64],
    d: &[f64],
    ad: &[f64],
    inv_d: &[f64],
    alpha: f64,
) -> (f64, f64) {
    let parts: Vec<(f64, f64)> = x
        .par_chunks_mut(CHUNK)
        .zip(r.par_chunks_mut(CHUNK))
        .zip(d.par_chunks(CHUNK).zip(ad.par_chunks(CHUNK)))
        .zip(inv_d.par_chunks(CHUNK))
        .map(|(((x, r), (d, ad)), inv_d)| {
            for (x, d) in x.iter_mut().zip(d) {
                *x += alpha * d;
            }
            for (r, a) in r.iter_mut().zip(ad) {
                *r -= alpha * a;
            }
            let rz: f64 = r.iter().zip(inv_d).map(|(r, i)| r * (r * i)).sum();
            let r2: f64 = r.iter().map(|r| r * r).sum();
            (rz, r2)
        })
        .collect();
    (parts.iter().map(|p| p.0).sum(), parts.iter().map(|p| p.1).sum())
}

/// `Σ_{i<n} f(i)`, summed in fixed chunks (reproducible).
fn dot_fn(n: usize, f: impl Fn(usize) -> f64 + Sync) -> f64 {
    let parts: Vec<f64> = (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| (c * CHUNK..((c + 1) * CHUNK).min(n)).map(&f).sum())
        .collect();
    parts.iter().sum()
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// The Euclidean distance |a − b|.
    pub(crate) fn distance(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt()
    }

    /// The 7-point Laplacian of an m³ grid with Dirichlet boundaries (diagonal 6, neighbours −1;
    /// the upper triangle stored):
    /// symmetric positive definite, like the PPE; m = 17 gives 4 913 unknowns, two SGS blocks.
    pub(crate) fn laplacian(m: usize) -> PpeSystem {
        let n = m * m * m;
        let mut s = PpeSystem {
            start: vec![0],
            ..Default::default()
        };
        for i in 0..n {
            let (x, y, z) = (i % m, (i / m) % m, i / (m * m));
            for (ok, j) in [
                (z > 0, i.wrapping_sub(m * m)),
                (y > 0, i.wrapping_sub(m)),
                (x > 0, i.wrapping_sub(1)),
                (x + 1 < m, i + 1),
                (y + 1 < m, i + m),
                (z + 1 < m, i + m * m),
            ] {
                if ok && j > i {
                    s.col.push(j as u32);
                    s.val.push(-1.0);
                }
            }
            s.start.push(s.col.len() as u32);
            s.diag.push(6.0);
            s.rhs.push(1.0 + (i % 7) as f64);
            s.particle.push(i as u32);
        }
        s
    }

    /// Aggregates of the m³ grid of [`laplacian`]: blocks of k³ points.
    pub(crate) fn block_aggregates(m: usize, k: usize) -> Vec<u32> {
        let b = m.div_ceil(k);
        (0..m * m * m)
            .map(|i| {
                let (x, y, z) = (i % m, (i / m) % m, i / (m * m));
                (x / k + b * (y / k + b * (z / k))) as u32
            })
            .collect()
    }

    /// The 5³ Dirichlet Laplacian (every row anchored) beside a pocket of three unknowns in a
    /// row, connected only to each other (Neumann all round: rows summing to zero) with a
    /// right-hand side that does not sum to zero over it: CG fails on the whole; the pocket is
    /// found by its lowest row, and once tied to a level the system solves, the pocket's
    /// pressures lying about that level (they differ by what its rows ask: x1 − x0 = b0, …).
    #[test]
    fn a_pocket_enclosed_by_solids_is_found_and_tied() {
        let mut a = laplacian(5);
        a.anchored = vec![true; a.len()];
        let first = a.len();
        for (k, col) in [(0, Some(first + 1)), (1, Some(first + 2)), (2, None)] {
            if let Some(c) = col {
                a.col.push(c as u32);
                a.val.push(-1.0);
            }
            a.start.push(a.col.len() as u32);
            a.diag.push(if k == 1 { 2.0 } else { 1.0 });
            a.rhs.push([1.0, 0.0, 2.0][k]);
            a.particle.push((first + k) as u32);
            a.anchored.push(false);
        }
        let mut x = vec![0.0; a.len()];
        assert!(a.solve(PpeSolver::JacobiPcg, &mut x, 1e-8, 2000).is_err());
        assert_eq!(a.enclosed_pockets(), vec![first]);
        a.tie(&[first], &[100.0]);
        let mut x = vec![0.0; a.len()];
        let report = a.solve(PpeSolver::JacobiPcg, &mut x, 1e-10, 2000);
        assert!(report.is_ok(), "{report:?}");
        assert!(a.relative_residual(&x) <= 1e-10);
        let pocket = &x[first..];
        assert!(pocket.iter().all(|v| (v - 100.0).abs() < 10.0), "{pocket:?}");
    }

    #[test]
    fn every_solver_reaches_the_tolerance_and_they_agree() {
        let mut a = laplacian(17);
        a.aggregate = block_aggregates(17, 3);
        let tol = 1e-8;
        let mut reference = vec![0.0; a.len()];
        let chol = a.solve(PpeSolver::FaerCholesky, &mut reference, tol, 1).unwrap();
        assert!(chol.residual <= tol);
        let norm = reference.iter().map(|v| v * v).sum::<f64>().sqrt();
        for solver in [
            PpeSolver::JacobiPcg,
            PpeSolver::SgsPcg,
            PpeSolver::TwoLevelPcg,
            PpeSolver::AdditiveTwoLevelPcg,
        ] {
            let mut x = vec![0.0; a.len()];
            let report = a.solve(solver, &mut x, tol, 1000).unwrap();
            // The solver's own residual is the one it reports, and it meets the tolerance.
            assert!(
                report.residual <= tol && a.relative_residual(&x) <= 1.01 * tol,
                "{solver:?}: {report:?}"
            );
            // |x − x*| ≤ κ(A) tol |x*|, κ ≈ 6/(6 − 6cos(π/18)) ≈ 66 for this grid.
            let err = distance(&x, &reference);
            assert!(err <= 66.0 * tol * norm, "{solver:?}: error {err:e}");
            println!(
                "{solver:?}: {} iterations, residual {:.1e}",
                report.iterations, report.residual
            );
        }
    }
}
