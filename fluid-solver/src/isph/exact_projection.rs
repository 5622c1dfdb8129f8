//! The exact projection of `pressure_gradient = "conservative"`: the pressure Poisson equation
//! built from the symmetric gradient the momentum equation uses, so that the projection removes
//! the divergence it measures (docs/physics.md §4.13, docs/notes/isph-exact-projection.md).
//!
//! The gradient is `(G p)_i = Σ_{fluid j} V (p_i + p_j) ∇W_ij + Σ_{solid w} V (2 p_i + Δp_iw) ∇W_iw`
//! ([`super::pair_laws::symmetric_term`]), antisymmetric pair by pair. Over the unknowns x (the
//! fluid particles not on the free surface) it is affine, `G p = G_x x + c`, with c the gradient
//! of the surface particles' Dirichlet pressures and of the walls' known differences Δp_iw. The
//! divergence that is its adjoint (`Σ_i V u_i·(G_x x)_i = −Σ_k V x_k (D u)_k` for every x) is
//!
//! `(D u)_k = Σ_{fluid j} V (u_j − u_k)·∇W_kj + Σ_{solid w} 2 V (u_w − u_k)·∇W_kw`,
//!
//! S2-8's difference divergence with each solid counted twice (the mirror of the wall's factor 2
//! in G), the solids' own velocity u_w entering as the known part. So the pressure does no work on
//! a velocity D calls divergence-free, and `v = v* − (Δt/ρ) G p` with
//! `D v = −α_d (1 − ρ̂/ρ0)/Δt_p` (S2-5's relaxation) is, with `D = −G_xᵀ` on the unknowns,
//!
//! `G_xᵀ G_x x = G_xᵀ ((ρ/Δt) v* − c) − (ρ/Δt) Σ_w 2 V u_w·∇W_kw − (ρ/Δt) α_d (1 − ρ̂_k/ρ0)/Δt_p`:
//!
//! the normal equations of the least-squares fit of `G p` to `ρ v*/Δt` over every fluid particle.
//! `G_xᵀ G_x` is symmetric positive semidefinite; it is blind to the lattice's checkerboard
//! (`p_i = ±1` by sites of alternating parity: the pair sums `p_i + p_j` cancel between the
//! parities), which the projection then neither sees nor damps. A share [`CHECKERBOARD_SHARE`] of
//! S2-9's assembled equation (`L x = b_S2`, [`super::ppe`]) is added to hold it:
//! `((1 − ε) G_xᵀ G_x + ε L) x = (1 − ε) b + ε b_S2`. Both equations hold hydrostatic water at rest,
//! so the blend does too; in motion the divergence left is `ε/(1 − ε)` times S2-9's own residual
//! (`tests/isph_divergence.rs` checks that identity: 0.68 of 1.41 1/s in the CI dam break, where
//! no row has a full support; a smaller ε leaves less but roughened the wall pressure).
//! The operator is applied without assembling it (two passes over the neighbour list per product:
//! `G_x x`, then `G_xᵀ` of it), preconditioned by the two-level method built on L
//! ([`super::ppe_two_level`]), to which it is spectrally close on smooth fields.
//!
//! With `kernel_correction = "moment"` (the default) every pair's `V ∇W` here, in G, c, D and the
//! bodies' completion, is the corrected vector of [`super::kernel_correction`], so the projection
//! stays exact (`tests/isph_divergence.rs`).
//!
//! A body's load, and the fluid's reaction to it, is the completion of
//! [`super::body_completion`]: fluid particle i's body term `2 p_i B_i + h_i`, linear in its own
//! pressure, so it enters G_x (`2 x_i B_i`), c (h_i, and `2 p_i B_i` of a surface particle) and
//! D (`2 (u_i − ū_i)·B_i`) as it is.

