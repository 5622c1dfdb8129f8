//! A terrain as heights on a regular grid of cell centres, and its height anywhere between them
//! (bilinear). Read from and written to ESRI ASCII grids by [`ascii_grid`](super::ascii_grid).

use super::error::GridError;

/// Heights `z` [m] at the centres of `ncols × nrows` cells of size `spacing` [m]. Column `c`
/// (from the west, from 0) and row `r` (from the SOUTH, from 0; an ESRI file lists the northern
/// row first) has its centre at `first_centre + (c dx, r dy)`.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightGrid {
    ncols: usize,
    nrows: usize,
    first_centre: [f64; 2],
    spacing: [f64; 2],
    /// Row-major from the south-west cell, x fastest.
    heights: Vec<f64>,
}

/// How far outside the centres' hull, in cells, a point still counts as on it (rounding of
/// coordinates computed elsewhere, e.g. a lattice aligned with the grid's outer centres).
const HULL_TOLERANCE: f64 = 1e-9;

impl HeightGrid {
    /// A grid of `ncols × nrows` heights listed row by row from the south-west cell (x fastest),
    /// the south-west cell's centre at `first_centre`, cells `spacing = [dx, dy]` apart.
    /// Refuses no cells, a spacing that is not finite and positive, a non-finite centre, a list of
    /// the wrong length and a non-finite height (naming its column and row from the south).
    pub fn new(
        ncols: usize,
        nrows: usize,
        first_centre: [f64; 2],
        spacing: [f64; 2],
        heights: Vec<f64>,
    ) -> Result<HeightGrid, GridError> {
        if ncols == 0 || nrows == 0 {
            return Err(GridError::new(format!(
                "a grid needs at least one column and one row, got {ncols} × {nrows}"
            )));
        }
        if !spacing.iter().all(|d| d.is_finite() && *d > 0.0) {
            return Err(GridError::new(format!(
                "the cell size must be finite and > 0 along x and y, got {spacing:?}"
            )));
        }
        if !first_centre.iter().all(|c| c.is_finite()) {
            return Err(GridError::new(format!(
                "the first centre must be finite, got {first_centre:?}"
            )));
        }
        let cells = ncols.checked_mul(nrows);
        if cells != Some(heights.len()) {
            return Err(GridError::new(format!(
                "{ncols} × {nrows} cells need {} heights, got {}",
                ncols.saturating_mul(nrows),
                heights.len()
            )));
        }
        let grid = HeightGrid {
            ncols,
            nrows,
            first_centre,
            spacing,
            heights,
        };
        if let Some(n) = grid.heights.iter().position(|h| !h.is_finite()) {
            let (c, r) = (n % ncols, n / ncols);
            let [x, y] = grid.centre(c, r);
            return Err(GridError::new(format!(
                "the height of column {c}, row {r} from the south (x = {x}, y = {y}) is {}: heights \
                 must be finite",
                grid.heights[n]
            )));
        }
        Ok(grid)
    }

    /// A grid whose heights are `f(x, y)` at the cell centres (see [`new`](Self::new)).
    pub fn from_fn(
        ncols: usize,
        nrows: usize,
        first_centre: [f64; 2],
        spacing: [f64; 2],
        f: impl Fn(f64, f64) -> f64,
    ) -> Result<HeightGrid, GridError> {
        let mut heights = Vec::with_capacity(ncols.saturating_mul(nrows).min(1 << 28));
        for r in 0..nrows {
            for c in 0..ncols {
                heights.push(f(
                    first_centre[0] + c as f64 * spacing[0],
                    first_centre[1] + r as f64 * spacing[1],
                ));
            }
        }
        HeightGrid::new(ncols, nrows, first_centre, spacing, heights)
    }

    /// Number of columns (along x).
    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// Number of rows (along y).
    pub fn nrows(&self) -> usize {
        self.nrows
    }

