//! The neighbour list of one ISPH step: for every fluid particle and every solid particle with
//! fluid within reach, the indices of the particles within the support r_e, built once per step
//! from the cell grid. Every later pass of the step (density, moments, divergence, PPE assembly,
//! wall pressure, gradient) walks ~60 true neighbours instead of the ~300 candidates of the
//! surrounding cells; the cells wholly beyond r_e are not visited
//! ([`CellGrid::for_each_range_within`]).

use crate::kind::FLUID;
use crate::neighbour_search::CellGrid;
use crate::particles::Particles;
use rayon::prelude::*;

/// Particles per block of the parallel build.
const BLOCK: usize = 512;

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
        // Blocks of BLOCK particles, each block's lists contiguous (one allocation per block),
        // then concatenated.
        let n = p.len();
        let blocks: Vec<(Vec<u32>, Vec<u32>, u64)> = (0..n.div_ceil(BLOCK))
            .into_par_iter()
            .map(|b| {
                let (mut index, mut end, mut seen) = (Vec::new(), Vec::new(), 0u64);
                for i in b * BLOCK..((b + 1) * BLOCK).min(n) {
                    if kind[i] == FLUID || grid.fluid_near(i, reach) {
                        let (xi, yi, zi) = (x[i], y[i], z[i]);
                        grid.for_each_range_within(i, [xi, yi, zi], radius, reach, |s, e| {
                            seen += (e - s) as u64;
                            for j in s..e {
                                let (dx, dy, dz) = (x[j] - xi, y[j] - yi, z[j] - zi);
                                let r2 = dx * dx + dy * dy + dz * dz;
                                if r2 < r2max && j != i {
                                    index.push(j as u32);
                                }
                            }
                        });
                    }
                    end.push(index.len() as u32);
                }
                (index, end, seen)
            })
            .collect();
        self.start.clear();
        self.start.push(0);
        self.index.clear();
        let mut seen = 0;
        for (index, end, s) in blocks {
            let offset = self.index.len() as u32;
            self.start.extend(end.iter().map(|e| offset + e));
            self.index.extend_from_slice(&index);
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
