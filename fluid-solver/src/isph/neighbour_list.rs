//! The neighbour list of one ISPH step: for every fluid particle and every solid particle with
//! fluid within reach, the indices of the particles within the support r_e, built once per step
//! from the cell grid. Every later pass of the step (density, moments, divergence, PPE assembly,
//! wall pressure, gradient) walks ~60 true neighbours instead of the ~300 candidates of the
//! surrounding cells; the cells wholly beyond r_e are not visited
//! ([`CellGrid::for_each_range_within`]). Each entry keeps its distance as the kernel reads it,
//! q = |x_j − x_i| / r_e ([`super::kernel::Wendland::q`]), computed once here: at S2's scale the
//! passes spent most of their time on the square root, and the density pass fell from 28 to
//! 12.7 ms per step; with the kernel's factors computed once the step went from 3.8e5 to 4.3e5
//! wall fluid-steps/s; keeping q (one multiplication by 1/r_e per pair here, instead of a
//! division by r_e in every pass) took about 10 ms more off the step (2.91 → 2.80 s for
//! `isph_vs_emps -- --s2 0.005 0.004`). q is stored in f32 (relative rounding 6e-8, far below
//! the PPE's tolerance 1e-6): the passes that walk the list are memory-bound, and 8 bytes per
//! pair instead of 12 took S2's step from 4.72–4.77e5 to 4.95–5.00e5 wall fluid-steps/s.

use super::kernel::Wendland;
use crate::neighbours::neighbour_search::{CellGrid, CELL_IN_SPACINGS};
use crate::particles::kind::FLUID;
use crate::particles::Particles;
use rayon::prelude::*;

/// The cell edge of ISPH's grid for a support of `radius_in_spacings`: half the support, so that
/// the list visits 5 × 5 rows of at most 5 cells (3.2e5 → 3.75e5 wall fluid-steps/s at S2's
/// scale, `isph_vs_emps -- --s2`: the 7 × 7 rows of 1.05 Δs cells cost more in row set-up than
/// their closer fit saves; a support of r_e and 1.5 Δs cells were slower), and never below the
/// shared grid's [`CELL_IN_SPACINGS`].
pub fn cell_edge(spacing: f64, radius_in_spacings: f64) -> f64 {
    spacing * (0.5 * radius_in_spacings).max(CELL_IN_SPACINGS)
}

/// Particles per block of the parallel build.
const BLOCK: usize = 512;

/// The neighbour lists of every particle, kept per block of [`BLOCK`] particles: each block is
/// built in place by one rayon task, its buffers reused from step to step (no concatenation, no
/// allocation once the lists have reached their size).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NeighbourList {
    blocks: Vec<Block>,
}

/// Neighbours of the block's k-th particle are `index[start[k] .. start[k + 1]]` (the particle
/// itself excluded), their distances over the support `q[start[k] .. start[k + 1]]`.
#[derive(Debug, Clone, Default, PartialEq)]
struct Block {
    start: Vec<u32>,
    index: Vec<u32>,
    q: Vec<f32>,
}

impl NeighbourList {
    /// Rebuilds the list for the particles in the grid's order; returns the candidates examined.
    pub fn build(&mut self, grid: &CellGrid, p: &Particles, k: &Wendland) -> u64 {
        self.build_listing(grid, p, k, false)
    }

    /// [`Self::build`] with every particle listed, solids with no fluid near included (the
    /// walls' geometry of the GPU path, [`crate::gpu::isph`]).
    pub fn build_every(&mut self, grid: &CellGrid, p: &Particles, k: &Wendland) -> u64 {
        self.build_listing(grid, p, k, true)
    }

    /// [`Self::build`], listing every particle when `every`.
    fn build_listing(&mut self, grid: &CellGrid, p: &Particles, k: &Wendland, every: bool) -> u64 {
        let (k, radius) = (*k, k.radius);
        let reach = grid.reach(radius);
        let r2max = radius * radius;
        let (x, y, z, kind) = (&p.x, &p.y, &p.z, &p.kind);
        let n = p.len();
        self.blocks.resize_with(n.div_ceil(BLOCK), Block::default);
        self.blocks
            .par_iter_mut()
            .enumerate()
            .map(|(b, block)| {
                let (index, start, q) = (&mut block.index, &mut block.start, &mut block.q);
                index.clear();
                q.clear();
                start.clear();
                start.push(0);
                let mut seen = 0u64;
                // Whether fluid is near the last solid's cell (the particles of a cell are
                // consecutive, so each cell is asked once).
                let mut near: Option<(u32, bool)> = None;
                for i in b * BLOCK..((b + 1) * BLOCK).min(n) {
                    let listed = every || kind[i] == FLUID || {
                        let c = grid.cell(i);
                        match near {
                            Some((last, answer)) if last == c => answer,
                            _ => {
                                let answer = grid.fluid_near(i, reach);
                                near = Some((c, answer));
                                answer
                            }
                        }
                    };
                    if listed {
                        let (xi, yi, zi) = (x[i], y[i], z[i]);
                        grid.for_each_range_within(i, [xi, yi, zi], radius, reach, |s, e| {
                            seen += (e - s) as u64;
                            for j in s..e {
                                let (dx, dy, dz) = (x[j] - xi, y[j] - yi, z[j] - zi);
                                let r2 = dx * dx + dy * dy + dz * dz;
                                if r2 < r2max && j != i {
                                    index.push(j as u32);
                                    q.push(r2 as f32); // r / r_e once the row is complete
                                }
                            }
                        });
                    }
                    let first = *start.last().unwrap_or(&0) as usize;
                    q[first..]
                        .iter_mut()
                        .for_each(|d| *d = k.q(f64::from(*d).sqrt()) as f32);
                    start.push(index.len() as u32);
                }
                seen
            })
            .sum()
    }

    /// The neighbours of particle `i`.
    #[inline(always)]
    pub fn of(&self, i: usize) -> &[u32] {
        let b = &self.blocks[i / BLOCK];
        let k = i % BLOCK;
        &b.index[b.start[k] as usize..b.start[k + 1] as usize]
    }

    /// The neighbours j of particle `i` with their q = |x_j − x_i| / r_e.
    #[inline(always)]
    pub fn pairs(&self, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let b = &self.blocks[i / BLOCK];
        let k = i % BLOCK;
        let (s, e) = (b.start[k] as usize, b.start[k + 1] as usize);
        b.index[s..e]
            .iter()
            .zip(&b.q[s..e])
            .map(|(&j, &q)| (j as usize, f64::from(q)))
    }

    /// The q = |x_j − x_i| / r_e of particle `i`'s neighbours, in the order of [`Self::of`].
    #[inline(always)]
    pub fn q(&self, i: usize) -> &[f32] {
        let b = &self.blocks[i / BLOCK];
        let k = i % BLOCK;
        &b.q[b.start[k] as usize..b.start[k + 1] as usize]
    }

    /// Bytes held.
    pub fn memory_bytes(&self) -> usize {
        self.blocks
            .iter()
            .map(|b| 4 * (b.start.capacity() + b.index.capacity()) + 4 * b.q.capacity())
            .sum()
    }
}
