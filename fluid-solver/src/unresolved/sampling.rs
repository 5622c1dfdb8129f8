//! The flow at the drag law's sample points (S2 §4(1)d): velocity by a kernel interpolation
//! normalised over the fluid particles present (Shepard), so a point near the free surface or a
//! wall is not biased low, and λ_min, the smallest eigenvalue of the moment matrix
//! `m = Σ_j V_j (x_j − x) ⊗ ∇W(x − x_j)` (S2-10), which tells how full the point's support is:
//! 1 inside the water, 0.5 on a flat free surface, 0 in the air.
//!
//! Which particles count: the velocity averages water (fluid) particles only — wall particles
//! are at rest and would pull it towards zero; the moment matrix counts every particle that
//! fills space (fluid, walls, bodies, inflow), because a wall is not a free surface and a member
//! standing on the floor is fully submerged. A point with no fluid particle within the support
//! is dry: velocity 0, λ_min 0.
//!
//! Accuracy: a uniform field is interpolated exactly wherever a fluid particle is present (the
//! weights sum to one). A linear field `u = u0 + G·x` comes back as `u0 + G·x̄`, x̄ the kernel-
//! weighted centroid of the particles present, so its error is `G·(x̄ − x)`: at most |G| R
//! anywhere, and inside the water about zero (the centroid of a full, symmetric support is the
//! point itself); see the sampling tests for the bound near a surface or a wall.
//!
//! The particles near a point come from the step's own cell list ([`CellGrid::for_each_near_point_trimmed`]),
//! so no second grid is built: see [`super`] for when that list is valid.

use super::kernel::Wendland;
use super::spreading::{half_width_of, share_of, shares_around, Share};
use crate::neighbours::neighbour_search::{CellGrid, Rows};
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use rayon::prelude::*;
use std::ops::Range;

/// Index pairs of the upper triangle of a 3 × 3 matrix, row by row.
const UPPER: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];

/// The flow at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub velocity: [f64; 3],
    pub lambda_min: f64,
}

/// Samples the flow at `points` (3 per point) for particles of spacing `spacing` (volume Δs³);
/// `grid` is the cell list sorted for `p`.
pub fn sample(p: &Particles, grid: &CellGrid, spacing: f64, points: &[f64]) -> Vec<Sample> {
    let kernel = Wendland::for_spacing(spacing);
    let drift = grid.drift(p);
    points
        .par_chunks_exact(3)
        .with_min_len(64)
        .map_init(Vec::new, |rows, x| {
            let x = [x[0], x[1], x[2]];
            sample_near(p, grid, drift, &kernel, spacing.powi(3), x, None, rows).unwrap_or_else(dry)
        })
        .collect()
}

