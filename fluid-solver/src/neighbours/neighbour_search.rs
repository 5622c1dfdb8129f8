//! Neighbour search by cell lists, rebuilt every step.
//!
//! The domain is cut into cubic cells of 1.05 Δs (r_e,grad / 2, and ≥ r_e / 3), so E-MPS's
//! gradient looks 2 cells and its number density 3 cells each way (ISPH's grid has cells of half
//! its support, [`crate::isph::neighbour_list::cell_edge`], so its list looks 2 cells each way). A counting sort by cell index (x
//! fastest) reorders the particles, so a run of cells along x is one contiguous index range:
//! a neighbour query visits (2·reach + 1)² ranges, each read straight through memory. A
//! running count of fluid particles per cell tells in (2·reach + 1)² look-ups whether a wall
//! particle has any water near it.

use crate::particles::kind::FLUID;
use crate::particles::Particles;
use rayon::prelude::*;

/// Cell edge in spacings.
pub const CELL_IN_SPACINGS: f64 = 1.05;
/// Empty cells kept around the domain so that no query needs a bounds check.
pub const PAD: usize = 3;
/// Cells each way up to which [`CellGrid::for_each_row_near_point`] keeps its rows' distances in
/// a table (3 at the drag samples' 2.4 Δs support; wider searches compute them per row).
const MAX_ROW_REACH: usize = 7;

/// A uniform grid of cells over a box, with the particles sorted by cell.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CellGrid {
    origin: [f64; 3],
    inv_cell: f64,
    cell: f64,
    dims: [usize; 3],
    /// Particles of cell c are `start[c] .. start[c + 1]` (after [`CellGrid::sort`]).
    start: Vec<u32>,
    /// Cell index of each particle, in the sorted order.
    cell_of: Vec<u32>,
    /// Sorting permutation: sorted index → previous index.
    perm: Vec<u32>,
    /// Fluid particles in the cells before cell c (after [`CellGrid::sort`]).
    fluid_before: Vec<u32>,
}

impl CellGrid {
    /// A grid covering `[lo, hi]` for particles of spacing `spacing`.
    pub fn new(lo: [f64; 3], hi: [f64; 3], spacing: f64) -> CellGrid {
        CellGrid::with_cell(lo, hi, CELL_IN_SPACINGS * spacing)
    }

    /// A grid covering `[lo, hi]` with cells of edge `cell`, which should be at least
    /// [`CELL_IN_SPACINGS`] Δs: the [`PAD`] cells of padding then hold every query within 3.15 Δs.
    pub fn with_cell(lo: [f64; 3], hi: [f64; 3], cell: f64) -> CellGrid {
        let mut dims = [0; 3];
        let mut origin = [0.0; 3];
        for a in 0..3 {
            dims[a] = ((hi[a] - lo[a]) / cell).ceil().max(1.0) as usize + 2 * PAD;
            origin[a] = lo[a] - PAD as f64 * cell;
        }
        let cells = dims[0] * dims[1] * dims[2];
        CellGrid {
            origin,
            inv_cell: 1.0 / cell,
            cell,
            dims,
            start: vec![0; cells + 1],
            cell_of: Vec::new(),
            perm: Vec::new(),
            fluid_before: vec![0; cells + 1],
        }
    }

    /// The same box with cells `extra` wider (the GPU's wide positions: gpu/frame.rs); the
    /// particles must be sorted again.
    pub fn widened(&self, extra: f64) -> CellGrid {
        let lo = self.origin.map(|o| o + PAD as f64 * self.cell);
        let hi: [f64; 3] = std::array::from_fn(|a| lo[a] + (self.dims[a] - 2 * PAD) as f64 * self.cell);
        CellGrid::with_cell(lo, hi, self.cell + extra)
    }

    /// The grid's origin (corner of its first cell, padding included), cell edge and cells per
    /// axis (x fastest): what the GPU's cell sort copies.
    pub fn geometry(&self) -> ([f64; 3], f64, [usize; 3]) {
        (self.origin, self.cell, self.dims)
    }

    /// Number of cells, padding included.
    pub fn cell_count(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }

    /// Bytes held by the grid.
    pub fn memory_bytes(&self) -> usize {
        4 * (self.start.capacity()
            + self.cell_of.capacity()
            + self.perm.capacity()
            + self.fluid_before.capacity())
    }

    /// Cells each way needed to see every neighbour within `radius`.
    pub fn reach(&self, radius: f64) -> usize {
        ((radius / self.cell) - 1e-9).ceil() as usize
    }

