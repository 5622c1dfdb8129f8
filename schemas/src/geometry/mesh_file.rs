//! Triangle meshes from files: STL (binary or ASCII, through `stl_io`) and Wavefront OBJ (through
//! `tobj`), chosen by the file's extension in any letter case; and binary STL written (for tests
//! and benchmarks that generate meshes).
//!
//! Both formats' vertices are merged by exact coordinates after reading (`−0` equal to `+0`), so
//! triangles that share a corner share its index and [`TriangleMesh::check_closed`] can match their
//! edges: `stl_io` merges by the f32 bit pattern (which keeps `−0` apart from `0`), and `tobj`'s
//! single index may duplicate a position that carries different normals or texture coordinates.
//! Coordinates are single precision in STL and as `tobj` reads them (f32); they are widened to
//! f64 exactly.

use super::error::{MeshError, MeshProblem};
use super::triangle_mesh::TriangleMesh;
use super::vec3::{cross, norm, sub};
use crate::atomic_file;
use std::collections::HashMap;
use std::io::{BufReader, Cursor};
use std::path::Path;

/// The extensions [`read_mesh`] reads, lower case.
pub const MESH_EXTENSIONS: [&str; 2] = ["stl", "obj"];

/// Reads the triangle mesh of `path`, by its extension (case-insensitive): `.stl`, binary or ASCII
/// (the facet normals are ignored: a triangle's orientation is its vertex order, counter-clockwise
/// seen from outside, as STL prescribes); `.obj`, every model in the file joined into one mesh,
/// polygons split into triangle fans, points and lines ignored, materials not read.
///
/// Refuses another extension (listing those allowed), a file that cannot be read or parsed, a
/// non-finite coordinate and a file without triangles; every error names the file. The mesh is
/// not checked to be a solid: call [`TriangleMesh::check_solid`] (and [`MeshError::in_file`]).
pub fn read_mesh(path: &Path) -> Result<TriangleMesh, MeshError> {
    let err = |problem| MeshError::new(problem).in_file(path);
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let (vertices, triangles) = match extension.as_str() {
        "stl" => read_stl(path)?,
        "obj" => read_obj(path)?,
        _ => {
            return Err(err(MeshProblem::Extension {
                found: path
                    .extension()
                    .map(|e| e.to_string_lossy().into_owned())
                    .unwrap_or_default(),
            }))
        }
    };
    if let Some(vertex) = vertices.iter().position(|v| v.iter().any(|c| !c.is_finite())) {
        return Err(err(MeshProblem::NonFinite {
            vertex,
            position: vertices[vertex].map(f64::from),
        }));
    }
    if triangles.is_empty() {
        return Err(err(MeshProblem::Empty));
    }
    merge_equal_vertices(&vertices, &triangles).map_err(|m| err(MeshProblem::Parse(m)))
}

/// Corner positions (f32, as both formats give them) and triangles indexing them.
type Soup = (Vec<[f32; 3]>, Vec<[usize; 3]>);

/// The mesh with one vertex per distinct position (`−0` and `+0` the same), in the order the
/// triangles first name them; unused vertices dropped. Fails when an index is out of range or
/// the mesh has more than `u32::MAX` vertices.
fn merge_equal_vertices(vertices: &[[f32; 3]], triangles: &[[usize; 3]]) -> Result<TriangleMesh, String> {
    let mut index: HashMap<[u32; 3], u32> = HashMap::with_capacity(vertices.len());
    let mut merged: Vec<[f64; 3]> = Vec::with_capacity(vertices.len());
    let mut out = Vec::with_capacity(triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        let mut new = [0u32; 3];
        for (slot, &i) in new.iter_mut().zip(tri) {
            let v = vertices
                .get(i)
                .ok_or_else(|| format!("triangle {t} names vertex {i}, but there are {}", vertices.len()))?;
            // adding +0 turns −0 into +0 and leaves every other value alone
            let key = v.map(|c| (c + 0.0).to_bits());
            let next = u32::try_from(merged.len())
                .map_err(|_| format!("more than {} distinct vertices", u32::MAX))?;
            *slot = *index.entry(key).or_insert_with(|| {
                merged.push(v.map(|c| f64::from(c + 0.0)));
                next
            });
        }
        out.push(new);
    }
    Ok(TriangleMesh {
        vertices: merged,
        triangles: out,
    })
}

