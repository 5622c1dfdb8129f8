//! Tests of `schemas::geometry::mesh_file`.

use schemas::geometry::mesh_file::*;
use schemas::geometry::triangle_mesh::TriangleMesh;
use std::path::Path;
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