    /// Cell index of a point; points outside the grid are clamped onto its inner border.
    #[inline]
    fn cell_index(&self, p: [f64; 3]) -> u32 {
        let mut idx = 0;
        let mut stride = 1;
        for ((&pa, &origin), &dim) in p.iter().zip(&self.origin).zip(&self.dims) {
            let c = ((pa - origin) * self.inv_cell).floor();
            let c = (c.max(PAD as f64) as usize).min(dim - PAD - 1);
            idx += c * stride;
            stride *= dim;
        }
        idx as u32
    }

    /// Counting sort of the particles by cell; reorders every particle array and fills the
    /// cell ranges.
    pub fn sort(&mut self, p: &mut Particles, scratch: &mut Vec<f64>) {
        let n = p.len();
        let mut cells = std::mem::take(&mut self.cell_of);
        cells.resize(n, 0);
        cells
            .par_iter_mut()
            .enumerate()
            .with_min_len(4096)
            .for_each(|(i, c)| *c = self.cell_index([p.x[i], p.y[i], p.z[i]]));
        // Counts per cell, summed into each cell's end; the scatter runs backwards and takes each
        // end down to its cell's start (stable, and no pass to shift the ends back).
        self.start.fill(0);
        for &c in &cells {
            self.start[c as usize] += 1;
        }
        running_sum(&mut self.start);
        self.perm.resize(n, 0);
        for (i, &c) in cells.iter().enumerate().rev() {
            let slot = &mut self.start[c as usize];
            *slot -= 1;
            self.perm[*slot as usize] = i as u32;
        }
        let perm = &self.perm;
        self.cell_of.resize(n, 0);
        self.cell_of
            .par_iter_mut()
            .zip(perm.par_iter())
            .with_min_len(4096)
            .for_each(|(c, &j)| *c = cells[j as usize]);
        p.permute(&self.perm, scratch);
        self.fluid_before.fill(0);
        for (&c, &k) in self.cell_of.iter().zip(&p.kind) {
            if k == FLUID {
                self.fluid_before[c as usize + 1] += 1;
            }
        }
        running_sum(&mut self.fluid_before);
    }

    /// The cell of particle `i` (after [`CellGrid::sort`]).
    #[inline(always)]
    pub fn cell(&self, i: usize) -> u32 {
        self.cell_of[i]
    }

    /// Whether any fluid particle lies in the cells within `reach` of particle `i`'s cell.
    pub fn fluid_near(&self, i: usize, reach: usize) -> bool {
        let mut any = false;
        self.for_each_cell_range(i, reach, |lo, hi| {
            any |= self.fluid_before[hi] > self.fluid_before[lo]
        });
        any
    }

    /// Calls `f(begin, end)` for each contiguous index range of the cells within `reach` of
    /// particle `i`'s cell (valid after [`CellGrid::sort`], until particles are added or removed).
    #[inline(always)]
    pub fn for_each_range(&self, i: usize, reach: usize, mut f: impl FnMut(usize, usize)) {
        self.for_each_cell_range(i, reach, |lo, hi| {
            f(self.start[lo] as usize, self.start[hi] as usize)
        });
    }

    /// As [`CellGrid::for_each_range`] for particle `i` at `at`, leaving out the cells whose box
    /// lies `radius` or farther from `at` (whole rows of cells, and the ends of the others): in
    /// 3D about 2.5× fewer candidates at r_e = 2.4 Δs. Every particle closer than `radius` is
    /// still in a visited range: a particle clamped onto the border cells lies beyond its cell's
    /// box, farther from an inner point than the box, and a clamped `at` visits every range.
    #[inline(always)]
    pub fn for_each_range_within(
        &self,
        i: usize,
        at: [f64; 3],
        radius: f64,
        reach: usize,
        mut f: impl FnMut(usize, usize),
    ) {
        let c = self.cell_of[i] as usize;
        let nx = self.dims[0];
        let nxy = nx * self.dims[1];
        let cc = [c % nx, (c / nx) % self.dims[1], c / nxy];
        let u: [f64; 3] = std::array::from_fn(|a| (at[a] - self.origin[a]) * self.inv_cell);
        if (0..3).any(|a| u[a].floor() != cc[a] as f64) {
            return self.for_each_range(i, reach, f);
        }
        // Squared distance (in cells) from `at` to the cells at offset o along axis a.
        let gap2 = |a: usize, o: i64| {
            let k = cc[a] as f64 + o as f64;
            let g = if o < 0 {
                u[a] - (k + 1.0)
            } else if o > 0 {
                k - u[a]
            } else {
                0.0
            };
            g * g
        };
        let rr = (radius * self.inv_cell).powi(2) * (1.0 + 1e-9);
        let r = reach as i64;
        for dz in -r..=r {
            let gz = gap2(2, dz);
            if gz > rr {
                continue;
            }
            for dy in -r..=r {
                let rest = rr - gz - gap2(1, dy);
                if rest < 0.0 {
                    continue;
                }
                let lo = (-r..=0).find(|&o| gap2(0, o) <= rest).unwrap_or(0);
                let hi = (0..=r).rev().find(|&o| gap2(0, o) <= rest).unwrap_or(0);
                let row = ((cc[2] as i64 + dz) as usize) * nxy + ((cc[1] as i64 + dy) as usize) * nx;
                let (a, b) = (
                    row + (cc[0] as i64 + lo) as usize,
                    row + (cc[0] as i64 + hi) as usize + 1,
                );
                f(self.start[a] as usize, self.start[b] as usize);
            }
        }
    }

