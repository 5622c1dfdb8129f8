//! Interacting pairs: how many (fluid particle, neighbour) pairs lie within a radius, the count
//! GPU SPH codes report per second as GPIPS (giga particle interactions per second). A pair pass
//! over the fluid (number density, pressure gradient, Laplacian) sums one term per such pair.

use super::neighbour_search::CellGrid;
use crate::particles::kind::FLUID;
use crate::particles::Particles;
use rayon::prelude::*;

/// Directed pairs (i, j), i a fluid particle and j any other particle, closer than `radius`, in
/// `p` sorted by `grid` ([`CellGrid::sort`]).
pub fn interacting_pairs(p: &Particles, grid: &CellGrid, radius: f64) -> u64 {
    let reach = grid.reach(radius);
    let r2 = radius * radius;
    (0..p.len())
        .into_par_iter()
        .with_min_len(1024)
        .filter(|&i| p.kind[i] == FLUID)
        .map(|i| {
            let mut near = 0u64;
            grid.for_each_range(i, reach, |begin, end| {
                for j in begin..end {
                    let d = [p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i]];
                    let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                    if j != i && d2 < r2 {
                        near += 1;
                    }
                }
            });
            near
        })
        .sum()
}
