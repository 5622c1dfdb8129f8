//! Tests of `schemas::geometry::lattice_fill`.

use schemas::geometry::lattice::Lattice;
use schemas::geometry::lattice_fill::*;
use schemas::geometry::site_set::SiteSet;
use schemas::geometry::triangle_mesh::TriangleMesh;
use schemas::geometry::HeightGrid;

fn lattice(origin: [f64; 3], spacing: f64, n: [usize; 3]) -> Lattice {
    Lattice { origin, spacing, n }
}

/// Every site, with its centre.
fn sites(l: &Lattice) -> impl Iterator<Item = ([usize; 3], [f64; 3])> + '_ {
    (0..l.n[0]).flat_map(move |i| {
        (0..l.n[1]).flat_map(move |j| (0..l.n[2]).map(move |k| ([i, j, k], l.site_centre([i, j, k]))))
    })
}

/// Asserts that the fill equals `inside` at every site.
fn assert_fill(set: &SiteSet, inside: impl Fn([f64; 3]) -> bool, what: &str) {
    let l = *set.lattice();
    let mut count = 0;
    for ([i, j, k], x) in sites(&l) {
        let want = inside(x);
        count += usize::from(want);
        assert_eq!(
            set.contains(i, j, k),
            want,
            "{what}: site ({i}, {j}, {k}) at {x:?}"
        );
    }
    assert_eq!(set.count(), count, "{what}");
}

/// The closed box's `contains_point`: faces included.
fn in_box(min: [f64; 3], max: [f64; 3]) -> impl Fn([f64; 3]) -> bool {
    move |x| (0..3).all(|a| min[a] <= x[a] && x[a] <= max[a])
}

fn check_cuboid(l: &Lattice, min: [f64; 3], max: [f64; 3], what: &str) {
    let set = sites_inside_mesh(&TriangleMesh::cuboid(min, max), l);
    assert_fill(&set, in_box(min, max), what);
}

#[test]
fn cuboids_give_the_sites_a_box_contains() {
    let l = lattice([-0.3, 0.1, 0.25], 0.1, [17, 13, 11]);
    check_cuboid(&l, [0.03, 0.41, 0.5], [1.02, 1.111, 1.07], "generic box");
    // faces half a spacing from the sites, i.e. on the cells' faces
    let (lo, hi) = (l.site_centre([2, 3, 1]), l.site_centre([9, 10, 7]));
    let half = 0.5 * l.spacing;
    check_cuboid(
        &l,
        lo.map(|c| c - half),
        hi.map(|c| c + half),
        "faces between sites",
    );
    let set = sites_inside_mesh(
        &TriangleMesh::cuboid(lo.map(|c| c - half), hi.map(|c| c + half)),
        &l,
    );
    assert_eq!(set.count(), 8 * 8 * 7);
    // faces, edges and corners through site centres: those sites count as inside
    check_cuboid(&l, lo, hi, "faces through sites");
    let set = sites_inside_mesh(&TriangleMesh::cuboid(lo, hi), &l);
    assert_eq!(set.count(), 8 * 8 * 7);
    // a box one layer of sites thick, its lower face through them
    check_cuboid(&l, lo, [hi[0], hi[1], lo[2] + half], "one layer");
    // the tank: the lattice's own box, and a larger one
    check_cuboid(&l, l.origin, l.upper_corner(), "the lattice's box");
    check_cuboid(&l, [-5.0; 3], [5.0; 3], "a box around the lattice");
    let set = sites_inside_mesh(&TriangleMesh::cuboid(l.origin, l.upper_corner()), &l);
    assert_eq!(set.count(), l.site_count());
    // a box beyond the lattice, and one overlapping its corner
    check_cuboid(&l, [5.0; 3], [6.0; 3], "beyond");
    check_cuboid(&l, [-1.0; 3], lo, "over the corner");
}

