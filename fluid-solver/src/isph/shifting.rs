//! Particle shifting (case key `shifting = "lind"`): Lind, Xu, Stansby & Rogers (2012, J. Comput.
//! Phys. 231, 1499–1523, after Xu, Stansby & Laurence 2009) move every fluid particle, after its
//! position update, down the gradient of the particle concentration `C_i = Σ_j V W_ij`:
//!
//! `δr_i = −D ∇C_i`, `∇C_i = Σ_j V ∇_i W_ij` (fluid and solid neighbours),
//!
//! with a coefficient in the velocity-scaled form of Skillen, Lind, Stansby & Rogers (2013,
//! Comput. Methods Appl. Mech. Engrg. 265, 163–173), `D = A h |u|_max Δt` (h = r_e/2, A the case's
//! `shifting_coefficient`, default 0.5, `|u|_max` over the fluid after the velocity update): one
//! D for all particles, as Lind et al.'s, so water at rest is not shifted. Skillen et al. take
//! each particle's own |u_i| (A = 2); measured on the L/20 dam break with the symmetric gradient
//! at 2.0 Δs, that form hardly smooths the far-wall probe (the water standing against the wall is
//! slow: high-pass 422 Pa at A = 0.5, 290 at A = 2, without the wall rule below, against 323 without shifting and 215 with
//! this form at A = 0.5; docs/notes/isph-symmetric-gradient-and-shifting.md). With this form
//! A = 2 was stopped by the detector at 0.29 s (a particle in the thin layer left on the floor
//! driven into it and thrown out at 10 m/s); 1 and 0.5 ran to 0.6 s.
//!
//! ∇C_i is taken at the step's start positions r^n on the step's neighbour list (the list the
//! step's other stages use), and the shift is added to r^{n+1}.
//!
//! Free surface, after Lind et al. (2012, their free-surface form with α = 0, as Skillen et al.
//! 2013): a particle in Marrone's band or on the surface (λ_min ≤ 0.9, S2-11) keeps only the
//! part of δr tangential to its outward normal ([`super::free_surface::outward_normal`]), so the
//! surface is not diffused outwards; a splash particle (λ_min ≤ 0.2) or one whose normal cannot be
//! formed is not shifted. Walls (ours): no particle is shifted towards a wall: for each
//! solid neighbour in turn, the part of δr along its normal into the fluid
//! ([`super::walls::normals`], a unit vector) is dropped when it points into the solid. The shift of one step is
//! capped at [`MAX_SHIFT`] Δs (ours, so that with the advective Courant limit 0.4 a particle
//! moves less than the instability detector's 0.5 Δs per step).
//!
//! Resolved bodies (ours): a fluid particle with a body particle among its neighbours is not
//! shifted, so the water in a body's support moves with its velocity only and the body's load
//! reads it unshifted. Without this rule, the box held fixed in the settling tank of
//! `tests/isph_bodies.rs` (symmetric gradient at 2.0 Δs) read ρgV +4.05 % at its lattice site
//! and +8.66 % 5 mm above it (bound 5 %; without shifting −0.08 % and +0.86 %): a particle at
//! 0.3 m/s in the settling water sets D for all, and the still water next to the box was shifted
//! by 0.5 Δs in 0.2 s. With it: −0.26 % and +0.45 %.
//!
//! Only positions move: velocities and pressures are not Taylor-corrected to the new position
//! (Lind et al. do), so shifting moves no momentum (the closed-box budget of
//! `tests/isph_momentum.rs` still closes to round-off); the pressure is only the PPE's warm start.

use super::free_surface::{outward_normal, LAMBDA_INNER, LAMBDA_SPLASH};
use super::kernel::Wendland;
use super::neighbour_list::NeighbourList;
use crate::neighbours::vector_field::VectorField;
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use rayon::prelude::*;

/// The largest shift of one step, in Δs.
pub const MAX_SHIFT: f64 = 0.1;

