//! Collision of close approaching particles, shared by both methods (Koshizuka's MPS codes; the
//! seeds are silent on it, see [`crate::emps::step`]): the pass over the fluid and the pair law
//! of a fluid–body collision, from which the body exchange takes a body's load and its reaction.

use crate::bodies::pair_law::{ExchangeScales, PairLaw};
use crate::neighbours::neighbour_search::CellGrid;
use crate::neighbours::vector_field::{add, PassTotals, VectorField};
use crate::particles::kind::FLUID;
use crate::particles::Particles;
use rayon::prelude::*;

/// Particles closer than this many spacings that approach each other collide.
pub const COLLISION_DISTANCE: f64 = 0.8;
/// Coefficient of restitution of a collision.
pub const RESTITUTION: f64 = 0.2;

/// Collision of close particles (Koshizuka's collision model; see the module doc): for fluid i and any neighbour j closer than `distance` that approaches
/// i, the normal relative velocity is reversed with restitution `e`: for a fluid j (equal mass)
/// `Δu_i = (1+e)/2 ((u_j − u_i)·n) n`, for a wall, dummy or body j (moved by its own
/// kinematics) `Δu_i = (1+e) ((u_j − u_i)·n) n`, with n = r_ij/|r_ij|. Writes Δu into `out`.
pub fn collision(grid: &CellGrid, p: &Particles, distance: f64, e: f64, out: &mut VectorField) -> PassTotals {
    let d2 = distance * distance;
    let reach = grid.reach(distance);
    let (x, y, z, kind) = (&p.x, &p.y, &p.z, &p.kind);
    let (vx, vy, vz) = (&p.vx, &p.vy, &p.vz);
    out.resize(p.len());
    (&mut out.x, &mut out.y, &mut out.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(256)
        .map(|(i, (ox, oy, oz))| {
            (*ox, *oy, *oz) = (0.0, 0.0, 0.0);
            if kind[i] != FLUID {
                return PassTotals::default();
            }
            let (xi, yi, zi) = (x[i], y[i], z[i]);
            let mut du = [0.0; 3];
            let mut wall = [0.0; 3];
            let mut seen = 0u64;
            grid.for_each_range(i, reach, |s, e_| {
                seen += (e_ - s) as u64;
                for j in s..e_ {
                    let r = [x[j] - xi, y[j] - yi, z[j] - zi];
                    let r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
                    // Written so that a NaN neighbour is skipped (it is the detector's to report).
                    if !(r2 < d2 && r2 > 0.0) {
                        continue;
                    }
                    let closing = (vx[j] - vx[i]) * r[0] + (vy[j] - vy[i]) * r[1] + (vz[j] - vz[i]) * r[2];
                    if closing >= 0.0 || closing.is_nan() {
                        continue;
                    }
                    let share = if kind[j] == FLUID { 0.5 } else { 1.0 };
                    let c = share * (1.0 + e) * closing / r2;
                    for a in 0..3 {
                        du[a] += c * r[a];
                        if kind[j] != FLUID {
                            wall[a] += c * r[a];
                        }
                    }
                }
            });
            (*ox, *oy, *oz) = (du[0], du[1], du[2]);
            PassTotals {
                from_non_fluid: wall,
                candidates: seen,
            }
        })
        .reduce(PassTotals::default, add)
}

/// The fluid particles whose velocity the pass changed (a nonzero Δu in `du`, as
/// [`collision`] wrote it).
pub fn kicked(du: &VectorField) -> u64 {
    (&du.x, &du.y, &du.z)
        .into_par_iter()
        .with_min_len(4096)
        .filter(|(x, y, z)| **x != 0.0 || **y != 0.0 || **z != 0.0)
        .count() as u64
}

/// The collision stage's force on body particle j from fluid particle i, `−m Δu_i / Δt` with
/// `Δu_i = (1+e) ((u_j − u_i)·r_ij) r_ij/|r_ij|²` when they are closer than the collision
/// distance and approach each other (the body particle moves with its rigid velocity, as a
/// wall), reported as impulse / Δt of the step.
pub fn contact_law<'a>(scales: &ExchangeScales, p: &'a Particles) -> PairLaw<'a> {
    let distance = COLLISION_DISTANCE * scales.spacing;
    let impulse_to_force = scales.particle_mass / scales.dt;
    PairLaw::new(distance, move |i, j| {
        let d = [p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i]];
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if !(r2 < distance * distance && r2 > 0.0) {
            return None;
        }
        let closing = (p.vx[j] - p.vx[i]) * d[0] + (p.vy[j] - p.vy[i]) * d[1] + (p.vz[j] - p.vz[i]) * d[2];
        if closing >= 0.0 || closing.is_nan() {
            return None;
        }
        let c = -impulse_to_force * (1.0 + RESTITUTION) * closing / r2;
        Some(d.map(|v| c * v))
    })
}