#[test]
fn a_box_turned_a_quarter_turn_about_z_keeps_its_sites() {
    // the rotation leaves coordinates like 6e-17 instead of 0: no site lies on a face here
    let l = lattice([0.0; 3], 0.25, [12, 12, 12]);
    let mesh = TriangleMesh::cuboid([-1.1, -0.6, 0.3], [-0.1, 1.4, 2.2]).transformed(
        [1.0; 3],
        [0.0, 0.0, -90.0],
        [0.0; 3],
    );
    let set = sites_inside_mesh(&mesh, &l);
    assert_fill(&set, in_box([-0.6, 0.1, 0.3], [1.4, 1.1, 2.2]), "turned box");
}

#[test]
fn slanted_vertical_faces_through_sites() {
    // a prism on the triangle x ≥ 0, y ≥ 0, x + y ≤ 4, for 0 ≤ z ≤ 3, sites at whole numbers:
    // its slanted vertical face runs through a diagonal of site columns
    let l = lattice([-2.5; 3], 1.0, [9, 9, 8]);
    let mesh = TriangleMesh {
        vertices: vec![
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [0.0, 4.0, 0.0],
            [0.0, 0.0, 3.0],
            [4.0, 0.0, 3.0],
            [0.0, 4.0, 3.0],
        ],
        triangles: vec![
            [0, 2, 1],
            [3, 4, 5],
            [0, 1, 4],
            [0, 4, 3],
            [1, 2, 5],
            [1, 5, 4],
            [2, 0, 3],
            [2, 3, 5],
        ],
    };
    assert_eq!(mesh.check_solid(), Ok(()));
    let set = sites_inside_mesh(&mesh, &l);
    assert_fill(
        &set,
        |x| x[0] >= 0.0 && x[1] >= 0.0 && x[0] + x[1] <= 4.0 && (0.0..=3.0).contains(&x[2]),
        "prism",
    );
}

#[test]
fn octahedron_with_vertices_and_edges_on_sites() {
    // |x| + |y| + |z| ≤ 3 with sites at whole numbers: lines through its vertices and edges,
    // and sites on its faces
    let l = lattice([-4.5; 3], 1.0, [9, 9, 9]);
    let r = 3.0;
    let mesh = TriangleMesh {
        vertices: vec![
            [r, 0.0, 0.0],
            [-r, 0.0, 0.0],
            [0.0, r, 0.0],
            [0.0, -r, 0.0],
            [0.0, 0.0, r],
            [0.0, 0.0, -r],
        ],
        triangles: vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ],
    };
    assert_eq!(mesh.check_solid(), Ok(()));
    let set = sites_inside_mesh(&mesh, &l);
    assert_fill(&set, |x| x[0].abs() + x[1].abs() + x[2].abs() <= r, "octahedron");
}

#[test]
fn cavities_and_separate_solids() {
    let l = lattice([0.0; 3], 0.1, [20, 10, 10]);
    let mut mesh = TriangleMesh::cuboid([0.05, 0.05, 0.05], [0.95, 0.95, 0.95]);
    let mut add = |m: TriangleMesh| {
        let offset = mesh.vertices.len() as u32;
        mesh.vertices.extend(m.vertices);
        mesh.triangles
            .extend(m.triangles.iter().map(|t| t.map(|v| v + offset)));
    };
    // an inverted inner box: a cavity
    let mut cavity = TriangleMesh::cuboid([0.3; 3], [0.7; 3]);
    cavity.triangles.iter_mut().for_each(|t| t.swap(1, 2));
    add(cavity);
    add(TriangleMesh::cuboid([1.2, 0.2, 0.2], [1.8, 0.8, 0.8]));
    assert_eq!(mesh.check_solid(), Ok(()));
    let set = sites_inside_mesh(&mesh, &l);
    assert_fill(
        &set,
        |x| {
            (in_box([0.05; 3], [0.95; 3])(x) && !(in_box([0.3; 3], [0.7; 3])(x)))
                || in_box([1.2, 0.2, 0.2], [1.8, 0.8, 0.8])(x)
        },
        "cavity",
    );
}

