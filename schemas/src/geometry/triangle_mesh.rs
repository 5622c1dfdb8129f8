//! An indexed triangle mesh, its bounding box, its placement (scale, rotate, translate) and the
//! two solids tests build from scratch (a cuboid and a UV sphere). Its checks are in
//! [`mesh_checks`](super::mesh_checks), its volume integrals in
//! [`mass_properties`](super::mass_properties).

use super::vec3::{add, mat_mul, mat_vec};

/// A surface of triangles over shared vertices [m]. A solid's triangles list their vertices
/// counter-clockwise seen from outside (the right-hand normal points out of the solid).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TriangleMesh {
    /// Vertex positions `[x, y, z]` [m].
    pub vertices: Vec<[f64; 3]>,
    /// Each triangle's three indices into `vertices`.
    pub triangles: Vec<[u32; 3]>,
}

/// The rotation matrix of `rotate_deg`: about x by `rotate_deg[0]`, then about y by
/// `rotate_deg[1]`, then about z by `rotate_deg[2]` (degrees, right-handed, about the fixed axes
/// through the origin): `R = R_z R_y R_x`.
pub fn rotation_matrix(rotate_deg: [f64; 3]) -> [[f64; 3]; 3] {
    let [(sx, cx), (sy, cy), (sz, cz)] = rotate_deg.map(|d| d.to_radians().sin_cos());
    let rx = [[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]];
    let ry = [[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]];
    let rz = [[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]];
    mat_mul(&rz, &mat_mul(&ry, &rx))
}

impl TriangleMesh {
    /// The axis-aligned bounding box `(min, max)` of the vertices (all of them, used by a
    /// triangle or not). An empty mesh gives `min = +∞`, `max = −∞`.
    pub fn aabb(&self) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for v in &self.vertices {
            for a in 0..3 {
                lo[a] = lo[a].min(v[a]);
                hi[a] = hi[a].max(v[a]);
            }
        }
        (lo, hi)
    }

    /// The mesh placed in the scene: each vertex `p` becomes `R (S p) + t`, i.e. scaled first
    /// (`S = diag(scale)`, one factor per axis; a uniform scale `s` is `[s, s, s]`), then rotated
    /// by [`rotation_matrix`]`(rotate_deg)` (about x, then y, then z, in degrees, about the
    /// origin), then translated by `translate`.
    ///
    /// A negative scale factor mirrors the mesh. When `det S < 0` (an odd number of negative
    /// factors) every triangle's vertex order is reversed, so a solid stays outward-oriented. A
    /// zero factor flattens the mesh; [`check_solid`](Self::check_solid) then refuses it as
    /// degenerate.
    pub fn transformed(&self, scale: [f64; 3], rotate_deg: [f64; 3], translate: [f64; 3]) -> TriangleMesh {
        let r = rotation_matrix(rotate_deg);
        let vertices = self
            .vertices
            .iter()
            .map(|v| {
                let scaled = [v[0] * scale[0], v[1] * scale[1], v[2] * scale[2]];
                add(mat_vec(&r, scaled), translate)
            })
            .collect();
        let mirrored = scale[0] * scale[1] * scale[2] < 0.0;
        let triangles = self
            .triangles
            .iter()
            .map(|&[a, b, c]| if mirrored { [a, c, b] } else { [a, b, c] })
            .collect();
        TriangleMesh { vertices, triangles }
    }

    /// The box `[min, max]` as 12 outward-oriented triangles over its 8 corners. Corner `v` has
    /// the `max` coordinate along axis `a` where bit `a` of `v` is set.
    pub fn cuboid(min: [f64; 3], max: [f64; 3]) -> TriangleMesh {
        let vertices = (0..8)
            .map(|v: usize| std::array::from_fn(|a| if v >> a & 1 == 1 { max[a] } else { min[a] }))
            .collect();
        let triangles = vec![
            [0, 2, 3],
            [0, 3, 1], // −z
            [4, 5, 7],
            [4, 7, 6], // +z
            [0, 1, 5],
            [0, 5, 4], // −y
            [2, 6, 7],
            [2, 7, 3], // +y
            [0, 4, 6],
            [0, 6, 2], // −x
            [1, 3, 7],
            [1, 7, 5], // +x
        ];
        TriangleMesh { vertices, triangles }
    }

    /// A closed, outward-oriented UV sphere: the two poles on the z axis through `centre`, and
    /// `n_lat − 1` rings of `n_lon` vertices at polar angles `θ_l = π l / n_lat`, azimuths
    /// `φ_m = 2π m / n_lon`; `2 n_lon (n_lat − 1)` triangles. All vertices lie on the sphere of
    /// `radius`, so the mesh is inscribed (its volume is below `4/3 π r³`). `n_lat` is raised
    /// to at least 2 and `n_lon` to at least 3.
    pub fn uv_sphere(centre: [f64; 3], radius: f64, n_lat: usize, n_lon: usize) -> TriangleMesh {
        let n_lat = n_lat.max(2);
        let n_lon = n_lon.max(3);
        let mut vertices = Vec::with_capacity(2 + (n_lat - 1) * n_lon);
        vertices.push(add(centre, [0.0, 0.0, radius]));
        for l in 1..n_lat {
            let (st, ct) = (std::f64::consts::PI * l as f64 / n_lat as f64).sin_cos();
            for m in 0..n_lon {
                let (sp, cp) = (std::f64::consts::TAU * m as f64 / n_lon as f64).sin_cos();
                vertices.push(add(centre, [radius * st * cp, radius * st * sp, radius * ct]));
            }
        }
        vertices.push(add(centre, [0.0, 0.0, -radius]));
        let south = (vertices.len() - 1) as u32;
        let ring = |l: usize, m: usize| (1 + (l - 1) * n_lon + m % n_lon) as u32;
        let mut triangles = Vec::with_capacity(2 * n_lon * (n_lat - 1));
        for m in 0..n_lon {
            triangles.push([0, ring(1, m), ring(1, m + 1)]);
        }
        for l in 1..n_lat - 1 {
            for m in 0..n_lon {
                let (u0, u1, d0, d1) = (ring(l, m), ring(l, m + 1), ring(l + 1, m), ring(l + 1, m + 1));
                triangles.push([u0, d0, d1]);
                triangles.push([u0, d1, u1]);
            }
        }
        for m in 0..n_lon {
            triangles.push([south, ring(n_lat - 1, m + 1), ring(n_lat - 1, m)]);
        }
        TriangleMesh { vertices, triangles }
    }

    /// The three corners of triangle `t`.
    ///
    /// # Panics
    /// If `t` or one of its indices is out of range ([`check_solid`](Self::check_solid) refuses
    /// such a mesh; [`read_mesh`](super::read_mesh) never makes one).
    pub fn corners(&self, t: usize) -> [[f64; 3]; 3] {
        self.triangles[t].map(|i| self.vertices[i as usize])
    }
}
