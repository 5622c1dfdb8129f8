//! Errors of the geometry inputs: a triangle mesh that cannot be read or is not a solid
//! ([`MeshError`]), a height grid that cannot be read or used ([`GridError`]). Every error names
//! the file (when there is one), what is wrong and what is allowed.

use std::fmt;
use std::path::{Path, PathBuf};

/// How an edge of a mesh breaks the rule "used by exactly two triangles, in opposite directions".
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeFault {
    /// Used by one triangle only: a hole in the surface.
    Open,
    /// Shared by more than two triangles: a non-manifold edge.
    OverShared,
    /// Used by two triangles in the same direction: one of them is flipped.
    SameDirection,
}

impl fmt::Display for EdgeFault {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            EdgeFault::Open => "open (used by one triangle only)",
            EdgeFault::OverShared => "shared by more than two triangles",
            EdgeFault::SameDirection => "used twice in the same direction (a flipped triangle)",
        })
    }
}

/// What is wrong with a mesh.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshProblem {
    /// The file could not be opened or read.
    Io(String),
    /// The file's contents are not a mesh of the format its extension names.
    Parse(String),
    /// The file's extension is not one of the formats read.
    Extension {
        /// The extension found (empty when the name has none).
        found: String,
    },
    /// The mesh has no triangles.
    Empty,
    /// A vertex coordinate is NaN or infinite.
    NonFinite {
        /// Index of the vertex.
        vertex: usize,
        /// Its coordinates.
        position: [f64; 3],
    },
    /// A triangle names a vertex that does not exist.
    IndexOutOfRange {
        /// Index of the triangle.
        triangle: usize,
        /// Its vertex indices.
        indices: [u32; 3],
        /// Number of vertices of the mesh.
        vertices: usize,
    },
    /// A triangle has (nearly) no area or names one vertex twice.
    Degenerate {
        /// Index of the first such triangle.
        triangle: usize,
        /// Its vertex indices.
        indices: [u32; 3],
        /// Its vertices' coordinates.
        vertices: [[f64; 3]; 3],
        /// Its area.
        area: f64,
        /// The smallest area allowed.
        min_area: f64,
        /// How many triangles of the mesh are degenerate.
        count: usize,
    },
    /// Some edges are not used by exactly two triangles in opposite directions.
    NotClosed {
        /// Edges used by one triangle only.
        open: usize,
        /// Edges shared by more than two triangles.
        over_shared: usize,
        /// Edges used by two triangles in the same direction.
        same_direction: usize,
        /// The offending edge of the lowest-numbered triangle: its fault, that triangle and the
        /// edge's two vertices' coordinates.
        first: (EdgeFault, usize, [f64; 3], [f64; 3]),
    },
    /// A closed mesh whose signed volume is not positive: its normals point inwards.
    Inverted {
        /// The signed volume found.
        volume: f64,
    },
}

fn point(p: &[f64; 3]) -> String {
    format!("({}, {}, {})", p[0], p[1], p[2])
}

fn plural(n: usize, one: &str, many: &str) -> String {
    if n == 1 {
        format!("{n} {one}")
    } else {
        format!("{n} {many}")
    }
}

impl fmt::Display for MeshProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshProblem::Io(e) => write!(f, "cannot be read: {e}"),
            MeshProblem::Parse(e) => write!(f, "{e}"),
            MeshProblem::Extension { found } => write!(
                f,
                "extension `{found}` is not a mesh format read here; allowed: `.stl` (binary or ASCII) \
                 and `.obj` (Wavefront), in any letter case"
            ),
            MeshProblem::Empty => f.write_str("the mesh has no triangles"),
            MeshProblem::NonFinite { vertex, position } => write!(
                f,
                "vertex {vertex} is {}: coordinates must be finite numbers",
                point(position)
            ),
            MeshProblem::IndexOutOfRange {
                triangle,
                indices,
                vertices,
            } => write!(
                f,
                "triangle {triangle} names vertices {indices:?}, but the mesh has {vertices} vertices \
                 (indices 0 to {})",
                vertices.saturating_sub(1)
            ),
            MeshProblem::Degenerate {
                triangle,
                indices,
                vertices,
                area,
                min_area,
                count,
            } => write!(
                f,
                "{} degenerate (area below {min_area:e}, 1e-12 × the bounding box's diagonal², or a \
                 vertex named twice); the first is triangle {triangle}, vertices {indices:?} at {}, {}, \
                 {}, area {area:e}",
                plural(*count, "triangle is", "triangles are"),
                point(&vertices[0]),
                point(&vertices[1]),
                point(&vertices[2]),
            ),
            MeshProblem::NotClosed {
                open,
                over_shared,
                same_direction,
                first: (fault, triangle, a, b),
            } => write!(
                f,
                "the surface is not closed and consistently oriented (every edge must be used by exactly \
                 two triangles, in opposite directions): {} open (used by one triangle only), {} shared \
                 by more than two triangles, {} used twice in the same direction (a flipped triangle); \
                 the first, of triangle {triangle}, is {fault}: {} – {}",
                plural(*open, "edge is", "edges are"),
                plural(*over_shared, "is", "are"),
                plural(*same_direction, "is", "are"),
                point(a),
                point(b)
            ),
            MeshProblem::Inverted { volume } => write!(
                f,
                "the mesh is inverted (its normals point inwards): its signed volume is {volume:e}; \
                 reverse the order of every triangle's vertices"
            ),
        }
    }
}

/// A mesh that cannot be read or is not a solid; names the file when it came from one.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshError {
    /// The file the mesh was read from, if any.
    pub file: Option<PathBuf>,
    /// What is wrong (boxed: some problems carry a triangle's coordinates).
    pub problem: Box<MeshProblem>,
}

impl MeshError {
    /// An error of a mesh that came from no file.
    pub fn new(problem: MeshProblem) -> Self {
        Self {
            file: None,
            problem: Box::new(problem),
        }
    }

    /// The same error, naming `file` (e.g. to report [`TriangleMesh::check_solid`] of a mesh read
    /// from `file`).
    ///
    /// [`TriangleMesh::check_solid`]: super::TriangleMesh::check_solid
    pub fn in_file(self, file: &Path) -> Self {
        Self {
            file: Some(file.to_path_buf()),
            problem: self.problem,
        }
    }
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.file {
            Some(file) => write!(f, "{}: {}", file.display(), self.problem),
            None => write!(f, "mesh: {}", self.problem),
        }
    }
}

impl std::error::Error for MeshError {}

/// A height grid that cannot be read or built; names the file and line when it came from one.
#[derive(Debug, Clone, PartialEq)]
pub struct GridError {
    /// The file the grid was read from, if any.
    pub file: Option<PathBuf>,
    /// The line of the file (from 1), when one line is at fault.
    pub line: Option<usize>,
    /// What is wrong and what is allowed.
    pub message: String,
}

impl GridError {
    /// An error of a grid built in code (no file).
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            file: None,
            line: None,
            message: message.into(),
        }
    }

    /// An error at `line` (from 1) of `file`, or of the whole file when `line` is `None`.
    pub fn at(file: &Path, line: Option<usize>, message: impl Into<String>) -> Self {
        Self {
            file: Some(file.to_path_buf()),
            line,
            message: message.into(),
        }
    }
}

impl fmt::Display for GridError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (&self.file, self.line) {
            (Some(file), Some(line)) => write!(f, "{}: line {line}: {}", file.display(), self.message),
            (Some(file), None) => write!(f, "{}: {}", file.display(), self.message),
            (None, _) => write!(f, "height grid: {}", self.message),
        }
    }
}

impl std::error::Error for GridError {}
