//! The lattice sites inside a closed triangle mesh ([`sites_inside_mesh`]) and below a terrain
//! ([`sites_below_surface`]): where wall particles are built.
//!
//! **Inside a mesh**, by rays along z: each column of sites `(i, j)` is the vertical line through
//! `(x_i, y_j)`; the triangles it crosses, sorted by height, give the winding number along it
//! (`+1` entering through a downward-facing triangle, `−1` leaving through an upward-facing one),
//! and a site is inside where the winding number is positive (for a closed, consistently
//! oriented mesh: between an entering and a leaving crossing; nested shells and overlapping
//! solids work too). The triangles are binned by their y-extent onto rows of columns, and rows are
//! filled in parallel.
//!
//! *Lines through edges and vertices.* Whether the line crosses a triangle is decided by the signs
//! of the three edge functions `w = (v − u) × (p − u)` of its xy-projection. A line through an
//! edge or vertex (some `w = 0`) is decided by simulation of simplicity (Edelsbrunner and Mücke,
//! "Simulation of simplicity", ACM Trans. Graph. 9(1), 1990): the line is moved to
//! `(x + ε, y + ε²)`, which gives `w = 0` the sign of `u_y − v_y`, or of `v_x − u_x` when
//! `u_y = v_y`. Each edge function is computed in one canonical vertex order (and negated for the
//! other), so the two triangles sharing an edge agree exactly: the moved line crosses exactly one
//! of two triangles that continue a surface across their shared edge, and both or neither where
//! the surface folds back (a silhouette). Vertical triangles are never crossed.
//!
//! *Sites on the surface count as inside* (the closed solid, as an axis-aligned box's
//! `contains_point` with its faces included): the crossings' intervals are closed, and wherever
//! the unmoved line touches a triangle only on its boundary (some `w = 0`) or runs within a
//! vertical triangle, the touched points and segments are added. This is exact when the
//! coordinates involved are exact in floating point, as for a box whose faces are at lattice
//! coordinates ([`Lattice::coordinate`]); otherwise a site within rounding of the surface may go
//! either way.
//!
//! **Below a terrain**: the sites with `z ≤ h(x, y)` ([`HeightGrid::height_at`](super::HeightGrid::height_at)); none in a column
//! outside the grid's centres.

use super::lattice::Lattice;
use super::site_set::{set_bits, SiteSet};
use super::triangle_mesh::TriangleMesh;
use rayon::prelude::*;

/// The sites of `lattice` inside the closed mesh or on its surface (module doc for the method and
/// the rule on the surface). Meaningful for a mesh that passes
/// [`TriangleMesh::check_solid`]; triangles naming a vertex that does not exist are skipped.
/// An invalid lattice ([`Lattice::check`]) gives no site.
pub fn sites_inside_mesh(mesh: &TriangleMesh, lattice: &Lattice) -> SiteSet {
    let mut set = SiteSet::empty(lattice);
    if lattice.check().is_err() || set.words_per_column() == 0 {
        return set;
    }
    let triangles: Vec<[[f64; 3]; 3]> = mesh
        .triangles
        .iter()
        .filter_map(|t| {
            let corner = |c: usize| mesh.vertices.get(t[c] as usize).copied();
            Some([corner(0)?, corner(1)?, corner(2)?])
        })
        .collect();
    let bins = RowBins::new(&triangles, lattice);
    let w = set.words_per_column();
    set.rows_mut().for_each(|(j, row)| {
        fill_row(lattice, &triangles, bins.row(j), j, row, w);
    });
    set
}

/// The sites of `lattice` at or below a terrain, `z ≤ h(x, y)`, in the columns where `height`
/// gives one (for a grid, [`HeightGrid::height_at`](super::HeightGrid::height_at): inside the hull of its cell centres); none in
/// the other columns. An invalid lattice ([`Lattice::check`]) gives no site.
pub fn sites_below_surface(height: impl Fn(f64, f64) -> Option<f64> + Sync, lattice: &Lattice) -> SiteSet {
    let mut set = SiteSet::empty(lattice);
    if lattice.check().is_err() {
        return set;
    }
    let w = set.words_per_column();
    set.rows_mut().for_each(|(j, row)| {
        let y = lattice.coordinate(1, j);
        for (i, column) in row.chunks_exact_mut(w.max(1)).enumerate() {
            if let Some(h) = height(lattice.coordinate(0, i), y) {
                set_bits(column, lattice.indices_within(2, f64::NEG_INFINITY, h));
            }
        }
    });
    set
}

/// The triangles whose y-extent covers each row of columns (compressed rows: the triangles of
/// row `j` are `entries[start[j]..start[j + 1]]`).
struct RowBins {
    start: Vec<usize>,
    entries: Vec<u32>,
}

