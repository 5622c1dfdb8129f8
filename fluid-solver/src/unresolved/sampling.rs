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
use crate::kind::{Kind, FLUID};
use crate::neighbour_search::{CellGrid, Rows};
use crate::particles::Particles;
use rayon::prelude::*;

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
        .map(|x| sample_at(p, grid, drift, &kernel, spacing.powi(3), [x[0], x[1], x[2]]))
        .collect()
}

/// The flow at `x`; `drift` is the grid's [`CellGrid::drift`] for `p`.
pub fn sample_at(
    p: &Particles,
    grid: &CellGrid,
    drift: f64,
    kernel: &Wendland,
    volume: f64,
    x: [f64; 3],
) -> Sample {
    let dry = Sample {
        velocity: [0.0; 3],
        lambda_min: 0.0,
    };
    let mut u = [0.0; 3];
    let mut weight = 0.0;
    // the moment matrix is symmetric (a radial kernel): its upper triangle
    let mut m = [0.0; 6];
    let gate = Kind::Gate.code();
    // no water within the support: dry, whatever walls are near
    let wet = grid.for_each_near_point_trimmed(p, x, kernel.radius, drift, Rows::AllIfFluid, |j, r2, d| {
        let kind = p.kind[j];
        if kind == gate {
            return;
        }
        let r = r2.sqrt();
        let (value, derivative) = kernel.value_and_derivative(r);
        if kind == FLUID {
            let w = volume * value;
            weight += w;
            u[0] += w * p.vx[j];
            u[1] += w * p.vy[j];
            u[2] += w * p.vz[j];
        }
        if r > 0.0 {
            // V (x_j − x) ⊗ ∇_x W(x − x_j) = −V W'(r)/r (d ⊗ d), d = x_j − x
            let s = -volume * derivative / r;
            for (k, (a, b)) in UPPER.iter().enumerate() {
                m[k] += s * d[*a] * d[*b];
            }
        }
    });

    if !wet || weight <= 0.0 {
        return dry;
    }
    let lambda_min = smallest_eigenvalue(&m);
    Sample {
        velocity: u.map(|c| c / weight),
        lambda_min,
    }
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
