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
