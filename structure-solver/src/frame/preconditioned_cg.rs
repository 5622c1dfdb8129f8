//! Conjugate gradients on the condensed effective matrix, preconditioned by the kept factor of an
//! older one. After a hinge forms or closes, only the members it changed are re-condensed: the
//! current matrix differs from the factored one by a change of small rank (those members' joints),
//! so the iteration converges in about rank + 1 steps (in exact arithmetic), and the step is solved
//! with the current tangent to [`CG_TOLERANCE`] instead of refactorising. Standard preconditioned CG
//! from x = 0: `z = P⁻¹ r`, `p = z + β p`, `α = rᵀz / pᵀAp`, with P the kept factor.

use super::assembly::SparseSystem;

/// Relative residual `‖b − A x‖ / ‖b‖` (condensed system) at which the iteration stops: far below
/// the unbalanced force a one-solve step leaves (1e-4 to 1e-2 of its first one in the benchmarks).
/// With 1e-6 or 1e-10 the benchmark's hinge rows took a similar number of products (within their
/// run-to-run scatter).
pub const CG_TOLERANCE: f64 = 1e-8;

/// What an iteration reached.
pub struct Iterated {
    /// Matrix products done.
    pub iterations: usize,
    /// Whether the relative residual reached [`CG_TOLERANCE`].
    pub converged: bool,
}

/// Solves `A x = b` in place (`x` holds b, then x) for A the system's current values, preconditioned
/// by its kept factor, in at most `max_iterations` products with A. It stops at a residual of
/// [`CG_TOLERANCE`] `‖b‖` or `enough`, whichever is larger (`enough`: the residual below which the
/// caller needs no more, 0 for the relative tolerance alone).
pub fn solve(
    system: &mut SparseSystem,
    x: &mut [f64],
    max_iterations: usize,
    enough: f64,
) -> Result<Iterated, String> {
    let n = x.len();
    let mut r = x.to_vec();
    let b_norm = dot(&r, &r).sqrt();
    let target = (CG_TOLERANCE * b_norm).max(enough);
    x.iter_mut().for_each(|v| *v = 0.0);
    if b_norm == 0.0 {
        return Ok(Iterated {
            iterations: 0,
            converged: true,
        });
    }
    let mut z = r.clone();
    system.solve_factored(&mut z)?;
    let mut p = z.clone();
    let mut rz = dot(&r, &z);
    let mut q = vec![0.0; n];
    for iteration in 1..=max_iterations {
        system.multiply(&p, &mut q);
        let pq = dot(&p, &q);
        if pq.is_nan() || pq <= 0.0 {
            return Err(format!(
                "the frame's system matrix is not positive definite (conjugate gradients met pᵀAp = {pq:e})"
            ));
        }
        let alpha = rz / pq;
        for ((xi, ri), (pi, qi)) in x.iter_mut().zip(r.iter_mut()).zip(p.iter().zip(&q)) {
            *xi += alpha * pi;
            *ri -= alpha * qi;
        }
        if dot(&r, &r).sqrt() <= target {
            return Ok(Iterated {
                iterations: iteration,
                converged: true,
            });
        }
        z.copy_from_slice(&r);
        system.solve_factored(&mut z)?;
        let rz_new = dot(&r, &z);
        let beta = rz_new / rz;
        rz = rz_new;
        for (pi, zi) in p.iter_mut().zip(&z) {
            *pi = zi + beta * *pi;
        }
    }
    Ok(Iterated {
        iterations: max_iterations,
        converged: false,
    })
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