#[test]
fn turned_boxes_give_the_sites_their_half_spaces_contain() {
    // boxes turned every which way (a fixed pseudo-random sequence), against the intersection
    // of their six half-spaces; sites within 1e-9 of a face plane are not compared
    let l = lattice([-1.0; 3], 0.1, [20; 3]);
    let mut seed = 12345u64;
    let mut next = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for case in 0..20 {
        let half = [0.2 + 0.5 * next(), 0.2 + 0.5 * next(), 0.2 + 0.5 * next()];
        let rotate = [360.0 * next(), 360.0 * next(), 360.0 * next()];
        let centre = [0.4 * next() - 0.2, 0.4 * next() - 0.2, 0.4 * next() - 0.2];
        let mesh = TriangleMesh::cuboid(half.map(|h| -h), half).transformed([1.0; 3], rotate, centre);
        let r = schemas::geometry::rotation_matrix(rotate);
        let set = sites_inside_mesh(&mesh, &l);
        for (s, x) in sites(&l) {
            let d = schemas::geometry::vec3::sub(x, centre);
            // the site's coordinates in the box's frame: Rᵀ d
            let local: [f64; 3] = std::array::from_fn(|a| (0..3).map(|b| r[b][a] * d[b]).sum());
            let margin =
                schemas::validation::smallest((0..3).map(|a| half[a] - local[a].abs()), f64::INFINITY);
            if margin.abs() > 1e-9 {
                assert_eq!(
                    set.contains(s[0], s[1], s[2]),
                    margin > 0.0,
                    "case {case}: site {s:?}"
                );
            }
        }
    }
}

#[test]
fn a_sphere_whose_poles_lie_on_a_column_of_sites() {
    // the vertical line through the centre runs through both poles, where 64 triangles meet
    let l = lattice([0.0; 3], 0.1, [21; 3]);
    let centre = l.site_centre([10, 10, 10]);
    let mesh = TriangleMesh::uv_sphere(centre, 0.73, 16, 64);
    let set = sites_inside_mesh(&mesh, &l);
    let column: Vec<usize> = (0..21).filter(|&k| set.contains(10, 10, k)).collect();
    assert_eq!(column, (3..=17).collect::<Vec<_>>());
}

#[test]
fn sphere_sites_lie_within_its_radius_and_count_its_volume() {
    let (centre, r) = ([0.013, -0.021, 0.007], 1.0);
    let mesh = TriangleMesh::uv_sphere(centre, r, 48, 96);
    let spacing = 0.05;
    let l = lattice([-1.2; 3], spacing, [48; 3]);
    let set = sites_inside_mesh(&mesh, &l);
    // the polyhedron lies between the sphere and the ball that touches its nearest face plane
    let r_in = (0..mesh.triangles.len()).map(|t| {
        let [a, b, c] = mesh.corners(t);
        let n = schemas::geometry::vec3::cross(
            schemas::geometry::vec3::sub(b, a),
            schemas::geometry::vec3::sub(c, a),
        );
        schemas::geometry::vec3::dot(n, schemas::geometry::vec3::sub(a, centre))
            / schemas::geometry::vec3::norm(n)
    });
    let r_in = schemas::validation::smallest(r_in, f64::INFINITY);
    assert!(r_in > 0.99 * r);
    for (s, x) in sites(&l) {
        let d = schemas::geometry::vec3::norm(schemas::geometry::vec3::sub(x, centre));
        if d > r * (1.0 + 1e-12) {
            assert!(!set.contains(s[0], s[1], s[2]), "site {s:?} at {d} > r");
        }
        if d < r_in * (1.0 - 1e-12) {
            assert!(set.contains(s[0], s[1], s[2]), "site {s:?} at {d} < r_in");
        }
    }
    // Counting sites measures the volume with cells of Δs³ centred on them; only cells the
    // surface cuts can be counted wrongly, each by at most one cell. They lie within √3/2 Δs
    // of the surface, about A √3 Δs / Δs³ of them, and their errors are of both signs and
    // cancel mostly: A / Δs² bounds the difference with a wide margin.
    let volume = mesh.signed_volume() / spacing.powi(3);
    let area: f64 = (0..mesh.triangles.len())
        .map(|t| mesh.triangle_area(t))
        .sum::<f64>()
        / spacing.powi(2);
    let n = set.count() as f64;
    assert!(
        (n - volume).abs() <= area,
        "{n} sites against V/Δs³ = {volume} (A/Δs² = {area})"
    );
    // and in fact far inside that bound
    assert!(
        (n - volume).abs() <= 0.05 * area,
        "{n} sites against V/Δs³ = {volume} (A/Δs² = {area})"
    );
}