    /// Calls `f(j, |r_j − at|²)` for every particle j within `radius` of the point `at` (strictly
    /// closer; valid after [`CellGrid::sort`], until particles are added or removed). `at` may be
    /// any point: one outside the grid sees the particles of the border cells within `radius`
    /// (spray above the grid is kept in its top layer, see [`crate::particles::layout::GRID_HEADROOM`]).
    /// Used for sampling the fluid at points that are not particles (probes, coupling samples).
    pub fn for_each_near_point(
        &self,
        p: &Particles,
        at: [f64; 3],
        radius: f64,
        mut f: impl FnMut(usize, f64),
    ) {
        let reach = self.reach(radius) as i64;
        let centre = self.cell_index(at) as usize;
        let nx = self.dims[0];
        let nxy = nx * self.dims[1];
        let c = [centre % nx, (centre / nx) % self.dims[1], centre / nxy];
        let r2max = radius * radius;
        let span = |a: usize| {
            let lo = (c[a] as i64 - reach).max(0) as usize;
            let hi = (c[a] as i64 + reach).min(self.dims[a] as i64 - 1) as usize;
            (lo, hi)
        };
        let ((x0, x1), (y0, y1), (z0, z1)) = (span(0), span(1), span(2));
        for cz in z0..=z1 {
            for cy in y0..=y1 {
                let row = cz * nxy + cy * nx;
                for j in self.start[row + x0] as usize..self.start[row + x1 + 1] as usize {
                    let d = [p.x[j] - at[0], p.y[j] - at[1], p.z[j] - at[2]];
                    let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                    if r2 < r2max {
                        f(j, r2);
                    }
                }
            }
        }
    }

    /// How far the particles have moved out of the cells they were sorted into: the largest
    /// distance, along any axis, from a particle to its cell's box [m] (0 right after
    /// [`CellGrid::sort`]; a particle outside the grid, kept in a border cell, counts its whole
    /// distance). One pass over the particles, shared by every point query of a call.
    pub fn drift(&self, p: &Particles) -> f64 {
        const CHUNK: usize = 4096;
        let (nx, ny, nz) = (self.dims[0] as i64, self.dims[1] as i64, self.dims[2] as i64);
        let n = p.len().min(self.cell_of.len());
        let (xs, ys, zs, cells) = (&p.x[..n], &p.y[..n], &p.z[..n], &self.cell_of[..n]);
        // i within [PAD, dim − PAD): the cells a sorted particle can be in
        let inner = |i: i64, dim: i64| ((i - PAD as i64) as u64) < (dim - 2 * PAD as i64) as u64;
        // a straight loop per chunk, not a call per particle (the drag cost bench, 110 072
        // particles: 13.4 M instructions a pass before, 10.1 M now; most particles have left
        // their cell a little since the sort and take `outside_cell`)
        (0..n.div_ceil(CHUNK))
            .into_par_iter()
            .map(|k| {
                let r = k * CHUNK..((k + 1) * CHUNK).min(n);
                let mut out: f64 = 0.0;
                for (((&x, &y), &z), &c) in xs[r.clone()]
                    .iter()
                    .zip(&ys[r.clone()])
                    .zip(&zs[r.clone()])
                    .zip(&cells[r])
                {
                    let (i, j, k) = (self.coord(0, x), self.coord(1, y), self.coord(2, z));
                    if inner(i, nx)
                        && inner(j, ny)
                        && inner(k, nz)
                        && i + j * nx + k * nx * ny == i64::from(c)
                    {
                        continue;
                    }
                    out = out.max(self.outside_cell(c as usize, [x, y, z]));
                }
                out
            })
            .reduce(|| 0.0, f64::max)
    }

