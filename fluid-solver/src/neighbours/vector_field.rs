//! A per-particle vector as three arrays, and the totals a pass over the pairs returns (the part
//! non-fluid neighbours contributed, the candidates examined): shared by both methods' passes.

/// Three arrays of a per-particle vector (x, y, z components).
#[derive(Debug, Clone, Default)]
pub struct VectorField {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub z: Vec<f64>,
}

impl VectorField {
    /// Resizes to `n` particles (values unspecified until a pass writes them).
    pub fn resize(&mut self, n: usize) {
        self.x.resize(n, 0.0);
        self.y.resize(n, 0.0);
        self.z.resize(n, 0.0);
    }
}

/// Sum of a vector pass over particles, with the part that non-fluid neighbours contributed.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PassTotals {
    /// Σ over fluid particles i of the contributions of their non-fluid neighbours j.
    pub from_non_fluid: [f64; 3],
    /// Neighbour candidates examined (distance evaluations).
    pub candidates: u64,
}

pub fn add(a: PassTotals, b: PassTotals) -> PassTotals {
    PassTotals {
        from_non_fluid: [
            a.from_non_fluid[0] + b.from_non_fluid[0],
            a.from_non_fluid[1] + b.from_non_fluid[1],
            a.from_non_fluid[2] + b.from_non_fluid[2],
        ],
        candidates: a.candidates + b.candidates,
    }
}