use super::body_completion::BodyCompletion;
use super::kernel::Wendland;
use super::neighbour_list::NeighbourList;
use super::pair_gradients::PairGradients;
use super::pair_laws;
use super::ppe::{jacobi, pcg, PpeFailure, PpeReport, PpeSystem, NOT_AN_UNKNOWN};
use super::ppe_two_level::{self, Form};
use super::walls::NeumannPair;
use crate::neighbours::vector_field::VectorField;
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use rayon::prelude::*;
use schemas::case::fluid::PpeSolver;

/// The bodies' completion if any fluid particle has a body neighbour (the body terms are
/// skipped otherwise).
pub fn near(bodies: &BodyCompletion) -> Option<&BodyCompletion> {
    bodies.any().then_some(bodies)
}

/// ε of the blend `(1 − ε) G_xᵀ G_x + ε L` (module doc).
pub const CHECKERBOARD_SHARE: f64 = 0.1;

/// `c_i`: the symmetric gradient at every fluid particle i (0 elsewhere) of the known pressures
/// alone, the surface particles' `dirichlet` values, the walls' differences Δp_iw of `walls`
/// and the bodies' terms `2 p_i B_i + h_i` ([`BodyCompletion::term`]), with the unknowns at 0.
pub fn known_gradient(
    k: &Wendland,
    list: &NeighbourList,
    walls: &NeumannPair,
    bodies: &BodyCompletion,
    (row_of, dirichlet): (&[u32], &[f64]),
    out: &mut VectorField,
) {
    let p = walls.p;
    let known = |i: usize| {
        if row_of[i] == NOT_AN_UNKNOWN {
            dirichlet[i]
        } else {
            0.0
        }
    };
    let bodies = near(bodies);
    let body = Kind::Body.code();
    out.resize(p.len());
    (&mut out.x, &mut out.y, &mut out.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(512)
        .for_each(|(i, (ox, oy, oz))| {
            let mut g = [0.0; 3];
            if p.kind[i] == FLUID {
                let pi = known(i);
                for (j, q) in list.pairs(i) {
                    if p.kind[j] == body {
                        continue;
                    }
                    let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
                    let t = if p.kind[j] == FLUID {
                        pair_laws::fluid_term(k, walls, (i, j), d, q, (pi, known(j)))
                    } else {
                        pair_laws::wall_term(k, walls, (i, j), d, q, pi)
                    };
                    (0..3).for_each(|a| g[a] += t[a]);
                }
                if let Some(bodies) = bodies {
                    let t = bodies.term(i, pi);
                    (0..3).for_each(|a| g[a] += t[a]);
                }
            }
            (*ox, *oy, *oz) = (g[0], g[1], g[2]);
        });
}

/// `(G_x x)_i` for every fluid particle i (0 elsewhere): the linear part of the symmetric
/// gradient with the unknowns' pressures `x` (unknown r is particle `particle[r]`) and 0
/// everywhere else, `Σ_j (x_i + x_j) c_ij` with the step's `pairs` ([`PairGradients`]) plus the
/// bodies' `2 x_i B_i`; `full` holds x by particle (0 elsewhere: only the unknowns' entries are
/// ever written).
pub fn gradient_of_unknowns(
    list: &NeighbourList,
    p: &Particles,
    (pairs, bodies): (&PairGradients, Option<&BodyCompletion>),
    (particle, x): (&[u32], &[f64]),
    full: &mut Vec<f64>,
    out: &mut VectorField,
) {
    full.resize(p.len(), 0.0);
    for (&i, &v) in particle.iter().zip(x) {
        full[i as usize] = v;
    }
    let full = &*full;
    out.resize(p.len());
    (&mut out.x, &mut out.y, &mut out.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(512)
        .for_each(|(i, (ox, oy, oz))| {
            let mut g = [0.0; 3];
            if p.kind[i] == FLUID {
                let xi = full[i];
                for (c, &j) in pairs.of(i).iter().zip(list.of(i)) {
                    let s = xi + full[j as usize];
                    (0..3).for_each(|a| g[a] += s * f64::from(c[a]));
                }
                if let Some(bodies) = bodies {
                    let b = bodies.zero[i];
                    (0..3).for_each(|a| g[a] += 2.0 * xi * b[a]);
                }
            }
            (*ox, *oy, *oz) = (g[0], g[1], g[2]);
        });
}

/// The bodies' part of `(G_xᵀ y)_k − s (solids' velocities)` at fluid particle k:
/// `2 (y_k − s ū_k)·B_k` ([`BodyCompletion`]).
#[inline(always)]
fn body_adjoint(bodies: Option<&BodyCompletion>, k: usize, y: [f64; 3], s: f64) -> f64 {
    match bodies {
        Some(b) => {
            let (z, u) = (b.zero[k], b.velocity[k]);
            2.0 * ((y[0] - s * u[0]) * z[0] + (y[1] - s * u[1]) * z[1] + (y[2] - s * u[2]) * z[2])
        }
        None => 0.0,
    }
}

/// `out_r = (G_xᵀ y)_k − s (Σ_w 2 V u_w·∇W_kw + the bodies' part)` for each unknown
/// k = `particle[r]` (module doc), with y a field on the fluid particles (0 elsewhere) and `s` =
/// 0 for the operator, ρ/Δt for the right-hand side's solid velocities u: `Σ_j (y_k − y_j)·c_kj`
/// over the step's `pairs` ([`PairGradients`]: fluid neighbours, and walls with their factor 2),
/// minus `s Σ_w u_w·c_kw`, plus the bodies' part ([`body_adjoint`]).
pub fn adjoint_at_unknowns(
    list: &NeighbourList,
    p: &Particles,
    (pairs, bodies): (&PairGradients, Option<&BodyCompletion>),
    particle: &[u32],
    (y, solid_velocity_scale): (&VectorField, f64),
    out: &mut [f64],
) {
    let s = solid_velocity_scale;
    out.par_iter_mut()
        .zip(particle)
        .with_min_len(512)
        .for_each(|(o, &kk)| {
            let i = kk as usize;
            let yi = [y.x[i], y.y[i], y.z[i]];
            let mut sum = 0.0;
            for (c, &j) in pairs.of(i).iter().zip(list.of(i)) {
                let j = j as usize;
                let mut dy = [yi[0] - y.x[j], yi[1] - y.y[j], yi[2] - y.z[j]];
                if s != 0.0 && p.kind[j] != FLUID {
                    dy = [dy[0] - s * p.vx[j], dy[1] - s * p.vy[j], dy[2] - s * p.vz[j]];
                }
                sum += dy[0] * f64::from(c[0]) + dy[1] * f64::from(c[1]) + dy[2] * f64::from(c[2]);
            }
            *o = sum + body_adjoint(bodies, i, yi, s);
        });
}

/// `out = (1 − ε) G_xᵀ y + ε A x` for the unknowns in one pass over their pairs: y = G_x x
/// (from [`gradient_of_unknowns`], which also wrote x by particle into `full`), A S2-9's matrix
/// of the PPE ([`super::ppe`]) from the weights of `pairs`, `(A x)_k = Σ_{fluid j} F_kj (x_k − x_j)`
/// with x = 0 off the unknowns, and the bodies' part ([`body_adjoint`]).
pub fn apply_operator(
    list: &NeighbourList,
    (pairs, bodies): (&PairGradients, Option<&BodyCompletion>),
    particle: &[u32],
    (y, full): (&VectorField, &[f64]),
    out: &mut [f64],
) {
    let eps = CHECKERBOARD_SHARE;
    out.par_iter_mut()
        .zip(particle)
        .with_min_len(512)
        .for_each(|(o, &kk)| {
            let i = kk as usize;
            let (yi, xi) = ([y.x[i], y.y[i], y.z[i]], full[i]);
            let (mut adjoint, mut laplacian) = (body_adjoint(bodies, i, yi, 0.0), 0.0);
            for (c, &j) in pairs.of(i).iter().zip(list.of(i)) {
                let j = j as usize;
                adjoint += (yi[0] - y.x[j]) * f64::from(c[0])
                    + (yi[1] - y.y[j]) * f64::from(c[1])
                    + (yi[2] - y.z[j]) * f64::from(c[2]);
                laplacian += f64::from(c[3]) * (xi - full[j]);
            }
            *o = (1.0 - eps) * adjoint + eps * laplacian;
        });
}

/// Blends the exact projection's right-hand side into `ppe.rhs`, which holds S2-9's `b_S2` of
/// the same unknowns: `(1 − ε) b + ε b_S2` (module doc), with v* in the particles, the step's
/// `dt` (the pressure's step Δt_p), ρ̂/ρ0 in `ratio` and the density relaxation's `alpha_d`.
#[allow(clippy::too_many_arguments)]
pub fn blend_right_hand_side(
    k: &Wendland,
    list: &NeighbourList,
    walls: &NeumannPair,
    dirichlet: &[f64],
    ratio: &[f64],
    alpha_d: f64,
    dt: f64,
    (pairs, bodies): (&PairGradients, &BodyCompletion),
    ppe: &mut PpeSystem,
    scratch: &mut VectorField,
) {
    let p = walls.p;
    let rho = walls.density;
    known_gradient(k, list, walls, bodies, (&ppe.row_of, dirichlet), scratch);
    let s = rho / dt;
    (&mut scratch.x, &mut scratch.y, &mut scratch.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(4096)
        .for_each(|(i, (x, y, z))| {
            if p.kind[i] == FLUID {
                (*x, *y, *z) = (s * p.vx[i] - *x, s * p.vy[i] - *y, s * p.vz[i] - *z);
            }
        });
    let mut b = vec![0.0; ppe.len()];
    adjoint_at_unknowns(
        list,
        p,
        (pairs, near(bodies)),
        &ppe.particle,
        (scratch, s),
        &mut b,
    );
    let eps = CHECKERBOARD_SHARE;
    ppe.rhs
        .par_iter_mut()
        .zip(&b)
        .zip(&ppe.particle)
        .with_min_len(4096)
        .for_each(|((r, b), &i)| {
            let relaxation = s * alpha_d * (1.0 - ratio[i as usize]) / dt;
            *r = (1.0 - eps) * (b - relaxation) + eps * *r;
        });
}

/// Solves `((1 − ε) G_xᵀ G_x + ε L) x = ppe.rhs` (module doc) from the warm start `x`, L the
/// matrix in `ppe`, preconditioned by the two-level method on L with the two-level `solver`s
/// and by L's diagonal with the others.
#[allow(clippy::too_many_arguments)]
pub fn solve(
    list: &NeighbourList,
    p: &Particles,
    (pairs, bodies): (&PairGradients, &BodyCompletion),
    ppe: &PpeSystem,
    solver: PpeSolver,
    x: &mut [f64],
    tol: f64,
    max_iterations: u32,
) -> Result<PpeReport, PpeFailure> {
    let operator = (pairs, near(bodies));
    let mut y = VectorField::default();
    let mut full = Vec::new();
    let apply = |d: &[f64], out: &mut [f64]| {
        gradient_of_unknowns(list, p, operator, (&ppe.particle, d), &mut full, &mut y);
        apply_operator(list, operator, &ppe.particle, (&y, &full), out);
    };
    match solver {
        PpeSolver::TwoLevelPcg => {
            ppe_two_level::solve_operator(ppe, Form::Multiplicative, x, tol, max_iterations, apply)
        }
        PpeSolver::AdditiveTwoLevelPcg => {
            ppe_two_level::solve_operator(ppe, Form::Additive, x, tol, max_iterations, apply)
        }
        _ => pcg(&ppe.rhs, x, tol, max_iterations, apply, jacobi(&ppe.diag)),
    }
}
