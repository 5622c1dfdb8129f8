//! A cell list of the particles near a set of query points, for point queries (the step's own
//! cell list answers queries around particles only). Cells are one kernel support wide, so a
//! query visits the 27 cells around its point; particles outside the queries' bounding box
//! (grown by one support) are left out.

use crate::particles::Particles;

/// Particles sorted into cubic cells over the queries' box.
#[derive(Debug, Clone, Default)]
pub struct PointGrid {
    origin: [f64; 3],
    cell: f64,
    dims: [usize; 3],
    /// Particles of cell c are `index[start[c] .. start[c + 1]]`.
    start: Vec<u32>,
    index: Vec<u32>,
}

impl PointGrid {
    /// Sorts the particles that `keep` accepts and that lie within `radius` of the box of
    /// `points` (3 per point) into cells of edge `radius`.
    pub fn build(p: &Particles, keep: impl Fn(usize) -> bool, points: &[f64], radius: f64) -> PointGrid {
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
        let mut dims = [0; 3];
        for a in 0..3 {
            dims[a] = ((hi[a] - lo[a]) / radius).ceil().max(1.0) as usize;
        }
        let mut grid = PointGrid {
            origin: lo,
            cell: radius,
            dims,
            start: vec![0; dims[0] * dims[1] * dims[2] + 1],
            index: Vec::new(),
        };
        let cells: Vec<(u32, u32)> = (0..p.len())
            .filter(|&i| keep(i))
            .filter_map(|i| {
                grid.cell_of([p.x[i], p.y[i], p.z[i]])
                    .map(|c| (c as u32, i as u32))
            })
            .collect();
        for &(c, _) in &cells {
            grid.start[c as usize + 1] += 1;
        }
        for c in 0..grid.start.len() - 1 {
            grid.start[c + 1] += grid.start[c];
        }
        let mut next = grid.start.clone();
        grid.index = vec![0; cells.len()];
        for &(c, i) in &cells {
            grid.index[next[c as usize] as usize] = i;
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

    /// Calls `f(i)` for every kept particle in the 27 cells around `x` (every particle within
    /// one cell edge of `x`, and some farther).
    pub fn for_each_near(&self, x: [f64; 3], mut f: impl FnMut(usize)) {
        if self.start.is_empty() {
            return;
        }
        let base: [i64; 3] = std::array::from_fn(|a| ((x[a] - self.origin[a]) / self.cell).floor() as i64);
        let [nx, ny, nz] = self.dims.map(|d| d as i64);
        for k in (base[2] - 1).max(0)..=(base[2] + 1).min(nz - 1) {
            for j in (base[1] - 1).max(0)..=(base[1] + 1).min(ny - 1) {
                let (i0, i1) = ((base[0] - 1).max(0), (base[0] + 1).min(nx - 1));
                if i0 > i1 {
                    continue;
                }
                let row = (k * ny + j) * nx;
                let (s, e) = (
                    self.start[(row + i0) as usize],
                    self.start[(row + i1 + 1) as usize],
                );
                for &i in &self.index[s as usize..e as usize] {
                    f(i as usize);
                }
            }
        }
    }
}
