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

use super::kernel::Wendland;
use super::point_grid::PointGrid;
use crate::kind::{Kind, FLUID};
use crate::particles::Particles;
use nalgebra::{Matrix3, SymmetricEigen};
use rayon::prelude::*;

/// The flow at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub velocity: [f64; 3],
    pub lambda_min: f64,
}

/// Samples the flow at `points` (3 per point) for particles of spacing `spacing` (volume Δs³).
pub fn sample(p: &Particles, spacing: f64, points: &[f64]) -> Vec<Sample> {
    let kernel = Wendland::for_spacing(spacing);
    let grid = PointGrid::build(p, |i| p.kind[i] != Kind::Gate.code(), points, kernel.radius);
    points
        .par_chunks_exact(3)
        .with_min_len(64)
        .map(|x| sample_at(p, &grid, &kernel, spacing.powi(3), [x[0], x[1], x[2]]))
        .collect()
}

/// The flow at `x`.
pub fn sample_at(p: &Particles, grid: &PointGrid, kernel: &Wendland, volume: f64, x: [f64; 3]) -> Sample {
    let mut u = [0.0; 3];
    let mut weight = 0.0;
    let mut m = Matrix3::<f64>::zeros();
    grid.for_each_near(x, |j| {
        let d = [p.x[j] - x[0], p.y[j] - x[1], p.z[j] - x[2]];
        let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if r >= kernel.radius {
            return;
        }
        if p.kind[j] == FLUID {
            let w = volume * kernel.value(r);
            weight += w;
            u[0] += w * p.vx[j];
            u[1] += w * p.vy[j];
            u[2] += w * p.vz[j];
        }
        if r > 0.0 {
            // V (x_j − x) ⊗ ∇_x W(x − x_j) = −V W'(r)/r (d ⊗ d), d = x_j − x
            let s = -volume * kernel.derivative(r) / r;
            for a in 0..3 {
                for b in 0..3 {
                    m[(a, b)] += s * d[a] * d[b];
                }
            }
        }
    });
    if weight <= 0.0 {
        return Sample {
            velocity: [0.0; 3],
            lambda_min: 0.0,
        };
    }
    let lambda_min = SymmetricEigen::new(m).eigenvalues.min();
    Sample {
        velocity: u.map(|c| c / weight),
        lambda_min,
    }
}
