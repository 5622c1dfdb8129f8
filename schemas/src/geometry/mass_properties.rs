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

#[cfg(test)]
mod tests {
    use super::super::triangle_mesh::rotation_matrix;
    use super::super::vec3::mat_mul;
    use super::*;

    fn assert_matrix(got: [[f64; 3]; 3], want: [[f64; 3]; 3], tol: f64) {
        for i in 0..3 {
            for j in 0..3 {
                assert!(
                    (got[i][j] - want[i][j]).abs() <= tol,
                    "entry ({i}, {j}): {got:?} against {want:?}"
                );
            }
        }
    }

    fn diagonal(d: [f64; 3]) -> [[f64; 3]; 3] {
        [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]]
    }

    #[test]
    fn unit_cube() {
        let p = TriangleMesh::cuboid([0.0; 3], [1.0; 3]).mass_properties(1000.0);
        assert!((p.volume - 1.0).abs() < 1e-14);
        assert!((p.mass - 1000.0).abs() < 1e-11);
        assert_eq!(p.centre, [0.5; 3]);
        assert_matrix(p.inertia, diagonal([1000.0 / 6.0; 3]), 1e-11);
    }

    #[test]
    fn box_offset_from_the_origin() {
        // a 1 × 2 × 3 box far from the origin: I_xx = m (2² + 3²) / 12 and so on
        let min = [100.0, -200.0, 50.0];
        let p = TriangleMesh::cuboid(min, [101.0, -198.0, 53.0]).mass_properties(2.0);
        let m = 12.0;
        assert!((p.mass - m).abs() < 1e-10);
        let centre = [100.5, -199.0, 51.5];
        assert!(
            (0..3).all(|a| (p.centre[a] - centre[a]).abs() < 1e-12),
            "{:?}",
            p.centre
        );
        assert_matrix(
            p.inertia,
            diagonal([m * 13.0 / 12.0, m * 10.0 / 12.0, m * 5.0 / 12.0]),
            1e-10,
        );
    }

    #[test]
    fn rotated_box_has_the_inertia_rotated() {
        let rotate = [30.0, -20.0, 75.0];
        let body = TriangleMesh::cuboid([-0.5, -1.0, -1.5], [0.5, 1.0, 1.5]);
        let p = body
            .transformed([1.0; 3], rotate, [3.0, 4.0, 5.0])
            .mass_properties(1.0);
        let m = 6.0;
        let r = rotation_matrix(rotate);
        let rt = std::array::from_fn(|i| std::array::from_fn(|j| r[j][i]));
        let want = mat_mul(
            &r,
            &mat_mul(&diagonal([m * 13.0 / 12.0, m * 10.0 / 12.0, m * 5.0 / 12.0]), &rt),
        );
        assert_matrix(p.inertia, want, 1e-12);
        assert!((0..3).all(|a| (p.centre[a] - [3.0, 4.0, 5.0][a]).abs() < 1e-13));
        // a mirrored box has the same volume, mass and inertia
        let q = body
            .transformed([-1.0, 1.0, 1.0], rotate, [3.0, 4.0, 5.0])
            .mass_properties(1.0);
        assert!((q.volume - 6.0).abs() < 1e-12);
        assert_matrix(q.inertia, want, 1e-12);
    }

    /// The tetrahedron `p` as a closed mesh of its four faces, outward.
    fn tetrahedron(p: [[f64; 3]; 4]) -> TriangleMesh {
        let mut mesh = TriangleMesh {
            vertices: p.to_vec(),
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        };
        if mesh.signed_volume() < 0.0 {
            for t in &mut mesh.triangles {
                t.swap(1, 2);
            }
        }
        mesh
    }

    #[test]
    fn corner_tetrahedron_closed_form() {
        // (0,0,0), e_x, e_y, e_z: V = 1/6, centre 1/4, ∫x² dV = 1/60, ∫xy dV = 1/120, so about the
        // centre I_xx = 2/60 − V (2/16) = 1/80 and I_xy = −(1/120 − V/16) = 1/480
        let mesh = tetrahedron([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        assert_eq!(mesh.check_solid(), Ok(()));
        let p = mesh.mass_properties(1.0);
        assert!((p.volume - 1.0 / 6.0).abs() < 1e-15);
        assert!((0..3).all(|a| (p.centre[a] - 0.25).abs() < 1e-15));
        let (d, o) = (1.0 / 80.0, 1.0 / 480.0);
        assert_matrix(p.inertia, [[d, o, o], [o, d, o], [o, o, d]], 1e-15);
    }

    #[test]
    fn tonon_2004_example() {
        // Tonon (2004), the numerical example: density 1
        let mesh = tetrahedron([
            [8.33220, -11.86875, 0.93355],
            [0.75523, 5.00000, 16.37072],
            [52.61236, 5.00000, -5.38580],
            [2.00000, 5.00000, 3.00000],
        ]);
        let p = mesh.mass_properties(1.0);
        // the paper's values come from its vertices as printed, to 5 decimals: agreement to 1e-6
        assert!((p.volume / 1873.233236 - 1.0).abs() < 1e-6, "{}", p.volume);
        // the paper prints x = 15.92492; the vertices' mean is 15.9249475
        let centre = [15.92492, 0.78281, 3.72962];
        assert!(
            (0..3).all(|a| (p.centre[a] - centre[a]).abs() < 5e-5),
            "{:?}",
            p.centre
        );
        let (a, b, c) = (43520.33257, 194711.28938, 191168.76173);
        // a' = ∫yz, b' = ∫xz, c' = ∫xy about the centre (the paper's eq. 9); its printed matrix
        // E_Q swaps b' and c'
        let (a1, b1, c1) = (4417.66150, -46343.16662, 11996.20119);
        let want = [[a, -c1, -b1], [-c1, b, -a1], [-b1, -a1, c]];
        assert_matrix(p.inertia, want, 1e-6 * b);
    }
}
