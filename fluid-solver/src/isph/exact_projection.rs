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
//! A body's load, and the fluid's reaction to it, is the face law of [`super::pair_laws`]: each
//! wet body particle's force `−π_j E_j − H_j` from the pressure `π_j` it reads from its fluid
//! neighbours (Adami's weights), shared among them by the same weights. Without the faces'
//! clamp at 0 that is linear in the fluid's pressures too, so it enters G_x, c and D as it is
//! (a two-hop coupling through the body particle); where a face's clamp acts (a face above the
//! water) the projection is not exact.

use super::kernel::Wendland;
use super::neighbour_list::NeighbourList;
use super::pair_gradients::PairGradients;
use super::pair_laws::BodyFaces;
use super::ppe::{jacobi, pcg, PpeFailure, PpeReport, PpeSystem, NOT_AN_UNKNOWN};
use super::ppe_two_level::{self, Form};
use super::walls::NeumannPair;
use crate::neighbours::vector_field::VectorField;
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use rayon::prelude::*;
use schemas::case::fluid::PpeSolver;

/// The bodies' face laws if any body particle is wet (the passes over the bodies are skipped
/// otherwise).
pub fn wet(faces: &BodyFaces) -> Option<&BodyFaces> {
    faces.weight.iter().any(|&w| w > 0.0).then_some(faces)
}

/// ε of the blend `(1 − ε) G_xᵀ G_x + ε L` (module doc).
pub const CHECKERBOARD_SHARE: f64 = 0.1;

/// Each wet body particle's reading of a fluid field through its face law,
/// `π_j = Σ_f W_fj value(f, j) / Σ_f W_fj` over its fluid neighbours f (0 elsewhere).
fn body_means(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    faces: Option<&BodyFaces>,
    value: impl Fn(usize, usize) -> f64 + Sync,
    out: &mut Vec<f64>,
) {
    let Some(faces) = faces else {
        return;
    };
    out.resize(p.len(), 0.0);
    out.par_iter_mut()
        .enumerate()
        .with_min_len(4096)
        .for_each(|(j, o)| {
            *o = 0.0;
            let den = faces.weight.get(j).copied().unwrap_or(0.0);
            if den > 0.0 {
                let num: f64 = list
                    .pairs(j)
                    .filter(|&(f, _)| p.kind[f] == FLUID)
                    .map(|(f, q)| k.w_at(q) * value(f, j))
                    .sum();
                *o = num / den;
            }
        });
}