    /// The distance, along any axis, from the point `at` to the box of cell `c` (≤ 0 inside it).
    fn outside_cell(&self, c: usize, at: [f64; 3]) -> f64 {
        let nx = self.dims[0];
        let cell = [c % nx, (c / nx) % self.dims[1], c / (nx * self.dims[1])];
        let mut out: f64 = 0.0;
        for (a, pa) in at.into_iter().enumerate() {
            let lo = self.origin[a] + cell[a] as f64 * self.cell;
            out = out.max(lo - pa).max(pa - lo - self.cell);
        }
        out
    }

    /// Cell coordinate of position `v` along axis `a`, unclamped (a floor without a libm call).
    #[inline(always)]
    fn coord(&self, a: usize, v: f64) -> i64 {
        let t = (v - self.origin[a]) * self.inv_cell;
        let i = t as i64;
        i - i64::from((i as f64) > t)
    }

    /// As [`CellGrid::for_each_near_point`], visiting only the cells that can hold a particle
    /// within `radius` of `at` given that no particle is farther than `drift` ([`CellGrid::drift`])
    /// from its cell: along each axis the cells covering `at ± (radius + drift)`, and in each
    /// non-empty row along x only the cells within `√(radius² − d_yz²) + drift`, d_yz the row's
    /// distance across x (rows with d_yz ≥ radius are skipped). Never more than the 7³ block of
    /// [`CellGrid::for_each_near_point`], and the same particles in the same order wherever that
    /// block sees all of them, so sums over them are equal to the last bit. `rows`: which rows
    /// are read ([`Rows`]); `f(j, r², x_j − at)`. Returns whether any row was read.
    pub fn for_each_near_point_trimmed(
        &self,
        p: &Particles,
        at: [f64; 3],
        radius: f64,
        drift: f64,
        rows: Rows,
        mut f: impl FnMut(usize, f64, [f64; 3]),
    ) -> bool {
        let r2max = radius * radius;
        self.for_each_row_near_point(at, radius, drift, rows, |range| {
            let (xs, ys, zs) = (&p.x[range.clone()], &p.y[range.clone()], &p.z[range.clone()]);
            for (k, ((x, y), z)) in xs.iter().zip(ys).zip(zs).enumerate() {
                let d = [x - at[0], y - at[1], z - at[2]];
                let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                if r2 < r2max {
                    f(range.start + k, r2, d);
                }
            }
        })
    }

    /// The index ranges that [`CellGrid::for_each_near_point_trimmed`] reads (one per row of
    /// cells along x, in increasing order), for a caller that runs its own loop over the
    /// particles of each (the drag law's samples: one pass over several arrays, no call per
    /// particle). Every particle within `radius` of `at` is in one of them, with others farther
    /// away. Returns whether any range was read.
    pub fn for_each_row_near_point(
        &self,
        at: [f64; 3],
        radius: f64,
        drift: f64,
        rows: Rows,
        mut f: impl FnMut(std::ops::Range<usize>),
    ) -> bool {
        let reach = self.reach(radius) as i64;
        let nx = self.dims[0];
        let nxy = nx * self.dims[1];
        // the coordinates of `at`'s cell, clamped as `cell_index` does (the same floor, no libm call)
        let c = [0, 1, 2].map(|a| {
            self.coord(a, at[a])
                .clamp(PAD as i64, (self.dims[a] - PAD - 1) as i64) as usize
        });
        let r2max = radius * radius;
        // a margin for the rounding of cell borders
        let drift = drift + 1e-9 * self.cell;
        // cells along axis a whose box, widened by `drift`, comes within `half` of `at`, within
        // the block of `reach` around the centre cell
        let span = |a: usize, half: f64| {
            let lo = (c[a] as i64 - reach).max(self.coord(a, at[a] - half - drift));
            let hi = (c[a] as i64 + reach).min(self.coord(a, at[a] + half + drift));
            (lo.max(0) as usize, hi.min(self.dims[a] as i64 - 1))
        };
        // squared distance from `at` along axis a to cell i's box widened by `drift`
        let gap2 = |a: usize, i: usize| {
            let lo = self.origin[a] + i as f64 * self.cell - drift;
            let hi = lo + self.cell + 2.0 * drift;
            let g = if at[a] < lo {
                lo - at[a]
            } else if at[a] > hi {
                at[a] - hi
            } else {
                0.0
            };
            g * g
        };
        let (x0, x1) = span(0, radius);
        let ((y0, y1), (z0, z1)) = (span(1, radius), span(2, radius));
        if x1 < x0 as i64 || y1 < y0 as i64 || z1 < z0 as i64 {
            return false;
        }
        let (x1, y1, z1) = (x1 as usize, y1 as usize, z1 as usize);
        if rows == Rows::AllIfFluid && !self.fluid_in_block([x0, x1], [y0, y1], [z0, z1]) {
            return false;
        }
        // the rows' squared distances across y, once per point (at most 2 reach + 1 of them)
        let mut gy2 = [0.0; 2 * MAX_ROW_REACH + 1];
        let per_row = y1 - y0 < gy2.len();
        if per_row {
            (y0..=y1).for_each(|cy| gy2[cy - y0] = gap2(1, cy));
        }
        let mut read = false;
        for cz in z0..=z1 {
            let gz2 = gap2(2, cz);
            if gz2 >= r2max {
                continue;
            }
            for cy in y0..=y1 {
                let across = gz2 + if per_row { gy2[cy - y0] } else { gap2(1, cy) };
                if across >= r2max {
                    continue;
                }
                let row = cz * nxy + cy * nx;
                let (lo, hi) = (row + x0, row + x1 + 1);
                if self.start[lo] == self.start[hi]
                    || (rows == Rows::Fluid && self.fluid_before[lo] == self.fluid_before[hi])
                {
                    continue;
                }
                let (a, b) = span(0, (r2max - across).sqrt());
                if b < a as i64 {
                    continue;
                }
                read = true;
                f(self.start[row + a] as usize..self.start[row + b as usize + 1] as usize);
            }
        }
        read
    }

