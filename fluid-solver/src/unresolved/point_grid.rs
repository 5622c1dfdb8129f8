//! A cell list of the particles near a set of query points, for point queries (the step's own
//! cell list answers queries around particles only). Cells are half a kernel support wide, so a
//! query visits the 5 × 5 × 5 cells around its point (a box of 2.5 supports: 27 % of it lies in
//! the support's sphere, against 15 % for 3 × 3 × 3 cells of one support); particles outside
//! the queries' bounding box (grown by one support) are left out.

use crate::particles::Particles;

/// Cells each way a query visits.
const REACH: i64 = 2;

/// One particle as a query reads it, stored in cell order (queries read memory straight through).
#[derive(Debug, Clone, Copy, Default)]
pub struct Entry {
    pub position: [f64; 3],
    pub velocity: [f64; 3],
    /// Index in the particle arrays.
    pub index: u32,
    /// Whether `mark` accepted it.
    pub marked: bool,
}

/// Particles sorted into cubic cells over the queries' box.
#[derive(Debug, Clone, Default)]
pub struct PointGrid {
    origin: [f64; 3],
    cell: f64,
    dims: [usize; 3],
    /// Particles of cell c are `entries[start[c] .. start[c + 1]]`.
    start: Vec<u32>,
    entries: Vec<Entry>,
    /// Marked particles (e.g. water) in the cells before cell c.
    marked_before: Vec<u32>,
}

impl PointGrid {
    /// Sorts the particles that `keep` accepts and that lie within `radius` of the box of
    /// `points` (3 per point) into cells of edge `radius / 2`, counting per cell those that
    /// `mark` accepts too.
    pub fn build(
        p: &Particles,
        keep: impl Fn(usize) -> bool,
        mark: impl Fn(usize) -> bool,
        points: &[f64],
        radius: f64,
    ) -> PointGrid {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for q in points.chunks_exact(3) {
            for a in 0..3 {
                lo[a] = lo[a].min(q[a] - radius);
                hi[a] = hi[a].max(q[a] + radius);
            }
        }
        if points.is_empty()
            || radius.is_nan()
            || radius <= 0.0
            || lo.iter().chain(&hi).any(|v| !v.is_finite())
        {
            return PointGrid::default();
        }
        let cell = radius / REACH as f64;
        let mut dims = [0; 3];
        for a in 0..3 {
            dims[a] = ((hi[a] - lo[a]) / cell).ceil().max(1.0) as usize;
        }
        let mut grid = PointGrid {
            origin: lo,
            cell,
            dims,
            start: vec![0; dims[0] * dims[1] * dims[2] + 1],
            entries: Vec::new(),
            marked_before: vec![0; dims[0] * dims[1] * dims[2] + 1],
        };
        let cells: Vec<(u32, u32)> = (0..p.len())
            .filter(|&i| keep(i))
            .filter_map(|i| {
                grid.cell_of([p.x[i], p.y[i], p.z[i]])
                    .map(|c| (c as u32, i as u32))
            })
            .collect();
        for &(c, i) in &cells {
            grid.start[c as usize + 1] += 1;
            grid.marked_before[c as usize + 1] += u32::from(mark(i as usize));
        }
        for c in 0..grid.start.len() - 1 {
            grid.start[c + 1] += grid.start[c];
            grid.marked_before[c + 1] += grid.marked_before[c];
        }
        let mut next = grid.start.clone();
        grid.entries = vec![Entry::default(); cells.len()];
        for &(c, i) in &cells {
            let k = i as usize;
            grid.entries[next[c as usize] as usize] = Entry {
                position: [p.x[k], p.y[k], p.z[k]],
                velocity: [p.vx[k], p.vy[k], p.vz[k]],
                index: i,
                marked: mark(k),
            };
            next[c as usize] += 1;
        }
        grid
    }

    /// The cell of `x`, or None outside the grid.
    fn cell_of(&self, x: [f64; 3]) -> Option<usize> {
        let mut idx = 0;
        let mut stride = 1;
        for ((&xa, &origin), &dim) in x.iter().zip(&self.origin).zip(&self.dims) {
            let c = ((xa - origin) / self.cell).floor();
            if c.is_nan() || c < 0.0 || c as usize >= dim {
                return None;
            }
            idx += c as usize * stride;
            stride *= dim;
        }
        Some(idx)
    }

    /// Calls `f(entry)` for every kept particle in the 5 × 5 × 5 cells around `x` (every
    /// particle within one support of `x`, and some farther).
    pub fn for_each_near(&self, x: [f64; 3], mut f: impl FnMut(&Entry)) {
        self.for_each_row(x, |s, e| {
            self.entries[s as usize..e as usize].iter().for_each(&mut f)
        });
    }

    /// Whether any marked particle lies in the 5 × 5 × 5 cells around `x` (25 look-ups).
    pub fn marked_near(&self, x: [f64; 3]) -> bool {
        let mut any = false;
        self.for_each_cell_row(x, |c0, c1| any |= self.marked_before[c1] > self.marked_before[c0]);
        any
    }

    /// Calls `f(first, end)` with the index range of each row of cells around `x`.
    fn for_each_row(&self, x: [f64; 3], mut f: impl FnMut(u32, u32)) {
        self.for_each_cell_row(x, |c0, c1| f(self.start[c0], self.start[c1]));
    }

    /// Calls `f(first cell, one past the last cell)` for each row (along x) of the 5 × 5 × 5
    /// cells around `x`, clipped to the grid.
    fn for_each_cell_row(&self, x: [f64; 3], mut f: impl FnMut(usize, usize)) {
        if self.start.is_empty() {
            return;
        }
        let base: [i64; 3] = std::array::from_fn(|a| ((x[a] - self.origin[a]) / self.cell).floor() as i64);
        let [nx, ny, nz] = self.dims.map(|d| d as i64);
        for k in (base[2] - REACH).max(0)..=(base[2] + REACH).min(nz - 1) {
            for j in (base[1] - REACH).max(0)..=(base[1] + REACH).min(ny - 1) {
                let (i0, i1) = ((base[0] - REACH).max(0), (base[0] + REACH).min(nx - 1));
                if i0 > i1 {
                    continue;
                }
                let row = (k * ny + j) * nx;
                f((row + i0) as usize, (row + i1 + 1) as usize);
            }
        }
    }
}
