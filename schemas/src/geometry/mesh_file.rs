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

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    /// A file name in the temporary folder no other test or process uses.
    fn scratch(name: &str) -> PathBuf {
        std::env::temp_dir().join(format!("schemas-mesh-file-{}-{name}", std::process::id()))
    }

    fn write(path: &Path, contents: impl AsRef<[u8]>) {
        std::fs::write(path, contents).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }

    fn read(path: &Path) -> TriangleMesh {
        read_mesh(path).unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn binary_stl_round_trip() {
        let path = scratch("round-trip.STL");
        let sphere = TriangleMesh::uv_sphere([1.0, 2.0, 3.0], 0.5, 12, 24);
        write_binary_stl(&path, &sphere).unwrap_or_else(|e| panic!("{e}"));
        let back = read(&path);
        let _ = std::fs::remove_file(&path);
        assert_eq!(back.check_solid(), Ok(()));
        assert_eq!(back.vertices.len(), sphere.vertices.len());
        assert_eq!(back.triangles.len(), sphere.triangles.len());
        for t in 0..sphere.triangles.len() {
            let (want, got) = (sphere.corners(t), back.corners(t));
            for c in 0..3 {
                assert_eq!(got[c], want[c].map(|x| f64::from(x as f32)), "triangle {t}");
            }
        }
    }

    #[test]
    fn a_binary_stl_whose_header_starts_with_solid_is_binary() {
        let path = scratch("solid-header.stl");
        write_binary_stl(&path, &TriangleMesh::cuboid([0.0; 3], [1.0; 3])).unwrap_or_else(|e| panic!("{e}"));
        let mut bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{e}"));
        bytes[..12].copy_from_slice(b"solid cube\n ");
        write(&path, &bytes);
        let mesh = read(&path);
        let _ = std::fs::remove_file(&path);
        assert_eq!(mesh.check_solid(), Ok(()));
        assert!((mesh.signed_volume() - 1.0).abs() < 1e-12);
    }

    /// A unit tetrahedron in ASCII STL with CRLF line ends, no solid name, `-0` beside `0`,
    /// exponents and a wrong facet normal (ignored).
    const ASCII_TETRAHEDRON: &str = "solid\r
facet normal 0 0 0\r
 outer loop\r
  vertex 0 0 0\r
  vertex 0 1 0\r
  vertex 1 0 0\r
 endloop\r
endfacet\r
facet normal 0 -1 0\r
 outer loop\r
  vertex -0 0 0\r
  vertex 1e0 0 0\r
  vertex 0 0 1\r
 endloop\r
endfacet\r
facet normal -1 0 0\r
 outer loop\r
  vertex 0 0 0\r
  vertex 0 0 1.0\r
  vertex 0 1 0\r
 endloop\r
endfacet\r
facet normal 1 1 1\r
 outer loop\r
  vertex 1 0 0\r
  vertex 0 1 0\r
  vertex 0 0 10e-1\r
 endloop\r
endfacet\r
endsolid\r
";

    #[test]
    fn ascii_stl_is_read_and_its_vertices_merged() {
        let path = scratch("tetrahedron.stl");
        write(&path, ASCII_TETRAHEDRON);
        let mesh = read(&path);
        let _ = std::fs::remove_file(&path);
        assert_eq!(mesh.vertices.len(), 4);
        assert_eq!(mesh.check_solid(), Ok(()));
        assert!((mesh.signed_volume() - 1.0 / 6.0).abs() < 1e-15);
    }

    #[test]
    fn ascii_stl_of_several_solids_in_capitals() {
        // the tetrahedron's first face in one solid, the other three in a second, in capitals
        let upper = ASCII_TETRAHEDRON.to_uppercase();
        let split = upper.replacen("ENDFACET\r\n", "ENDFACET\r\nENDSOLID\r\nSOLID SECOND\r\n", 1);
        let path = scratch("two-solids.stl");
        write(&path, split);
        let mesh = read(&path);
        let _ = std::fs::remove_file(&path);
        assert_eq!(mesh.triangles.len(), 4);
        assert_eq!(mesh.check_solid(), Ok(()));
    }

    #[test]
    fn obj_quads_are_triangulated_and_models_joined() {
        // a unit cube of six quads in two objects, normals per face (which make tobj's single
        // index duplicate the corners) and a texture coordinate
        let obj = "# cube\n\
            v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n\
            vt 0 0\n\
            vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\n\
            o bottom_and_top\n\
            f 1/1/1 3/1/1 4/1/1 2/1/1\n\
            f 5/1/2 6/1/2 8/1/2 7/1/2\n\
            o sides\n\
            f 1//3 2//3 6//3 5//3\n\
            f 3//4 7//4 8//4 4//4\n\
            f 1//5 5//5 7//5 3//5\n\
            f 2//6 4//6 8//6 6//6\n\
            l 1 8\n";
        let path = scratch("cube.Obj");
        write(&path, obj);
        let mesh = read(&path);
        let _ = std::fs::remove_file(&path);
        assert_eq!(mesh.triangles.len(), 12);
        assert_eq!(mesh.vertices.len(), 8);
        assert_eq!(mesh.check_solid(), Ok(()));
        let p = mesh.mass_properties(1.0);
        assert!((p.volume - 1.0).abs() < 1e-15 && p.centre == [0.5; 3]);
    }

    #[test]
    fn errors_name_the_file_and_what_is_allowed() {
        let path = scratch("mesh.ply");
        let e = read_mesh(&path).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(
            e.contains("mesh.ply") && e.contains("`.stl`") && e.contains("`.obj`"),
            "{e}"
        );

        let path = scratch("missing.stl");
        let e = read_mesh(&path).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(e.contains("missing.stl") && e.contains("cannot be read"), "{e}");

        let path = scratch("garbage.stl");
        write(
            &path,
            "this is not a mesh at all, neither binary nor ascii; it goes on for a while \
            so that it is longer than the header of a binary file",
        );
        let e = read_mesh(&path).err().map(|e| e.to_string()).unwrap_or_default();
        let _ = std::fs::remove_file(&path);
        assert!(
            e.contains("garbage.stl") && e.contains("neither a binary STL"),
            "{e}"
        );

        let path = scratch("broken.stl");
        write(
            &path,
            "solid x\nfacet normal 0 0 1\n outer loop\n vertex 0 0 zero\n",
        );
        let e = read_mesh(&path).err().map(|e| e.to_string()).unwrap_or_default();
        let _ = std::fs::remove_file(&path);
        assert!(
            e.contains("broken.stl") && e.contains("not a valid ASCII STL"),
            "{e}"
        );

        let path = scratch("empty.stl");
        write(&path, "solid nothing\nendsolid nothing\n");
        let e = read_mesh(&path).err().map(|e| e.to_string()).unwrap_or_default();
        let _ = std::fs::remove_file(&path);
        assert!(e.contains("empty.stl") && e.contains("no triangles"), "{e}");

        let path = scratch("bad-face.obj");
        write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
        let e = read_mesh(&path).err().map(|e| e.to_string()).unwrap_or_default();
        let _ = std::fs::remove_file(&path);
        assert!(e.contains("bad-face.obj") && e.contains("OBJ"), "{e}");

        let path = scratch("nan.obj");
        write(&path, "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        let e = read_mesh(&path).err().map(|e| e.to_string()).unwrap_or_default();
        let _ = std::fs::remove_file(&path);
        assert!(e.contains("nan.obj") && e.contains("finite"), "{e}");
    }

    #[test]
    fn a_solid_check_names_the_file() {
        let path = scratch("open.stl");
        let mut cube = TriangleMesh::cuboid([0.0; 3], [1.0; 3]);
        cube.triangles.pop();
        write_binary_stl(&path, &cube).unwrap_or_else(|e| panic!("{e}"));
        let mesh = read(&path);
        let _ = std::fs::remove_file(&path);
        let e = mesh.check_solid().map_err(|e| e.in_file(&path).to_string());
        let e = e.err().unwrap_or_default();
        assert!(e.contains("open.stl") && e.contains("3 edges are open"), "{e}");
    }
}