/// `−∇C_i` of every fluid particle with the surface and wall treatment of the module doc (the
/// shift per unit D, 1/m), 0 for other particles; `lambda` and `takes_part` as in
/// [`super::free_surface`], `wall_normals` the solids' normals into the fluid.
pub fn directions(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    lambda: &[f64],
    takes_part: &[u8],
    wall_normals: &VectorField,
    out: &mut VectorField,
) {
    out.resize(p.len());
    (&mut out.x, &mut out.y, &mut out.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(512)
        .for_each(|(i, (ox, oy, oz))| {
            let s = if p.kind[i] == FLUID && lambda[i] > LAMBDA_SPLASH {
                direction(k, list, p, lambda[i], takes_part, wall_normals, i)
            } else {
                [0.0; 3]
            };
            (*ox, *oy, *oz) = (s[0], s[1], s[2]);
        });
}

/// `−∇C_i` of fluid particle i, treated at the surface and walls; 0 beside a body.
fn direction(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    lambda: f64,
    takes_part: &[u8],
    wall_normals: &VectorField,
    i: usize,
) -> [f64; 3] {
    let body = Kind::Body.code();
    if list.of(i).iter().any(|&j| p.kind[j as usize] == body) {
        return [0.0; 3];
    }
    let mut s = [0.0; 3];
    for (j, q) in list.pairs(i) {
        let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
        // −V ∇_i W_ij = −V (W'/r)(x_i − x_j)
        let c = -k.volume * k.dw_over_r_at(q);
        (0..3).for_each(|a| s[a] += c * d[a]);
    }
    if lambda <= LAMBDA_INNER {
        let Some(n) = outward_normal(k, list, p, takes_part, i) else {
            return [0.0; 3];
        };
        drop_along(&mut s, n, f64::INFINITY);
    }
    // Into no wall: each solid neighbour's normal into the fluid in turn (at a corner the walls'
    // normals differ, and a mean of them would let a particle into one of the walls).
    for &j in list.of(i) {
        let j = j as usize;
        if p.kind[j] != FLUID {
            let n = [wall_normals.x[j], wall_normals.y[j], wall_normals.z[j]];
            if n != [0.0; 3] {
                drop_along(&mut s, n, 0.0);
            }
        }
    }
    s
}

/// Removes from `s` its component along the unit vector `n` when that component is below `above`
/// (always for `f64::INFINITY`).
fn drop_along(s: &mut [f64; 3], n: [f64; 3], above: f64) {
    let sn = s[0] * n[0] + s[1] * n[1] + s[2] * n[2];
    if sn < above {
        (0..3).for_each(|a| s[a] -= sn * n[a]);
    }
}

/// Adds `D × direction`, `D = A h |u|_max Δt` with h = r_e/2 and `|u|_max` over the fluid
/// particles' velocities, capped at [`MAX_SHIFT`] Δs per particle, to the fluid's positions.
pub fn apply(p: &mut Particles, directions: &VectorField, a: f64, k: &Wendland, dt: f64) {
    let cap = MAX_SHIFT * k.spacing;
    let u_max = (&p.vx, &p.vy, &p.vz, &p.kind)
        .into_par_iter()
        .with_min_len(4096)
        .filter(|t| *t.3 == FLUID)
        .map(|(u, v, w, _)| (u * u + v * v + w * w).sqrt())
        .reduce(|| 0.0, f64::max);
    let d = a * 0.5 * k.radius * u_max * dt;
    (&mut p.x, &mut p.y, &mut p.z, &p.kind)
        .into_par_iter()
        .enumerate()
        .with_min_len(4096)
        .filter(|(_, t)| *t.3 == FLUID)
        .for_each(|(i, (x, y, z, _))| {
            let s = [d * directions.x[i], d * directions.y[i], d * directions.z[i]];
            let len = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            let f = if len > cap { cap / len } else { 1.0 };
            *x += f * s[0];
            *y += f * s[1];
            *z += f * s[2];
        });
}
