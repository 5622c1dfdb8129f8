//! The checks that make a triangle mesh a solid: indices in range, finite coordinates, no
//! degenerate triangle, every edge used by exactly two triangles in opposite directions (closed
//! and consistently oriented), and a positive volume (normals pointing out).
//! Self-intersections are not looked for.

use super::error::{EdgeFault, MeshError, MeshProblem};
use super::triangle_mesh::TriangleMesh;
use super::vec3::{cross, norm, sub};
use rayon::slice::ParallelSliceMut;

/// Triangles with an area below this fraction of the bounding box's squared diagonal are
/// degenerate ([`TriangleMesh::check_degenerate`]).
pub const DEGENERATE_AREA_FRACTION: f64 = 1e-12;

impl TriangleMesh {
    /// The area of triangle `t`, `|(b − a) × (c − a)| / 2`.
    ///
    /// # Panics
    /// If `t` or one of its indices is out of range.
    pub fn triangle_area(&self, t: usize) -> f64 {
        let [a, b, c] = self.corners(t);
        0.5 * norm(cross(sub(b, a), sub(c, a)))
    }

    /// Refuses a triangle naming a vertex that does not exist, and a non-finite vertex.
    pub fn check_indices(&self) -> Result<(), MeshError> {
        let n = self.vertices.len();
        if let Some((triangle, &indices)) = self
            .triangles
            .iter()
            .enumerate()
            .find(|(_, t)| t.iter().any(|&i| i as usize >= n))
        {
            return Err(MeshError::new(MeshProblem::IndexOutOfRange {
                triangle,
                indices,
                vertices: n,
            }));
        }
        if let Some((vertex, &position)) = self
            .vertices
            .iter()
            .enumerate()
            .find(|(_, v)| v.iter().any(|c| !c.is_finite()))
        {
            return Err(MeshError::new(MeshProblem::NonFinite { vertex, position }));
        }
        Ok(())
    }

    /// The indices of the triangles that name one vertex twice or have an area below
    /// `min_area`, in order.
    ///
    /// # Panics
    /// If an index is out of range ([`check_indices`](Self::check_indices) refuses that).
    pub fn degenerate_triangles(&self, min_area: f64) -> Vec<usize> {
        (0..self.triangles.len())
            .filter(|&t| {
                let [a, b, c] = self.triangles[t];
                a == b || b == c || c == a || self.triangle_area(t) < min_area
            })
            .collect()
    }

    /// Refuses degenerate triangles: a vertex named twice, or an area below
    /// [`DEGENERATE_AREA_FRACTION`] × the bounding box's squared diagonal; names the first one's
    /// index and vertices and says how many there are. Checks the indices first.
    pub fn check_degenerate(&self) -> Result<(), MeshError> {
        self.check_indices()?;
        let (lo, hi) = self.aabb();
        let diagonal = norm(sub(hi, lo));
        let min_area = DEGENERATE_AREA_FRACTION * diagonal * diagonal;
        let bad = self.degenerate_triangles(min_area);
        match bad.first() {
            None => Ok(()),
            Some(&triangle) => Err(MeshError::new(MeshProblem::Degenerate {
                triangle,
                indices: self.triangles[triangle],
                vertices: self.corners(triangle),
                area: self.triangle_area(triangle),
                min_area,
                count: bad.len(),
            })),
        }
    }

    /// Refuses a surface that is not closed and consistently oriented: every undirected edge must
    /// be used by exactly two triangles, once in each direction. The error counts the open edges
    /// (used once), the over-shared ones (more than two triangles) and those used twice in the
    /// same direction (a flipped triangle), and gives the offending edge of the lowest-numbered
    /// triangle with its vertices' coordinates. Checks the indices first.
    ///
    /// Edges are matched by vertex index: two vertices at the same place under different indices
    /// leave both edges open ([`read_mesh`](super::read_mesh) merges such vertices).
    pub fn check_closed(&self) -> Result<(), MeshError> {
        self.check_indices()?;
        // (undirected key, triangle, forward = from the lower index to the higher)
        let mut edges: Vec<(u64, u32, bool)> = Vec::with_capacity(3 * self.triangles.len());
        for (t, tri) in self.triangles.iter().enumerate() {
            for e in 0..3 {
                let (a, b) = (tri[e], tri[(e + 1) % 3]);
                let key = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
                edges.push((key, t as u32, a < b));
            }
        }
        edges.par_sort_unstable();
        let (mut open, mut over_shared, mut same_direction) = (0, 0, 0);
        let mut first: Option<(EdgeFault, usize, u64)> = None;
        for group in edges.chunk_by(|x, y| x.0 == y.0) {
            let fault = match group {
                [_] => EdgeFault::Open,
                [x, y] if x.2 == y.2 => EdgeFault::SameDirection,
                [_, _] => continue,
                _ => EdgeFault::OverShared,
            };
            match fault {
                EdgeFault::Open => open += 1,
                EdgeFault::OverShared => over_shared += 1,
                EdgeFault::SameDirection => same_direction += 1,
            }
            // sorted by triangle within the group: the first entry is its lowest triangle
            let t = group[0].1 as usize;
            if first.is_none_or(|(_, ft, _)| t < ft) {
                first = Some((fault, t, group[0].0));
            }
        }
        match first {
            None => Ok(()),
            Some((fault, t, key)) => {
                let a = self.vertices[(key >> 32) as usize];
                let b = self.vertices[(key & 0xffff_ffff) as usize];
                Err(MeshError::new(MeshProblem::NotClosed {
                    open,
                    over_shared,
                    same_direction,
                    first: (fault, t, a, b),
                }))
            }
        }
    }

