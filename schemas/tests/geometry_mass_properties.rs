//! Tests of `schemas::geometry::mass_properties`.

use schemas::geometry::triangle_mesh::rotation_matrix;
use schemas::geometry::triangle_mesh::TriangleMesh;
use schemas::geometry::vec3::mat_mul;

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
