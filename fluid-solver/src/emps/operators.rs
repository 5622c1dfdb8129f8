//! The E-MPS particle operators as passes over the cell list: number density (S1-15), the
//! pressure gradient (S1-3) and the velocity Laplacian (S1-4). The collision pass both methods
//! share is [`crate::neighbours::collision`].
//!
//! Each pass is a gather: particle i sums over its neighbours and writes only its own slot, so
//! the passes run in parallel without locks. The inner loops are branch-free over contiguous
//! index ranges (see [`crate::neighbours::neighbour_search`]).

use super::kernel::Kernel;
use crate::neighbours::neighbour_search::CellGrid;
use crate::neighbours::vector_field::{add, PassTotals, VectorField};
use crate::particles::kind::{DUMMY, FLUID};
use crate::particles::Particles;
use rayon::prelude::*;

/// S1-15 (sum part): `n_i = Σ_{j≠i} w(|r_j − r_i|)` with r_e = 3.1 Δs, for fluid particles and
/// for wall, body and gate particles that have fluid within r_e,grad (only those enter the
/// gradient S1-3 of a fluid particle). Dummies and walls away from the water get n = 0, so
/// P = 0: no fluid particle would read their pressure. Returns the candidates examined.
pub fn number_density(grid: &CellGrid, kernel: &Kernel, p: &mut Particles) -> u64 {
    let re = kernel.re;
    let re2 = re * re;
    let inv_re = 1.0 / re;
    let reach = grid.reach(re);
    let reach_grad = grid.reach(kernel.re_grad);
    let (x, y, z, kind) = (&p.x, &p.y, &p.z, &p.kind);
    p.number_density
        .par_iter_mut()
        .enumerate()
        .with_min_len(256)
        .map(|(i, n)| {
            if kind[i] == DUMMY || (kind[i] != FLUID && !grid.fluid_near(i, reach_grad)) {
                *n = 0.0;
                return 0;
            }
            let (xi, yi, zi) = (x[i], y[i], z[i]);
            let mut sum = 0.0;
            let mut seen = 0u64;
            grid.for_each_range(i, reach, |s, e| {
                seen += (e - s) as u64;
                for ((&xj, &yj), &zj) in x[s..e].iter().zip(&y[s..e]).zip(&z[s..e]) {
                    let (dx, dy, dz) = (xj - xi, yj - yi, zj - zi);
                    let r2 = dx * dx + dy * dy + dz * dz;
                    let r = r2.sqrt();
                    let w = (re - r) * (re - r) / r * inv_re;
                    sum += if r2 < re2 && r2 > 0.0 { w } else { 0.0 };
                }
            });
            *n = sum;
            seen
        })
        .sum()
}

/// S1-3: `⟨∇f⟩_i = d/n0_grad Σ_j (f_j + f_i) r_ij/|r_ij|² w_grad(|r_ij|)` for fluid particles i,
/// over neighbours j that carry pressure (dummies only fill the number density). Writes `out`
/// (0 for non-fluid particles). `from_non_fluid` is Σ_i of the part due to non-fluid j.
pub fn gradient(
    grid: &CellGrid,
    kernel: &Kernel,
    p: &Particles,
    f: &[f64],
    out: &mut VectorField,
) -> PassTotals {
    let re = kernel.re_grad;
    let re2 = re * re;
    let inv_re = 1.0 / re;
    let factor = kernel.gradient_factor();
    let reach = grid.reach(re);
    let (x, y, z, kind) = (&p.x, &p.y, &p.z, &p.kind);
    out.resize(p.len());
    (&mut out.x, &mut out.y, &mut out.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(256)
        .map(|(i, (ox, oy, oz))| {
            if kind[i] != FLUID {
                (*ox, *oy, *oz) = (0.0, 0.0, 0.0);
                return PassTotals::default();
            }
            let (xi, yi, zi, fi) = (x[i], y[i], z[i], f[i]);
            let mut g = [0.0; 3];
            let mut wall = [0.0; 3];
            let mut seen = 0u64;
            grid.for_each_range(i, reach, |s, e| {
                seen += (e - s) as u64;
                let it = x[s..e]
                    .iter()
                    .zip(&y[s..e])
                    .zip(&z[s..e])
                    .zip(&f[s..e])
                    .zip(&kind[s..e]);
                for ((((&xj, &yj), &zj), &fj), &kj) in it {
                    let (dx, dy, dz) = (xj - xi, yj - yi, zj - zi);
                    let r2 = dx * dx + dy * dy + dz * dz;
                    let r = r2.sqrt();
                    let c = (fj + fi) * (re / r - r * inv_re) / r2;
                    let c = if r2 < re2 && r2 > 0.0 && kj != DUMMY {
                        c
                    } else {
                        0.0
                    };
                    g[0] += c * dx;
                    g[1] += c * dy;
                    g[2] += c * dz;
                    let cw = if kj != FLUID { c } else { 0.0 };
                    wall[0] += cw * dx;
                    wall[1] += cw * dy;
                    wall[2] += cw * dz;
                }
            });
            (*ox, *oy, *oz) = (factor * g[0], factor * g[1], factor * g[2]);
            PassTotals {
                from_non_fluid: wall.map(|v| factor * v),
                candidates: seen,
            }
        })
        .reduce(PassTotals::default, add)
}

/// S1-4: `⟨∇²u⟩_i = 2d/(λ0 n0) Σ_j (u_j − u_i) w(|r_ij|)` for fluid particles i over every
/// neighbour j (walls and dummies have u = 0: no slip). Writes `out` (0 for non-fluid particles).
pub fn laplacian(grid: &CellGrid, kernel: &Kernel, p: &Particles, out: &mut VectorField) -> PassTotals {
    let re = kernel.re;
    let re2 = re * re;
    let inv_re = 1.0 / re;
    let factor = kernel.laplacian_factor();
    let reach = grid.reach(re);
    let (x, y, z, kind) = (&p.x, &p.y, &p.z, &p.kind);
    let (vx, vy, vz) = (&p.vx, &p.vy, &p.vz);
    out.resize(p.len());
    (&mut out.x, &mut out.y, &mut out.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(256)
        .map(|(i, (ox, oy, oz))| {
            if kind[i] != FLUID {
                (*ox, *oy, *oz) = (0.0, 0.0, 0.0);
                return PassTotals::default();
            }
            let (xi, yi, zi) = (x[i], y[i], z[i]);
            let (ui, vi, wi) = (vx[i], vy[i], vz[i]);
            let mut l = [0.0; 3];
            let mut wall = [0.0; 3];
            let mut seen = 0u64;
            grid.for_each_range(i, reach, |s, e| {
                seen += (e - s) as u64;
                for j in s..e {
                    let (dx, dy, dz) = (x[j] - xi, y[j] - yi, z[j] - zi);
                    let r2 = dx * dx + dy * dy + dz * dz;
                    let r = r2.sqrt();
                    let w = (re - r) * (re - r) / r * inv_re;
                    let w = if r2 < re2 && r2 > 0.0 { w } else { 0.0 };
                    let d = [(vx[j] - ui) * w, (vy[j] - vi) * w, (vz[j] - wi) * w];
                    let m = if kind[j] != FLUID { 1.0 } else { 0.0 };
                    for a in 0..3 {
                        l[a] += d[a];
                        wall[a] += m * d[a];
                    }
                }
            });
            (*ox, *oy, *oz) = (factor * l[0], factor * l[1], factor * l[2]);
            PassTotals {
                from_non_fluid: wall.map(|v| factor * v),
                candidates: seen,
            }
        })
        .reduce(PassTotals::default, add)
}