/// The gradient at every fluid particle i (0 elsewhere) of `pressure(i)` on the fluid, of the
/// walls' pressure `2 pressure(i) + wall(i, w)` per pair, and of the bodies' face laws through
/// the readings `means` ([`body_means`]) with the faces' heads if `hydro`: the symmetric form
/// of [`super::pair_laws::symmetric_term`] and [`super::pair_laws::face_share`] without the
/// faces' clamp.
#[allow(clippy::too_many_arguments)]
fn symmetric_gradient(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    faces: Option<&BodyFaces>,
    pressure: impl Fn(usize) -> f64 + Sync,
    wall: impl Fn(usize, usize) -> f64 + Sync,
    (means, hydro): (&[f64], bool),
    out: &mut VectorField,
) {
    let body = Kind::Body.code();
    out.resize(p.len());
    (&mut out.x, &mut out.y, &mut out.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(512)
        .for_each(|(i, (ox, oy, oz))| {
            let mut g = [0.0; 3];
            if p.kind[i] == FLUID {
                let pi = pressure(i);
                for (j, q) in list.pairs(i) {
                    if p.kind[j] == body {
                        continue;
                    }
                    let pij = if p.kind[j] == FLUID {
                        pi + pressure(j)
                    } else {
                        2.0 * pi + wall(i, j)
                    };
                    let c = k.volume * k.dw_over_r_at(q) * pij;
                    g[0] += c * (p.x[i] - p.x[j]);
                    g[1] += c * (p.y[i] - p.y[j]);
                    g[2] += c * (p.z[i] - p.z[j]);
                }
                if let Some(faces) = faces {
                    add_face_terms(k, list, p, faces, i, (means, hydro), &mut g);
                }
            }
            (*ox, *oy, *oz) = (g[0], g[1], g[2]);
        });
}

/// Adds to fluid particle i's gradient `g` its body neighbours' face-law terms `F_ij / V`,
/// `F_ij = (W_ij / Σ_f W_fj)(−π_j E_j − H_j)` ([`super::pair_laws::face_share`] without the
/// faces' clamp), π_j the readings `means` and H_j only if `hydro`.
#[inline(always)]
fn add_face_terms(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    faces: &BodyFaces,
    i: usize,
    (means, hydro): (&[f64], bool),
    g: &mut [f64; 3],
) {
    let body = Kind::Body.code();
    for (j, q) in list.pairs(i) {
        let den = faces.weight[j];
        if p.kind[j] == body && den > 0.0 {
            let share = k.w_at(q) / (den * k.volume);
            let (e, h) = (faces.area[j], faces.hydro[j]);
            let h = if hydro { h } else { [0.0; 3] };
            (0..3).for_each(|a| g[a] -= share * (means[j] * e[a] + h[a]));
        }
    }
}

/// `(G_x x)_i` for every fluid particle i (0 elsewhere): the linear part of the symmetric
/// gradient with the unknowns' pressures `x` (unknown r is particle `particle[r]`) and 0
/// everywhere else, `Σ_j (x_i + x_j) c_ij` with the step's `pairs` ([`PairGradients`]) plus the
/// bodies' face-law terms; `full` holds x by particle (0 elsewhere: only the unknowns' entries
/// are ever written).
#[allow(clippy::too_many_arguments)]
pub fn gradient_of_unknowns(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    (pairs, faces): (&PairGradients, Option<&BodyFaces>),
    (particle, x): (&[u32], &[f64]),
    full: &mut Vec<f64>,
    means: &mut Vec<f64>,
    out: &mut VectorField,
) {
    full.resize(p.len(), 0.0);
    for (&i, &v) in particle.iter().zip(x) {
        full[i as usize] = v;
    }
    let full = &*full;
    body_means(k, list, p, faces, |f, _| full[f], means);
    let means = &*means;
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
                if let Some(faces) = faces {
                    add_face_terms(k, list, p, faces, i, (means, false), &mut g);
                }
            }
            (*ox, *oy, *oz) = (g[0], g[1], g[2]);
        });
}

/// `c_i`: the symmetric gradient at every fluid particle i (0 elsewhere) of the known pressures
/// alone, the surface particles' `dirichlet` values, the walls' differences Δp_iw of `walls`
/// and the bodies' faces' heads, with the unknowns at 0.
pub fn known_gradient(
    k: &Wendland,
    list: &NeighbourList,
    walls: &NeumannPair,
    faces: &BodyFaces,
    (row_of, dirichlet): (&[u32], &[f64]),
    means: &mut Vec<f64>,
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
    let faces = wet(faces);
    body_means(k, list, p, faces, |f, j| known(f) + walls.difference(f, j), means);
    let wall = |i: usize, j: usize| walls.difference(i, j);
    symmetric_gradient(k, list, p, faces, known, wall, (means, true), out);
}

/// `out_r = (G_xᵀ y)_k − s (Σ_w 2 V u_w·∇W_kw + the bodies' part)` for each unknown
/// k = `particle[r]` (module doc), with y a field on the fluid particles (0 elsewhere) and `s` =
/// 0 for the operator, ρ/Δt for the right-hand side's solid velocities u: `Σ_j (y_k − y_j)·c_kj`
/// over the step's `pairs` ([`PairGradients`]: fluid neighbours, and walls with their factor 2),
/// minus `s Σ_w u_w·c_kw`, plus the bodies' part ([`add_body_adjoint`]).
#[allow(clippy::too_many_arguments)]
pub fn adjoint_at_unknowns(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    (pairs, faces): (&PairGradients, Option<&BodyFaces>),
    particle: &[u32],
    (y, solid_velocity_scale): (&VectorField, f64),
    eta: &mut Vec<f64>,
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
            *o = sum;
        });
    if let Some(faces) = faces {
        add_body_adjoint(k, list, p, faces, particle, (y, s, 1.0), eta, out);
    }
}