/// As [`sample`], with the shares of the reactions paired with the points (`reactions`, 6 per
/// point: centroid, force; the force is not read; `widths`, 1 per reaction or empty, their
/// members' widths) over the fluid around their centroids, as [`share_of`] finds them with the
/// point as fall-back, for every wet point (None for a dry one: its sub-member takes no force).
/// The fluid spreads the next step's reactions with them ([`super::spreading::spread_reusing`])
/// when the particles have not moved since and the centroids are the same (a fixed member). A
/// reaction of a member no wider than a particle whose centroid lies within half the kernel's
/// support of its point is served by the point's own search of the cell list, widened by their
/// distance: one search instead of two, and the same particles in the same order as each one's
/// own search (the cell list is read in index order), so the same sums. A wider member's
/// reaction (its footprint, [`super::spreading`]) is searched on its own.
pub fn sample_with_shares(
    p: &Particles,
    grid: &CellGrid,
    spacing: f64,
    points: &[f64],
    reactions: &[f64],
    widths: &[f64],
) -> (Vec<Sample>, Vec<Option<Share>>) {
    if reactions.len() != 2 * points.len() {
        return (sample(p, grid, spacing, points), Vec::new());
    }
    let kernel = Wendland::for_spacing(spacing);
    let drift = grid.drift(p);
    points
        .par_chunks_exact(3)
        .zip(reactions.par_chunks_exact(6))
        .enumerate()
        .with_min_len(64)
        // the index ranges of each point's cells, in one buffer per rayon job
        .map_init(Vec::new, |rows, (k, (x, r))| {
            let (x, c) = ([x[0], x[1], x[2]], [r[0], r[1], r[2]]);
            let apart = (0..3).map(|a| (c[a] - x[a]).powi(2)).sum::<f64>().sqrt();
            let volume = spacing.powi(3);
            let half_width = half_width_of(widths, k, spacing);
            if apart > 0.5 * kernel.radius || half_width > 0.0 {
                let s = sample_near(p, grid, drift, &kernel, volume, x, None, rows).unwrap_or_else(dry);
                let wet = s.velocity != [0.0; 3] || s.lambda_min != 0.0;
                return (
                    s,
                    wet.then(|| share_of(p, grid, drift, &kernel, c, Some(x), half_width)),
                );
            }
            let mut share = ShareSearch {
                centroid: c,
                apart,
                share: Vec::new(),
                sum: 0.0,
            };
            let s = sample_near(p, grid, drift, &kernel, volume, x, Some(&mut share), rows);
            let Some(s) = s else {
                return (dry(), None);
            };
            let ShareSearch { mut share, sum, .. } = share;
            share.iter_mut().for_each(|(_, w)| *w /= sum);
            if share.is_empty() {
                return (s, Some((shares_around(p, grid, drift, &kernel, x, 0.0), true)));
            }
            (s, Some((share, false)))
        })
        .unzip()
}

/// A point with no water within the support.
fn dry() -> Sample {
    Sample {
        velocity: [0.0; 3],
        lambda_min: 0.0,
    }
}

/// The shares of a reaction at `centroid`, `apart` from the sample point, found by the sample
/// point's search: the unnormalised weights `W(x_c − x_k)` of the fluid particles and their sum.
struct ShareSearch {
    centroid: [f64; 3],
    apart: f64,
    share: Vec<(u32, f64)>,
    sum: f64,
}

/// The flow at `x` (None: dry); with `shares`, the search widened by its `apart` also collects
/// the shares around its centroid, in the cell list's order. `rows` is scratch space for the
/// index ranges of the cells to read ([`CellGrid::for_each_row_near_point`]).
#[allow(clippy::too_many_arguments)]
fn sample_near(
    p: &Particles,
    grid: &CellGrid,
    drift: f64,
    kernel: &Wendland,
    volume: f64,
    x: [f64; 3],
    shares: Option<&mut ShareSearch>,
    rows: &mut Vec<Range<usize>>,
) -> Option<Sample> {
    // widened by the centroid's distance, a little more against its rounding
    let reach = match &shares {
        Some(s) if s.apart > 0.0 => kernel.radius + s.apart + 1e-9 * kernel.radius,
        _ => kernel.radius,
    };
    rows.clear();
    // no water within the support: dry, whatever walls are near
    if !grid.for_each_row_near_point(x, reach, drift, Rows::AllIfFluid, |r| rows.push(r)) {
        return None;
    }
    let sums = match shares {
        Some(s) => sums_over::<true>(p, kernel, volume, x, reach, rows, s),
        None => {
            let mut none = ShareSearch {
                centroid: x,
                apart: 0.0,
                share: Vec::new(),
                sum: 0.0,
            };
            sums_over::<false>(p, kernel, volume, x, reach, rows, &mut none)
        }
    };
    let (u, weight, m) = sums;
    if weight <= 0.0 {
        return None;
    }
    let lambda_min = smallest_eigenvalue(&m);
    Some(Sample {
        velocity: u.map(|c| c / weight),
        lambda_min,
    })
}

