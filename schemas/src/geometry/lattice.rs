//! A simple cubic lattice of sites in a box: where wall and fluid particles are placed.

/// Sites at `origin + (i + ½, j + ½, k + ½) spacing` for `i < n[0]`, `j < n[1]`, `k < n[2]`: the
/// centres of the `n[0] × n[1] × n[2]` cubic cells filling the box
/// `[origin, origin + n spacing]` [m].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lattice {
    /// The box's lower corner `[x, y, z]` [m] (half a spacing below the first site).
    pub origin: [f64; 3],
    /// The distance between neighbouring sites, `Δs` [m].
    pub spacing: f64,
    /// Number of sites along x, y and z.
    pub n: [usize; 3],
}

impl Lattice {
    /// Coordinate along `axis` (0 = x, 1 = y, 2 = z) of the sites with index `index` on it,
    /// `origin[axis] + (index + ½) Δs`. Every site coordinate in this module is computed by this
    /// one expression, so a mesh built from them meets the sites exactly.
    pub fn coordinate(&self, axis: usize, index: usize) -> f64 {
        self.origin[axis] + (index as f64 + 0.5) * self.spacing
    }

    /// The centre of site `(i, j, k)`.
    pub fn site_centre(&self, [i, j, k]: [usize; 3]) -> [f64; 3] {
        [
            self.coordinate(0, i),
            self.coordinate(1, j),
            self.coordinate(2, k),
        ]
    }

    /// Number of sites, `n[0] n[1] n[2]` (saturating).
    pub fn site_count(&self) -> usize {
        self.n.iter().fold(1usize, |a, b| a.saturating_mul(*b))
    }

    /// The box's upper corner, `origin + n Δs`.
    pub fn upper_corner(&self) -> [f64; 3] {
        std::array::from_fn(|a| self.origin[a] + self.n[a] as f64 * self.spacing)
    }

    /// Refuses a spacing that is not finite and positive and a non-finite origin (the fills give
    /// no site for such a lattice).
    pub fn check(&self) -> Result<(), String> {
        if !(self.spacing.is_finite() && self.spacing > 0.0) {
            return Err(format!(
                "the lattice spacing must be finite and > 0, got {}",
                self.spacing
            ));
        }
        if !self.origin.iter().all(|c| c.is_finite()) {
            return Err(format!(
                "the lattice origin must be finite, got {:?}",
                self.origin
            ));
        }
        Ok(())
    }

    /// The range of indices `lo..hi` along `axis` whose coordinates lie in `[from, to]`, found
    /// with [`coordinate`](Self::coordinate) itself so that a bound equal to a site's coordinate
    /// includes that site. Empty (`lo ≥ hi`) when none does or a bound is NaN.
    pub fn indices_within(&self, axis: usize, from: f64, to: f64) -> std::ops::Range<usize> {
        let n = self.n[axis];
        if from.partial_cmp(&to).is_none_or(|o| o.is_gt()) || n == 0 {
            return 0..0;
        }
        // first index with coordinate ≥ from
        let mut lo = self.estimate(axis, from).min(n);
        while lo > 0 && self.coordinate(axis, lo - 1) >= from {
            lo -= 1;
        }
        while lo < n && self.coordinate(axis, lo) < from {
            lo += 1;
        }
        // one past the last index with coordinate ≤ to
        let mut hi = self.estimate(axis, to).saturating_add(1).min(n);
        while hi < n && self.coordinate(axis, hi) <= to {
            hi += 1;
        }
        while hi > 0 && self.coordinate(axis, hi - 1) > to {
            hi -= 1;
        }
        lo..hi.max(lo)
    }

    /// `round((value − origin) / Δs − ½)` clamped to `[0, n]`: an index near `value`'s site.
    fn estimate(&self, axis: usize, value: f64) -> usize {
        let u = ((value - self.origin[axis]) / self.spacing - 0.5).round();
        if u.is_nan() || u <= 0.0 {
            0
        } else {
            u.min(self.n[axis] as f64) as usize
        }
    }
}
