//! Tests of `schemas::geometry::mesh_checks`.

use schemas::geometry::error::{EdgeFault, MeshError, MeshProblem};
use schemas::geometry::triangle_mesh::TriangleMesh;

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