    /// The cell size `[dx, dy]` [m].
    pub fn spacing(&self) -> [f64; 2] {
        self.spacing
    }

    /// The centre `[x, y]` of the cell in column `col` (from the west) and row `row` (from the
    /// south), both from 0.
    pub fn centre(&self, col: usize, row: usize) -> [f64; 2] {
        [
            self.first_centre[0] + col as f64 * self.spacing[0],
            self.first_centre[1] + row as f64 * self.spacing[1],
        ]
    }

    /// The height at the centre of column `col`, row `row` from the south; `None` outside.
    pub fn height(&self, col: usize, row: usize) -> Option<f64> {
        if col < self.ncols && row < self.nrows {
            self.heights.get(row * self.ncols + col).copied()
        } else {
            None
        }
    }

    /// The cells' outer edges `([x_min, y_min], [x_max, y_max])`: what the file's
    /// `xllcorner`, `yllcorner` and `ncols × cellsize`, `nrows × cellsize` describe.
    pub fn extent(&self) -> ([f64; 2], [f64; 2]) {
        let (lo, hi) = self.centres_extent();
        let [dx, dy] = self.spacing;
        (
            [lo[0] - 0.5 * dx, lo[1] - 0.5 * dy],
            [hi[0] + 0.5 * dx, hi[1] + 0.5 * dy],
        )
    }

    /// The hull of the cell centres `([x_min, y_min], [x_max, y_max])`: where
    /// [`height_at`](Self::height_at) gives a height. Half a cell inside [`extent`](Self::extent).
    pub fn centres_extent(&self) -> ([f64; 2], [f64; 2]) {
        (self.first_centre, self.centre(self.ncols - 1, self.nrows - 1))
    }

    /// The lowest height.
    pub fn min_height(&self) -> f64 {
        self.heights.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// The highest height.
    pub fn max_height(&self) -> f64 {
        self.heights.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }

    /// The height at `(x, y)`, bilinear between the four surrounding cell centres:
    /// `h = (1−s)(1−t) h₀₀ + s(1−t) h₁₀ + (1−s) t h₀₁ + s t h₁₁` with `s, t ∈ [0, 1]` the position
    /// within the square of centres. `None` outside the centres' hull
    /// ([`centres_extent`](Self::centres_extent); a point within 1e-9 of a cell of it counts as
    /// on it): the half cell between the outer centres and the outer edges has no height, since
    /// nothing there is known but the edge cells' own values. A grid of one column (row) has
    /// heights only on the line `x` (`y`) of its centres.
    pub fn height_at(&self, x: f64, y: f64) -> Option<f64> {
        let (c, s) = axis_position((x - self.first_centre[0]) / self.spacing[0], self.ncols)?;
        let (r, t) = axis_position((y - self.first_centre[1]) / self.spacing[1], self.nrows)?;
        let h = |dc: usize, dr: usize| {
            let (cc, rr) = ((c + dc).min(self.ncols - 1), (r + dr).min(self.nrows - 1));
            self.heights[rr * self.ncols + cc]
        };
        Some(
            (1.0 - s) * (1.0 - t) * h(0, 0)
                + s * (1.0 - t) * h(1, 0)
                + (1.0 - s) * t * h(0, 1)
                + s * t * h(1, 1),
        )
    }
}

/// The lower centre's index and the fraction in `[0, 1]` towards the next for position `u` (in
/// cells from the first centre) on an axis of `n` centres; `None` outside `[0, n − 1]` (beyond
/// [`HULL_TOLERANCE`]) or for NaN.
fn axis_position(u: f64, n: usize) -> Option<(usize, f64)> {
    let last = (n - 1) as f64;
    if !(u >= -HULL_TOLERANCE && u <= last + HULL_TOLERANCE) {
        return None;
    }
    let u = u.clamp(0.0, last);
    if n == 1 {
        return Some((0, 0.0));
    }
    let i = (u.floor() as usize).min(n - 2);
    Some((i, u - i as f64))
}
