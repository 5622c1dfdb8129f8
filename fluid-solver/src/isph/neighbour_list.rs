//! The neighbour list of one ISPH step: for every fluid particle and every solid particle with
//! fluid within reach, the indices of the particles within the support r_e, built once per step
//! from the cell grid. Every later pass of the step (density, moments, divergence, PPE assembly,
//! wall pressure, gradient) walks ~60 true neighbours instead of the ~300 candidates of the
//! surrounding cells.

use crate::kind::FLUID;
use crate::neighbour_search::CellGrid;
use crate::particles::Particles;
use rayon::prelude::*;

/// Neighbours of particle i are `index[start[i] .. start[i + 1]]` (i itself excluded).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NeighbourList {
    pub start: Vec<u32>,
    pub index: Vec<u32>,
}

impl NeighbourList {
    /// Rebuilds the list for the particles in the grid's order; returns the candidates examined.
    pub fn build(&mut self, grid: &CellGrid, p: &Particles, radius: f64) -> u64 {
        let reach = grid.reach(radius);
        let r2max = radius * radius;
        let (x, y, z, kind) = (&p.x, &p.y, &p.z, &p.kind);
        let lists: Vec<(Vec<u32>, u64)> = (0..p.len())
            .into_par_iter()
            .with_min_len(512)
            .map(|i| {
                let mut out = Vec::new();
                if kind[i] != FLUID && !grid.fluid_near(i, reach) {
                    return (out, 0);
                }
                let (xi, yi, zi) = (x[i], y[i], z[i]);
                let mut seen = 0u64;
                grid.for_each_range(i, reach, |s, e| {
                    seen += (e - s) as u64;
                    for j in s..e {
                        let (dx, dy, dz) = (x[j] - xi, y[j] - yi, z[j] - zi);
                        let r2 = dx * dx + dy * dy + dz * dz;
                        if r2 < r2max && j != i {
                            out.push(j as u32);
                        }
                    }
                });
                (out, seen)
            })
            .collect();
        self.start.clear();
        self.start.push(0);
        let mut total = 0u32;
        for (l, _) in &lists {
            total += l.len() as u32;
            self.start.push(total);
        }
        self.index.clear();
        self.index.reserve(total as usize);
        let mut seen = 0;
        for (l, s) in lists {
            self.index.extend_from_slice(&l);
            seen += s;
        }
        seen
    }

    /// The neighbours of particle `i`.
    #[inline(always)]
    pub fn of(&self, i: usize) -> &[u32] {
        &self.index[self.start[i] as usize..self.start[i + 1] as usize]
    }

    /// Bytes held.
    pub fn memory_bytes(&self) -> usize {
        4 * (self.start.capacity() + self.index.capacity())
    }
}