/// The Shepard sums at `x` over the particles of `rows` within the kernel's support (velocity
/// times weight, weight, the moment matrix's upper triangle), and with `SHARES` the weights of
/// the fluid particles around `shares.centroid` among those within `reach` (the same operations
/// in the same order as a call per particle, so equal sums to the last bit; one loop over the
/// arrays with the sums in registers does both).
fn sums_over<const SHARES: bool>(
    p: &Particles,
    kernel: &Wendland,
    volume: f64,
    x: [f64; 3],
    reach: f64,
    rows: &[Range<usize>],
    shares: &mut ShareSearch,
) -> ([f64; 3], f64, [f64; 6]) {
    let kernel = *kernel;
    let mut u = [0.0; 3];
    let mut weight = 0.0;
    // the moment matrix is symmetric (a radial kernel): its upper triangle
    let mut m = [0.0; 6];
    let gate = Kind::Gate.code();
    let r2max = kernel.radius * kernel.radius;
    let reach2 = reach * reach;
    let c = shares.centroid;
    let mut sum = shares.sum;
    for range in rows {
        let first = range.start;
        let xs = &p.x[range.clone()];
        let n = xs.len();
        let (ys, zs) = (&p.y[range.clone()][..n], &p.z[range.clone()][..n]);
        let kinds = &p.kind[range.clone()][..n];
        let (vx, vy, vz) = (
            &p.vx[range.clone()][..n],
            &p.vy[range.clone()][..n],
            &p.vz[range.clone()][..n],
        );
        for k in 0..n {
            let d = [xs[k] - x[0], ys[k] - x[1], zs[k] - x[2]];
            let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if r2 >= reach2 {
                continue;
            }
            let kind = kinds[k];
            if kind == gate {
                continue;
            }
            if SHARES && kind == FLUID {
                let e = [xs[k] - c[0], ys[k] - c[1], zs[k] - c[2]];
                let rc2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
                if rc2 < r2max {
                    let w = kernel.value(rc2.sqrt());
                    if w > 0.0 {
                        if shares.share.capacity() == 0 {
                            // a full support holds about 60 particles: one allocation
                            shares.share.reserve(96);
                        }
                        shares.share.push(((first + k) as u32, w));
                        sum += w;
                    }
                }
            }
            if r2 >= r2max {
                continue;
            }
            let r = r2.sqrt();
            let (value, derivative) = kernel.value_and_derivative(r);
            if kind == FLUID {
                let w = volume * value;
                weight += w;
                u[0] += w * vx[k];
                u[1] += w * vy[k];
                u[2] += w * vz[k];
            }
            if r > 0.0 {
                // V (x_j − x) ⊗ ∇_x W(x − x_j) = −V W'(r)/r (d ⊗ d), d = x_j − x
                let s = -volume * derivative / r;
                for (k, (a, b)) in UPPER.iter().enumerate() {
                    m[k] += s * d[*a] * d[*b];
                }
            }
        }
    }
    shares.sum = sum;
    (u, weight, m)
}

/// Smallest eigenvalue of the symmetric 3 × 3 matrix with upper triangle `m` (order of
/// [`UPPER`]), in closed form (Smith 1961, Commun. ACM 4(4): the eigenvalues of `q I + p B` are
/// `q + 2p cos(φ + 2πk/3)` with `cos 3φ = det(B)/2`).
pub fn smallest_eigenvalue(m: &[f64; 6]) -> f64 {
    let [a, b, c, d, e, f] = *m; // [[a b c] [b d e] [c e f]]
    let off = b * b + c * c + e * e;
    let q = (a + d + f) / 3.0;
    let p2 = (a - q).powi(2) + (d - q).powi(2) + (f - q).powi(2) + 2.0 * off;
    if p2 <= 1e-30 * (q * q).max(f64::MIN_POSITIVE) {
        return q;
    }
    let p = (p2 / 6.0).sqrt();
    let (ba, bd, bf) = ((a - q) / p, (d - q) / p, (f - q) / p);
    let (bb, bc, be) = (b / p, c / p, e / p);
    let det = ba * (bd * bf - be * be) - bb * (bb * bf - be * bc) + bc * (bb * be - bd * bc);
    let phi = (0.5 * det).clamp(-1.0, 1.0).acos() / 3.0;
    q + 2.0 * p * (phi + 2.0 * std::f64::consts::PI / 3.0).cos()
}