#[test]
fn the_skin_of_a_big_cube_is_exactly_layers_deep() {
    let l = lattice([0.0; 3], 1.0, [40, 30, 70]);
    // sites 3..=34, 2..=27, 5..=66 inside
    let (lo, hi) = ([3usize, 2, 5], [34usize, 27, 66]);
    let mesh = TriangleMesh::cuboid(l.site_centre(lo), l.site_centre(hi));
    let set = sites_inside_mesh(&mesh, &l);
    assert_eq!(set.count(), 32 * 26 * 62);
    for layers in [1, 2, 4] {
        let skin = set.within_layers_of_outside(layers, true);
        let depth = |s: [usize; 3]| {
            (0..3)
                .map(|a| (s[a] - lo[a]).min(hi[a] - s[a]))
                .min()
                .unwrap_or(0)
        };
        for s in set.iter() {
            assert_eq!(
                skin.contains(s[0], s[1], s[2]),
                depth(s) < layers,
                "site {s:?}, {layers} layers"
            );
        }
        let inner = [32 - 2 * layers, 26 - 2 * layers, 62 - 2 * layers];
        assert_eq!(skin.count(), 32 * 26 * 62 - inner.iter().product::<usize>());
    }
    // a cube filling the lattice: its faces on the lattice's bounds are skin only when the
    // outside continues beyond the lattice
    let full = sites_inside_mesh(&TriangleMesh::cuboid(l.origin, l.upper_corner()), &l);
    assert_eq!(full.within_layers_of_outside(2, false).count(), 0);
    assert_eq!(
        full.within_layers_of_outside(2, true).count(),
        40 * 30 * 70 - 36 * 26 * 66
    );
}

#[test]
fn sites_below_a_terrain() {
    let grid = HeightGrid::from_fn(21, 11, [0.0, 0.0], [0.1, 0.2], |x, y| 0.3 + 0.2 * x - 0.1 * y)
        .unwrap_or_else(|e| panic!("{e}"));
    // the lattice reaches beyond the grid's centres (x ≤ 2, y ≤ 2) on the far side
    let l = lattice([0.0, 0.0, 0.0], 0.07, [35, 32, 12]);
    let set = sites_below_surface(|x, y| grid.height_at(x, y), &l);
    for (s, x) in sites(&l) {
        let on_grid = x[0] <= 2.0 && x[1] <= 2.0;
        let h = 0.3 + 0.2 * x[0] - 0.1 * x[1];
        if (x[2] - h).abs() > 1e-9 {
            assert_eq!(
                set.contains(s[0], s[1], s[2]),
                on_grid && x[2] < h,
                "site {s:?} at {x:?}"
            );
        }
    }
    assert!(set.count() > 1000);
}

#[test]
fn an_invalid_lattice_or_empty_mesh_gives_no_site() {
    let cube = TriangleMesh::cuboid([0.0; 3], [1.0; 3]);
    assert_eq!(
        sites_inside_mesh(&cube, &lattice([0.0; 3], 0.0, [4; 3])).count(),
        0
    );
    assert_eq!(
        sites_inside_mesh(&cube, &lattice([f64::NAN; 3], 0.1, [4; 3])).count(),
        0
    );
    assert_eq!(
        sites_inside_mesh(&TriangleMesh::default(), &lattice([0.0; 3], 0.1, [4; 3])).count(),
        0
    );
    assert_eq!(
        sites_inside_mesh(&cube, &lattice([0.0; 3], 0.1, [0, 4, 4])).count(),
        0
    );
}