impl RowBins {
    fn new(triangles: &[[[f64; 3]; 3]], lattice: &Lattice) -> RowBins {
        let ny = lattice.n[1];
        let rows: Vec<std::ops::Range<usize>> = triangles
            .par_iter()
            .map(|t| {
                let (lo, hi) = extent(t, 1);
                lattice.indices_within(1, lo, hi)
            })
            .collect();
        let mut start = vec![0usize; ny + 1];
        for r in &rows {
            for j in r.clone() {
                start[j + 1] += 1;
            }
        }
        for j in 0..ny {
            start[j + 1] += start[j];
        }
        let mut cursor = start.clone();
        let mut entries = vec![0u32; start[ny]];
        for (t, r) in rows.iter().enumerate() {
            for j in r.clone() {
                entries[cursor[j]] = t as u32;
                cursor[j] += 1;
            }
        }
        RowBins { start, entries }
    }

    fn row(&self, j: usize) -> &[u32] {
        &self.entries[self.start[j]..self.start[j + 1]]
    }
}

/// `(min, max)` of the triangle's coordinates along `axis`.
fn extent(t: &[[f64; 3]; 3], axis: usize) -> (f64, f64) {
    let c = [t[0][axis], t[1][axis], t[2][axis]];
    (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2]))
}

/// Fills row `j` (its `n_x` columns of `w` words each) from the triangles binned onto it.
fn fill_row(
    lattice: &Lattice,
    triangles: &[[[f64; 3]; 3]],
    row_triangles: &[u32],
    j: usize,
    row: &mut [u64],
    w: usize,
) {
    let y = lattice.coordinate(1, j);
    // (column, z, change of winding number going up)
    let mut crossings: Vec<(usize, f64, i32)> = Vec::new();
    // (column, z_lo, z_hi): points and segments where the line touches the surface
    let mut touches: Vec<(usize, f64, f64)> = Vec::new();
    for &t in row_triangles {
        let tri = &triangles[t as usize];
        let (lo, hi) = extent(tri, 0);
        for i in lattice.indices_within(0, lo, hi) {
            let contact = line_contact(tri, [lattice.coordinate(0, i), y]);
            if let Some((z, dir)) = contact.crossing {
                crossings.push((i, z, dir));
            }
            if let Some((lo, hi)) = contact.touch {
                touches.push((i, lo, hi));
            }
        }
    }
    if crossings.is_empty() && touches.is_empty() {
        return;
    }
    crossings.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    touches.sort_unstable_by_key(|t| t.0);
    for group in crossings.chunk_by(|a, b| a.0 == b.0) {
        let column = &mut row[group[0].0 * w..(group[0].0 + 1) * w];
        let mut winding = 0;
        let mut entered = None;
        for level in group.chunk_by(|a, b| a.1 == b.1) {
            let z = level[0].1;
            let before = winding;
            winding += level.iter().map(|c| c.2).sum::<i32>();
            if before <= 0 && winding > 0 {
                entered = Some(z);
            } else if before > 0 && winding <= 0 {
                if let Some(from) = entered.take() {
                    set_bits(column, lattice.indices_within(2, from, z));
                }
            }
        }
    }
    for &(i, lo, hi) in &touches {
        set_bits(&mut row[i * w..(i + 1) * w], lattice.indices_within(2, lo, hi));
    }
}

/// How the vertical line through a point meets one triangle.
#[derive(Debug, Default, PartialEq)]
struct Contact {
    /// The moved line (module doc) crosses the triangle at height `z`; the winding number changes
    /// by `dir` going up (`+1` through a downward-facing triangle).
    crossing: Option<(f64, i32)>,
    /// The line itself meets the triangle only on its boundary, or runs within a vertical
    /// triangle: the heights `[lo, hi]` it touches.
    touch: Option<(f64, f64)>,
}

/// The edge function `(v − u) × (p − u)` in xy (positive when `p` is left of `u → v`), computed
/// in a canonical order of `u` and `v` so that it is exactly antisymmetric.
fn edge_function(u: [f64; 3], v: [f64; 3], p: [f64; 2]) -> f64 {
    let raw = |u: [f64; 3], v: [f64; 3]| (v[0] - u[0]) * (p[1] - u[1]) - (v[1] - u[1]) * (p[0] - u[0]);
    if u[0] < v[0] || (u[0] == v[0] && u[1] <= v[1]) {
        raw(u, v)
    } else {
        -raw(v, u)
    }
}

