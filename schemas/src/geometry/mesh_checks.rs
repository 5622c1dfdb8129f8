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