/// Adds `scale` times the bodies' part of [`adjoint_at_unknowns`] to `out`: over the wet body
/// neighbours j of unknown k, `(W_kj / Σ_f W_fj) η_j` with
/// `η_j = −Σ_{fluid i} (W_ij / Σ_f W_fj) E_j·(y_i − s u_j) / V` (the adjoint of the face law's
/// share; a body moving with the water adds no divergence).
#[allow(clippy::too_many_arguments)]
fn add_body_adjoint(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    faces: &BodyFaces,
    particle: &[u32],
    (y, s, scale): (&VectorField, f64, f64),
    eta: &mut Vec<f64>,
    out: &mut [f64],
) {
    let body = Kind::Body.code();
    eta.resize(p.len(), 0.0);
    eta.par_iter_mut()
        .enumerate()
        .with_min_len(4096)
        .for_each(|(j, o)| {
            *o = 0.0;
            let den = faces.weight.get(j).copied().unwrap_or(0.0);
            if den > 0.0 {
                let e = faces.area[j];
                let u = [s * p.vx[j], s * p.vy[j], s * p.vz[j]];
                let sum: f64 = list
                    .pairs(j)
                    .filter(|&(f, _)| p.kind[f] == FLUID)
                    .map(|(f, q)| {
                        k.w_at(q) * (e[0] * (y.x[f] - u[0]) + e[1] * (y.y[f] - u[1]) + e[2] * (y.z[f] - u[2]))
                    })
                    .sum();
                *o = -sum / (den * k.volume);
            }
        });
    let eta = &*eta;
    out.par_iter_mut()
        .zip(particle)
        .with_min_len(512)
        .for_each(|(o, &kk)| {
            let i = kk as usize;
            for (j, q) in list.pairs(i) {
                let den = faces.weight[j];
                if p.kind[j] == body && den > 0.0 {
                    *o += scale * k.w_at(q) / den * eta[j];
                }
            }
        });
}

/// `out = (1 − ε) G_xᵀ y + ε A x` for the unknowns, the fluid and wall terms in one pass over
/// their pairs: y = G_x x (from [`gradient_of_unknowns`], which also wrote x by particle into
/// `full`), A S2-9's matrix of the PPE ([`super::ppe`]) from the weights of `pairs`,
/// `(A x)_k = Σ_{fluid j} F_kj (x_k − x_j)` with x = 0 off the unknowns; then the bodies' part.
#[allow(clippy::too_many_arguments)]
pub fn apply_operator(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    (pairs, faces): (&PairGradients, Option<&BodyFaces>),
    particle: &[u32],
    (y, full): (&VectorField, &[f64]),
    eta: &mut Vec<f64>,
    out: &mut [f64],
) {
    let eps = CHECKERBOARD_SHARE;
    out.par_iter_mut()
        .zip(particle)
        .with_min_len(512)
        .for_each(|(o, &kk)| {
            let i = kk as usize;
            let (yi, xi) = ([y.x[i], y.y[i], y.z[i]], full[i]);
            let (mut adjoint, mut laplacian) = (0.0, 0.0);
            for (c, &j) in pairs.of(i).iter().zip(list.of(i)) {
                let j = j as usize;
                adjoint += (yi[0] - y.x[j]) * f64::from(c[0])
                    + (yi[1] - y.y[j]) * f64::from(c[1])
                    + (yi[2] - y.z[j]) * f64::from(c[2]);
                laplacian += f64::from(c[3]) * (xi - full[j]);
            }
            *o = (1.0 - eps) * adjoint + eps * laplacian;
        });
    if let Some(faces) = faces {
        add_body_adjoint(k, list, p, faces, particle, (y, 0.0, 1.0 - eps), eta, out);
    }
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
    (pairs, faces): (&PairGradients, &BodyFaces),
    ppe: &mut PpeSystem,
    scratch: &mut VectorField,
) {
    let p = walls.p;
    let rho = walls.density;
    let mut bodies = Vec::new();
    known_gradient(
        k,
        list,
        walls,
        faces,
        (&ppe.row_of, dirichlet),
        &mut bodies,
        scratch,
    );
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
        k,
        list,
        p,
        (pairs, wet(faces)),
        &ppe.particle,
        (scratch, s),
        &mut bodies,
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
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    (pairs, faces): (&PairGradients, &BodyFaces),
    ppe: &PpeSystem,
    solver: PpeSolver,
    x: &mut [f64],
    tol: f64,
    max_iterations: u32,
) -> Result<PpeReport, PpeFailure> {
    let operator = (pairs, wet(faces));
    let mut y = VectorField::default();
    let (mut full, mut bodies) = (Vec::new(), Vec::new());
    let apply = |d: &[f64], out: &mut [f64]| {
        gradient_of_unknowns(
            k,
            list,
            p,
            operator,
            (&ppe.particle, d),
            &mut full,
            &mut bodies,
            &mut y,
        );
        apply_operator(k, list, p, operator, &ppe.particle, (&y, &full), &mut bodies, out);
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