    /// Whether a fluid particle is in the block of cells `x[0] ..= x[1]` × `y` × `z`: first
    /// over each plane's index range from the block's first row to its last (whole rows of the
    /// grid between them: a plane without water anywhere there says no for its rows at once),
    /// then row by row in the planes that may hold some (the drag cost bench, mostly dry
    /// points: 2.9 M instructions a sampling call less than row by row alone).
    fn fluid_in_block(&self, x: [usize; 2], y: [usize; 2], z: [usize; 2]) -> bool {
        let nx = self.dims[0];
        let nxy = nx * self.dims[1];
        let fluid = |lo: usize, hi: usize| self.fluid_before[hi] > self.fluid_before[lo];
        for cz in z[0]..=z[1] {
            let plane = cz * nxy;
            if !fluid(plane + y[0] * nx + x[0], plane + y[1] * nx + x[1] + 1) {
                continue;
            }
            for cy in y[0]..=y[1] {
                let row = plane + cy * nx;
                if fluid(row + x[0], row + x[1] + 1) {
                    return true;
                }
            }
        }
        false
    }

    /// The particles within `radius` of the point `at` (see [`CellGrid::for_each_near_point`]).
    pub fn particles_near(&self, p: &Particles, at: [f64; 3], radius: f64) -> Vec<usize> {
        let mut out = Vec::new();
        self.for_each_near_point(p, at, radius, |j, _| out.push(j));
        out
    }

    /// Calls `f(first cell, one past the last cell)` for each run of cells along x within
    /// `reach` of particle `i`'s cell.
    #[inline(always)]
    fn for_each_cell_range(&self, i: usize, reach: usize, mut f: impl FnMut(usize, usize)) {
        let c = self.cell_of[i] as usize;
        let nx = self.dims[0];
        let nxy = nx * self.dims[1];
        for dz in 0..=2 * reach {
            for dy in 0..=2 * reach {
                let row = c + dz * nxy + dy * nx;
                let lo = row - reach * nxy - reach * nx - reach;
                f(lo, lo + 2 * reach + 1);
            }
        }
    }
}

/// Which rows of cells a point query ([`CellGrid::for_each_near_point_trimmed`]) reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rows {
    /// Every row holding a particle.
    All,
    /// Only rows holding a fluid particle (sums over water only).
    Fluid,
    /// Every row holding a particle, but none when no fluid particle is in the block of cells
    /// (sums over every particle that mean nothing without water: the drag law's samples).
    AllIfFluid,
}

/// `v[c] ← v[0] + … + v[c]`, the sum carried in a register (a loop that reads back the entry it
/// just stored took 3.3 ms over S2's 1.3 million cells, about 5 cycles a cell).
fn running_sum(v: &mut [u32]) {
    let mut sum = 0;
    for e in v {
        sum += *e;
        *e = sum;
    }
}
