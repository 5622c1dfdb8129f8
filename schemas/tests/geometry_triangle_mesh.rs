//! Tests of `schemas::geometry::triangle_mesh`.

use schemas::geometry::triangle_mesh::*;
use schemas::geometry::vec3::mat_vec;

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() <= tol)
}

#[test]
fn the_cuboid_and_sphere_are_outward_solids() {
    let cube = TriangleMesh::cuboid([1.0, 2.0, 3.0], [2.0, 4.0, 6.0]);
    assert_eq!(cube.check_solid(), Ok(()));
    assert!((cube.signed_volume() - 6.0).abs() < 1e-12);
    assert_eq!(cube.aabb(), ([1.0, 2.0, 3.0], [2.0, 4.0, 6.0]));
    let sphere = TriangleMesh::uv_sphere([0.5, -1.0, 2.0], 2.0, 40, 80);
    assert_eq!(sphere.check_solid(), Ok(()));
    assert_eq!(sphere.triangles.len(), 2 * 80 * 39);
    let exact = 4.0 / 3.0 * std::f64::consts::PI * 8.0;
    let v = sphere.signed_volume();
    assert!(v < exact && v > 0.99 * exact, "{v} against {exact}");
}

#[test]
fn rotation_is_about_x_then_y_then_z() {
    // x → (about z by 90°) y; about x first leaves x alone
    let r = rotation_matrix([90.0, 0.0, 90.0]);
    assert!(close(mat_vec(&r, [1.0, 0.0, 0.0]), [0.0, 1.0, 0.0], 1e-15));
    // y → (about x by 90°) z → (about y by 90°) x
    let r = rotation_matrix([90.0, 90.0, 0.0]);
    assert!(close(mat_vec(&r, [0.0, 1.0, 0.0]), [1.0, 0.0, 0.0], 1e-15));
}

#[test]
fn transformed_scales_then_rotates_then_translates() {
    let cube = TriangleMesh::cuboid([0.0; 3], [1.0; 3]);
    let moved = cube.transformed([2.0, 1.0, 1.0], [0.0, 0.0, 90.0], [10.0, 0.0, 0.0]);
    // corner (1, 0, 0) → scaled (2, 0, 0) → rotated (0, 2, 0) → (10, 2, 0)
    assert!(close(moved.vertices[1], [10.0, 2.0, 0.0], 1e-14));
    assert_eq!(moved.check_solid(), Ok(()));
    assert!((moved.signed_volume() - 2.0).abs() < 1e-12);
}

#[test]
fn a_mirroring_scale_keeps_the_mesh_outward() {
    let sphere = TriangleMesh::uv_sphere([1.0, 0.0, 0.0], 1.0, 8, 12);
    for scale in [[-1.0, 1.0, 1.0], [1.0, -2.0, 1.0], [-1.0, -1.0, -1.0]] {
        let m = sphere.transformed(scale, [10.0, 20.0, 30.0], [0.0; 3]);
        assert_eq!(m.check_solid(), Ok(()), "scale {scale:?}");
    }
    // two mirrors are a rotation: the order is kept
    let m = sphere.transformed([-1.0, -1.0, 1.0], [0.0; 3], [0.0; 3]);
    assert_eq!(m.triangles, sphere.triangles);
}
