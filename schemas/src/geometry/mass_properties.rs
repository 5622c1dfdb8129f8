//! Volume, centre and inertia of the solid a closed, outward-oriented triangle mesh bounds, by the
//! divergence theorem: the solid is the signed sum of the tetrahedra joining a reference point `r`
//! to each triangle `(a, b, c)` (Eberly, "Polyhedral Mass Properties (Revisited)", Geometric
//! Tools, 2002; Tonon, "Explicit exact formulas for the 3-D tetrahedron inertia tensor in terms of
//! its vertex coordinates", J. Math. Stat. 1(1), 8–11, 2004). With `a, b, c` taken relative to
//! `r` and `d = a · (b × c)` (six times the tetrahedron's signed volume):
//!
//! - volume `V = Σ d / 6`,
//! - first moment `∫ x dV = Σ d (a + b + c) / 24`,
//! - second moment `∫ x xᵀ dV = Σ d (a aᵀ + b bᵀ + c cᵀ + s sᵀ) / 120`, `s = a + b + c`
//!   (Tonon's eq. for a tetrahedron with one vertex at the origin),
//!
//! and the inertia about the centre `c̄` is `I = ρ (tr(C) 𝟙 − C)` with
//! `C = ∫ x xᵀ dV − V c̄ c̄ᵀ` (parallel axes). `r` is the bounding box's centre, which keeps the
//! sums free of the cancellation a mesh far from the origin would bring.

use super::triangle_mesh::TriangleMesh;
use super::vec3::{add, cross, dot, sub};

/// Mass properties of a homogeneous solid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// Volume [m³].
    pub volume: f64,
    /// Mass, `density × volume` [kg].
    pub mass: f64,
    /// Centre of mass (of volume) [m].
    pub centre: [f64; 3],
    /// Inertia tensor about the centre [kg m²]: `I_ij = ∫ ρ (|x|² δ_ij − x_i x_j) dV`, `x`
    /// measured from the centre (so the off-diagonal entries are minus the products of inertia).
    pub inertia: [[f64; 3]; 3],
}

impl TriangleMesh {
    /// The reference point of the volume sums: the bounding box's centre (the origin for an
    /// empty mesh).
    fn reference_point(&self) -> [f64; 3] {
        if self.vertices.is_empty() {
            return [0.0; 3];
        }
        let (lo, hi) = self.aabb();
        std::array::from_fn(|a| 0.5 * (lo[a] + hi[a]))
    }

    /// The signed volume `Σ a · (b × c) / 6` over the triangles (relative to the bounding box's
    /// centre): the enclosed volume of a closed outward-oriented mesh, its negative for an
    /// inverted one.
    ///
    /// # Panics
    /// If an index is out of range ([`check_solid`](Self::check_solid) refuses that).
    pub fn signed_volume(&self) -> f64 {
        let r = self.reference_point();
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.corners(t).map(|v| sub(v, r));
                dot(a, cross(b, c))
            })
            .sum::<f64>()
            / 6.0
    }

    /// Volume, mass, centre and inertia about the centre of the solid the mesh bounds, of uniform
    /// `density` [kg/m³] (module doc for the formulas). Meaningful for a mesh that passes
    /// [`check_solid`](Self::check_solid); a zero volume gives a NaN centre.
    ///
    /// # Panics
    /// If an index is out of range ([`check_solid`](Self::check_solid) refuses that).
    pub fn mass_properties(&self, density: f64) -> MassProperties {
        let r = self.reference_point();
        let mut six_volume = 0.0;
        let mut moment = [0.0; 3]; // × 24
        let mut second = [[0.0; 3]; 3]; // × 120
        for t in 0..self.triangles.len() {
            let [a, b, c] = self.corners(t).map(|v| sub(v, r));
            let d = dot(a, cross(b, c));
            let s = add(add(a, b), c);
            six_volume += d;
            for i in 0..3 {
                moment[i] += d * s[i];
                for j in 0..3 {
                    second[i][j] += d * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
                }
            }
        }
        let volume = six_volume / 6.0;
        let centre_rel = moment.map(|m| m / 24.0 / volume);
        let mut cov = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                cov[i][j] = second[i][j] / 120.0 - volume * centre_rel[i] * centre_rel[j];
            }
        }
        let trace = cov[0][0] + cov[1][1] + cov[2][2];
        let inertia = std::array::from_fn(|i| {
            std::array::from_fn(|j| density * (f64::from(u8::from(i == j)) * trace - cov[i][j]))
        });
        MassProperties {
            volume,
            mass: density * volume,
            centre: add(centre_rel, r),
            inertia,
        }
    }
}