    /// Refuses a mesh that is not a solid: no triangles, an index out of range, a non-finite
    /// vertex, a degenerate triangle ([`check_degenerate`](Self::check_degenerate)), a surface
    /// not closed and consistently oriented ([`check_closed`](Self::check_closed)), or a closed
    /// surface with a non-positive [`signed_volume`](Self::signed_volume): "inverted (its normals
    /// point inwards)". Self-intersections are not looked for.
    pub fn check_solid(&self) -> Result<(), MeshError> {
        if self.triangles.is_empty() {
            return Err(MeshError::new(MeshProblem::Empty));
        }
        self.check_degenerate()?;
        self.check_closed()?;
        let volume = self.signed_volume();
        if volume > 0.0 {
            Ok(())
        } else {
            Err(MeshError::new(MeshProblem::Inverted { volume }))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> TriangleMesh {
        TriangleMesh::cuboid([0.0; 3], [1.0; 3])
    }

    fn problem(mesh: &TriangleMesh) -> MeshProblem {
        match mesh.check_solid() {
            Ok(()) => panic!("the mesh was accepted"),
            Err(e) => {
                assert!(e.to_string().starts_with("mesh: "), "{e}");
                *e.problem
            }
        }
    }

    #[test]
    fn a_removed_triangle_is_refused_as_open() {
        let mut m = cube();
        m.triangles.remove(5);
        match problem(&m) {
            MeshProblem::NotClosed {
                open: 3,
                over_shared: 0,
                same_direction: 0,
                first: (EdgeFault::Open, _, _, _),
            } => {}
            p => panic!("{p}"),
        }
        let text = MeshError::new(problem(&m)).to_string();
        assert!(text.contains("3 edges are open"), "{text}");
    }

    #[test]
    fn one_flipped_triangle_is_refused() {
        let mut m = cube();
        m.triangles[7].swap(1, 2);
        match problem(&m) {
            MeshProblem::NotClosed {
                open: 0,
                over_shared: 0,
                same_direction: 3,
                first: (EdgeFault::SameDirection, t, a, b),
            } => {
                // the lowest-numbered triangle sharing an edge with triangle 7
                assert!(t <= 7);
                assert!(a != b);
            }
            p => panic!("{p}"),
        }
    }

    #[test]
    fn an_inverted_cube_is_refused_as_inverted() {
        let mut m = cube();
        for t in &mut m.triangles {
            t.swap(1, 2);
        }
        match problem(&m) {
            MeshProblem::Inverted { volume } => assert!((volume + 1.0).abs() < 1e-12),
            p => panic!("{p}"),
        }
        assert!(MeshError::new(problem(&m))
            .to_string()
            .contains("inverted (its normals point inwards)"));
    }

    #[test]
    fn an_edge_of_three_triangles_is_refused() {
        let mut m = cube();
        m.triangles.push(m.triangles[0]);
        match problem(&m) {
            MeshProblem::NotClosed { over_shared: 3, .. } => {}
            p => panic!("{p}"),
        }
    }

    #[test]
    fn degenerate_triangles_are_refused_naming_the_first() {
        let mut m = cube();
        // a vertex named twice
        m.triangles[4] = [0, 1, 1];
        match problem(&m) {
            MeshProblem::Degenerate {
                triangle: 4,
                indices: [0, 1, 1],
                count: 1,
                ..
            } => {}
            p => panic!("{p}"),
        }
        let mut m = cube();
        m.vertices.push([0.5, 0.5, 0.0]);
        m.vertices.push([0.25, 0.25, 0.0]);
        m.triangles.push([0, 8, 9]); // three points on a line: no area
        match problem(&m) {
            MeshProblem::Degenerate {
                triangle: 12, area, ..
            } => assert_eq!(area, 0.0),
            p => panic!("{p}"),
        }
        let text = MeshError::new(problem(&m)).to_string();
        assert!(
            text.contains("triangle 12") && text.contains("(0.5, 0.5, 0)"),
            "{text}"
        );
    }

    #[test]
    fn bad_indices_and_coordinates_are_refused() {
        let mut m = cube();
        m.triangles[2][1] = 8;
        assert!(matches!(
            problem(&m),
            MeshProblem::IndexOutOfRange {
                triangle: 2,
                vertices: 8,
                ..
            }
        ));
        let mut m = cube();
        m.vertices[3][1] = f64::NAN;
        assert!(matches!(problem(&m), MeshProblem::NonFinite { vertex: 3, .. }));
        assert_eq!(problem(&TriangleMesh::default()), MeshProblem::Empty);
    }
}