/// Reads a binary or ASCII STL. Binary is recognised by its size, `84 + 50 n` bytes for the `n`
/// in bytes 80–83 (or more, when the file does not start with `solid` and so cannot be ASCII), so
/// a binary file whose header starts with `solid` (as some exporters write) is read as binary.
/// ASCII is read in any letter case, its first line may be `solid` without a name, and a file of
/// several `solid … endsolid` blocks gives all their triangles.
fn read_stl(path: &Path) -> Result<Soup, MeshError> {
    let err = |problem| MeshError::new(problem).in_file(path);
    let mut bytes = std::fs::read(path).map_err(|e| err(MeshProblem::Io(e.to_string())))?;
    let count = bytes
        .get(80..84)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]));
    let binary_len = count.map(|n| 84 + 50 * n as u64);
    let starts_solid = |b: &[u8]| b.len() >= 5 && b[..5].eq_ignore_ascii_case(b"solid");
    let text_start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    let ascii = starts_solid(&bytes[text_start..]);
    let size = bytes.len() as u64;
    if binary_len == Some(size) || (!ascii && binary_len.is_some_and(|n| n <= size)) {
        // stl_io takes a file starting with "solid " for ASCII; a binary header is free text
        bytes[0] = b' ';
        let mesh = stl_io::read_stl(&mut Cursor::new(bytes))
            .map_err(|e| err(MeshProblem::Parse(format!("not a valid binary STL: {e}"))))?;
        return Ok(soup(mesh, 0));
    }
    if !ascii {
        let size = match (count, binary_len) {
            (Some(n), Some(len)) => {
                format!("its header's triangle count {n} needs {len} bytes, the file has {size}")
            }
            _ => format!("the file has {size} bytes, fewer than the 84 of the header"),
        };
        return Err(err(MeshProblem::Parse(format!(
            "neither a binary STL (80-byte header, triangle count, 50 bytes per triangle: {size}) nor an \
             ASCII STL (whose first line starts with `solid`)"
        ))));
    }
    bytes.make_ascii_lowercase();
    // the offsets of the lines that start a solid
    let mut starts = Vec::new();
    let mut line_start = 0;
    for line in bytes.split(|&b| b == b'\n') {
        let indent = line.iter().take_while(|b| b.is_ascii_whitespace()).count();
        let rest = &line[indent..];
        if starts_solid(rest) && rest.get(5).is_none_or(|b| b.is_ascii_whitespace()) {
            starts.push(line_start + indent);
        }
        line_start += line.len() + 1;
    }
    starts.push(bytes.len());
    let (mut vertices, mut triangles): Soup = (Vec::new(), Vec::new());
    for (n, block) in starts.windows(2).enumerate() {
        let mut text = bytes[block[0]..block[1]].to_vec();
        if text.get(5) != Some(&b' ') {
            text.insert(5, b' ');
        }
        let mesh = stl_io::read_stl(&mut Cursor::new(text)).map_err(|e| {
            let binary = match (count, binary_len) {
                (Some(count), Some(len)) => format!(
                    "; read as binary STL instead, its header's triangle count {count} would need {len} \
                     bytes, the file has {size}"
                ),
                _ => String::new(),
            };
            err(MeshProblem::Parse(format!(
                "not a valid ASCII STL (in solid {} of the file): {e}{binary}",
                n + 1
            )))
        })?;
        let (v, t) = soup(mesh, vertices.len());
        vertices.extend(v);
        triangles.extend(t);
    }
    Ok((vertices, triangles))
}

/// The vertices and triangles of an `stl_io` mesh, the indices moved up by `offset`.
fn soup(mesh: stl_io::IndexedMesh, offset: usize) -> Soup {
    let vertices = mesh.vertices.iter().map(|v| v.0).collect();
    let triangles = mesh
        .faces
        .iter()
        .map(|f| f.vertices.map(|i| i + offset))
        .collect();
    (vertices, triangles)
}

/// Reads a Wavefront OBJ: all models joined, faces triangulated (fans), one index per corner.
fn read_obj(path: &Path) -> Result<Soup, MeshError> {
    let err = |problem| MeshError::new(problem).in_file(path);
    let file = std::fs::File::open(path).map_err(|e| err(MeshProblem::Io(e.to_string())))?;
    // `..Default::default()` stays for the fields tobj's optional features add, should another
    // crate of the build enable them
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    // materials do not matter to a solid: the loader reports none
    let (models, _materials) = tobj::load_obj_buf(&mut BufReader::new(file), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| err(MeshProblem::Parse(format!("not a valid OBJ file: {e}"))))?;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for model in &models {
        let offset = vertices.len();
        vertices.extend(model.mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        triangles.extend(
            model
                .mesh
                .indices
                .chunks_exact(3)
                .map(|t| [0, 1, 2].map(|c| offset + t[c] as usize)),
        );
    }
    Ok((vertices, triangles))
}

/// Writes `mesh` to `path` as binary STL (whole or not at all, [`atomic_file`]): coordinates
/// rounded to f32, each facet's normal the unit `(b − a) × (c − a)` (zero for a degenerate
/// triangle). Refuses an index out of range or more than `u32::MAX` triangles.
pub fn write_binary_stl(path: &Path, mesh: &TriangleMesh) -> Result<(), MeshError> {
    let err = |problem| MeshError::new(problem).in_file(path);
    mesh.check_indices().map_err(|e| e.in_file(path))?;
    if u32::try_from(mesh.triangles.len()).is_err() {
        return Err(err(MeshProblem::Parse(format!(
            "{} triangles: binary STL holds at most {}",
            mesh.triangles.len(),
            u32::MAX
        ))));
    }
    let facets: Vec<stl_io::Triangle> = (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            let n = cross(sub(b, a), sub(c, a));
            let length = norm(n);
            let unit = if length > 0.0 {
                n.map(|x| x / length)
            } else {
                [0.0; 3]
            };
            stl_io::Triangle {
                normal: stl_io::Normal::new(unit.map(|x| x as f32)),
                vertices: [a, b, c].map(|v| stl_io::Vertex::new(v.map(|x| x as f32))),
            }
        })
        .collect();
    atomic_file::write_with(path, |mut out| stl_io::write_stl(&mut out, facets.iter()))
        .map_err(|e| err(MeshProblem::Io(format!("cannot be written: {e}"))))
}
