//! The pressure Poisson equation of the projection (S2-5), assembled on the neighbour list and
//! solved every step.
//!
//! With S2-9's Laplacian `⟨∇²p⟩_i = Σ_j F_ij (p_j − p_i)`, `F_ij = −2 V W'(r)/r ≥ 0`, the rows of
//! the fluid particles that are not on the free surface form `A p = b` with
//! `A_ii = Σ_{fluid j} F_ij`, `A_ij = −F_ij` (j another unknown), surface neighbours entering as
//! p = 0 (Dirichlet) and wall neighbours as known pressure differences (Neumann, see
//! [`super::walls`]), which the step puts into b. A is symmetric (equal volumes) and, with at
//! least one surface neighbour per connected body of water, positive definite: conjugate
//! gradients apply.
//!
//! Two solvers ([`schemas::case::fluid::PpeSolver`]): a Jacobi-preconditioned CG over the rows in
//! rayon, warm-started from the last step's pressure (its dot products summed in fixed chunks, so
//! a run is bit-reproducible), and faer's sparse Cholesky factorisation of A. Both must reach
//! `|b − A p| ≤ tol |b|`, else the step fails with [`PpeFailure`].

use rayon::prelude::*;
use schemas::case::fluid::PpeSolver;

/// Row of a particle that is not an unknown.
pub const NOT_AN_UNKNOWN: u32 = u32::MAX;

/// Fixed chunk of the reductions (independent of the thread count, for reproducible sums).
const CHUNK: usize = 4096;

/// The assembled system `A p = b` over the unknowns.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PpeSystem {
    /// Particle index of each unknown.
    pub particle: Vec<u32>,
    /// Unknown number of each particle, or [`NOT_AN_UNKNOWN`].
    pub row_of: Vec<u32>,
    /// Off-diagonal entries of row r: `col[start[r] .. start[r + 1]]`, values `−F` in `val`.
    pub start: Vec<u32>,
    pub col: Vec<u32>,
    pub val: Vec<f64>,
    pub diag: Vec<f64>,
    pub rhs: Vec<f64>,
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

    /// `out = A x`.
    pub fn apply(&self, x: &[f64], out: &mut [f64]) {
        out.par_iter_mut()
            .enumerate()
            .with_min_len(1024)
            .for_each(|(r, o)| *o = self.row_times(r, x));
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

    /// Jacobi-preconditioned conjugate gradient (Saad 2003, Alg. 9.1), three passes over the
    /// unknowns per iteration: `Ad` with `d·Ad`; the updates of x and r with `r·z` and `r·r`
    /// (z = D⁻¹r is not stored); the new direction `d = z + βd`. Each reduction is summed per
    /// fixed chunk in the order of the unfused algorithm, so the result is bit-identical to it.
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
        let mut r = vec![0.0; n];
        self.apply(x, &mut r);
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
            let d_ad = self.apply_and_dot(&d, &mut ad);
            let alpha = rz / d_ad;
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

    /// `out = A x` and `x·out`, per fixed chunk of rows (the sum as [`dot`]'s).
    fn apply_and_dot(&self, x: &[f64], out: &mut [f64]) -> f64 {
        let parts: Vec<f64> = out
            .par_chunks_mut(CHUNK)
            .enumerate()
            .map(|(c, o)| {
                let r0 = c * CHUNK;
                for (k, o) in o.iter_mut().enumerate() {
                    *o = self.row_times(r0 + k, x);
                }
                x[r0..r0 + o.len()]
                    .iter()
                    .zip(o.iter())
                    .map(|(x, y)| x * y)
                    .sum::<f64>()
            })
            .collect();
        parts.iter().sum()
    }

    /// `(A x)_r`.
    #[inline(always)]
    fn row_times(&self, r: usize, x: &[f64]) -> f64 {
        let (s, e) = (self.start[r] as usize, self.start[r + 1] as usize);
        let mut sum = self.diag[r] * x[r];
        for (&c, &v) in self.col[s..e].iter().zip(&self.val[s..e]) {
            sum += v * x[c as usize];
        }
        sum
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
                    triplets.push(Triplet::new(c as usize, r, v));
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

/// `Σ a_i b_i`, summed in fixed chunks (reproducible).
fn dot(a: &[f64], b: &[f64]) -> f64 {
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