/// The sign of the edge function at the moved point `p + (ε, ε²)` where it is zero at `p`:
/// `(v − u) × (ε, ε²) = (v_x − u_x) ε² − (v_y − u_y) ε`. Zero for an edge of no length in xy.
fn perturbed_sign(u: [f64; 3], v: [f64; 3]) -> i32 {
    if u[1] != v[1] {
        if u[1] > v[1] {
            1
        } else {
            -1
        }
    } else if u[0] != v[0] {
        if v[0] > u[0] {
            1
        } else {
            -1
        }
    } else {
        0
    }
}

fn sign(x: f64) -> i32 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

/// How the vertical line through `p` meets the triangle `t` (module doc).
fn line_contact(t: &[[f64; 3]; 3], p: [f64; 2]) -> Contact {
    let [a, b, c] = *t;
    // w[m] is the edge function of the edge opposite corner m
    let edges = [(b, c), (c, a), (a, b)];
    let w = edges.map(|(u, v)| edge_function(u, v, p));
    let moved = std::array::from_fn::<i32, 3, _>(|m| match sign(w[m]) {
        0 => perturbed_sign(edges[m].0, edges[m].1),
        s => s,
    });
    let mut contact = Contact::default();
    let sum = w[0] + w[1] + w[2];
    if moved[0] != 0 && moved[0] == moved[1] && moved[1] == moved[2] && sum != 0.0 {
        contact.crossing = Some((height_at(t, w, sum), -moved[0]));
    }
    let on_edge = w.contains(&0.0);
    let signs = w.map(sign);
    let closed_inside = !signs.contains(&1) || !signs.contains(&-1);
    if on_edge && closed_inside {
        if signs.iter().all(|&s| s == 0) {
            contact.touch = vertical_segment(t, p);
        } else if sum != 0.0 {
            let z = height_at(t, w, sum);
            contact.touch = Some((z, z));
        }
    }
    contact
}

/// The height of the triangle's plane above `p` from its edge functions (barycentric weights
/// `w / sum`), taken from the corner of largest weight so that it is exact at a corner and on a
/// horizontal triangle.
fn height_at(t: &[[f64; 3]; 3], w: [f64; 3], sum: f64) -> f64 {
    let base = (0..3).fold(0, |m, n| if w[n].abs() > w[m].abs() { n } else { m });
    let z0 = t[base][2];
    let mut delta = 0.0;
    for n in 0..3 {
        if n != base {
            delta += w[n] * (t[n][2] - z0);
        }
    }
    z0 + delta / sum
}

/// The heights `[lo, hi]` where the vertical line through `p` meets a triangle whose projection
/// is a segment (or a point) containing `p`: the edges' heights at `p`, parametrised along the
/// axis (x or y) of the projection's larger extent. `None` when `p` is beyond the projection.
fn vertical_segment(t: &[[f64; 3]; 3], p: [f64; 2]) -> Option<(f64, f64)> {
    let (x_lo, x_hi) = extent(t, 0);
    let (y_lo, y_hi) = extent(t, 1);
    if p[0] < x_lo || p[0] > x_hi || p[1] < y_lo || p[1] > y_hi {
        return None;
    }
    let axis = if x_hi - x_lo >= y_hi - y_lo { 0 } else { 1 };
    let s = p[axis];
    let mut range: Option<(f64, f64)> = None;
    let mut add = |z: f64| {
        range = Some(range.map_or((z, z), |(lo, hi)| (lo.min(z), hi.max(z))));
    };
    for (u, v) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
        let (su, sv) = (u[axis], v[axis]);
        if s == su {
            add(u[2]);
        }
        if s == sv {
            add(v[2]);
        }
        if (su < s && s < sv) || (sv < s && s < su) {
            add(u[2] + (s - su) / (sv - su) * (v[2] - u[2]));
        }
    }
    range
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::HeightGrid;

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
            let r = crate::geometry::rotation_matrix(rotate);
            let set = sites_inside_mesh(&mesh, &l);
            for (s, x) in sites(&l) {
                let d = super::super::vec3::sub(x, centre);
                // the site's coordinates in the box's frame: Rᵀ d
                let local: [f64; 3] = std::array::from_fn(|a| (0..3).map(|b| r[b][a] * d[b]).sum());
                let margin =
                    crate::validation::smallest((0..3).map(|a| half[a] - local[a].abs()), f64::INFINITY);
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
            let n = super::super::vec3::cross(super::super::vec3::sub(b, a), super::super::vec3::sub(c, a));
            super::super::vec3::dot(n, super::super::vec3::sub(a, centre)) / super::super::vec3::norm(n)
        });
        let r_in = crate::validation::smallest(r_in, f64::INFINITY);
        assert!(r_in > 0.99 * r);
        for (s, x) in sites(&l) {
            let d = super::super::vec3::norm(super::super::vec3::sub(x, centre));
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
}
