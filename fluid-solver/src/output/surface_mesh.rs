//! Free-surface mesh of the fluid particles, for viewing (issue 5; S1 drew its surfaces with
//! marching cubes).
//!
//! The SPH colour field `c(x) = Σ_j Δs³ W(|x − x_j|, r)`, with `W` the Wendland C2 kernel of
//! radius `r = 2 Δs` (`W = 21/(2π r³) (1 − q)⁴ (1 + 4q)`, q = d/r), is 1 on average inside a fluid
//! on a lattice (0.99 … 1.03 between and at the sites) and 0 away from it. The surface is its
//! iso-surface `c = ½`, which on a flat lattice face lies 0.49 … 0.50 Δs outside the last particle
//! layer, where the particles' volume `N Δs³` ends. The iso-surface is extracted by Naive Surface
//! Nets (crate `fast-surface-nets`) on a grid of cell `Δs / 2`. The kernel rounds edges and
//! corners: a box loses about 0.45 Δs² of area per Δs of edge.
//!
//! The grid is sparse: chunks of 16³ cells exist only where a fluid particle's kernel reaches,
//! each is sampled and meshed on its own (in parallel, a batch of chunks at a time), and the chunk
//! meshes are welded where they overlap (the cells on chunk borders) by their global cell index. A
//! lone particle (c ≤ 0.42 at its centre) is below the iso-level and is not drawn. The mesh has no
//! holes; where two sheets of water touch across a grid face, Surface Nets joins them along edges
//! shared by four triangles (not a manifold there: 373 such edges in the 129 k triangles of the dam
//! break at t = 0.3 s, Δs = 1 cm).

use crate::particles::kind::FLUID;
use crate::particles::Particles;
use fast_surface_nets::ndshape::{ConstShape, ConstShape3u32};
use fast_surface_nets::{surface_nets, SurfaceNetsBuffer};
use rayon::prelude::*;
use std::collections::HashMap;

/// Grid cell size, in particle spacings.
pub const CELL_IN_SPACINGS: f64 = 0.5;
/// Kernel radius of the colour field, in particle spacings.
pub const RADIUS_IN_SPACINGS: f64 = 2.0;
/// The iso-level: half the colour of the interior.
pub const ISO_LEVEL: f64 = 0.5;

/// Cells per chunk side; a chunk samples 18 points per side (one shared with each neighbour
/// behind and one ahead), the layout `surface_nets` needs for chunks that join without seams.
const CHUNK_CELLS: i64 = 16;
type ChunkShape = ConstShape3u32<18, 18, 18>;
const CHUNK_LAST_POINT: u32 = 17;
// A particle reaches only the chunks next to its own (see `surface_of_points`).
const _: () = assert!(RADIUS_IN_SPACINGS / CELL_IN_SPACINGS < (CHUNK_CELLS - 1) as f64);

/// Chunks meshed in parallel before their meshes are welded and dropped.
const CHUNKS_PER_BATCH: usize = 64;

/// Particles farther than this many grid cells from the origin (a run gone astray) are left out,
/// which keeps the integer cell indices far from overflow.
const MAX_CELLS_FROM_ORIGIN: f64 = 1.0e12;

/// A triangle mesh in world coordinates [m].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriangleMesh {
    pub vertices: Vec<[f64; 3]>,
    /// Unit outward normal at each vertex (the colour field's descending gradient).
    pub normals: Vec<[f32; 3]>,
    /// Vertex indices, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

/// Wendland C2 kernel of `q = d / r` without its normalisation `21/(2π r³)`: `(1 − q)⁴ (1 + 4q)` for q < 1.
fn wendland(q: f64) -> f64 {
    if q < 1.0 {
        let a = 1.0 - q;
        a * a * a * a * (1.0 + 4.0 * q)
    } else {
        0.0
    }
}

/// The sampling grid: point `i` (any integer triple) sits at `i · cell`.
#[derive(Debug, Clone, Copy)]
struct Grid {
    cell: f64,
    radius: f64,
    /// `Δs³ · 21 / (2π r³)`: a particle's volume times the kernel's normalisation.
    scale: f64,
}

impl Grid {
    fn new(spacing: f64) -> Grid {
        Grid {
            cell: CELL_IN_SPACINGS * spacing,
            radius: RADIUS_IN_SPACINGS * spacing,
            scale: spacing.powi(3) * 21.0
                / (2.0 * std::f64::consts::PI * (RADIUS_IN_SPACINGS * spacing).powi(3)),
        }
    }

    /// The chunk holding the grid cell that holds `p`.
    fn home_chunk(&self, p: [f64; 3]) -> [i64; 3] {
        p.map(|x| ((x / self.cell).floor() as i64).div_euclid(CHUNK_CELLS))
    }

    /// Adds the colour of the particle at `p` to the samples of the chunk whose first point is `base`.
    fn splat(&self, p: [f64; 3], base: [i64; 3], colour: &mut [f32]) {
        // In cell units, relative to the chunk's first point.
        let reach = self.radius / self.cell;
        let reach2 = reach * reach;
        let u = [0, 1, 2].map(|a| p[a] / self.cell - base[a] as f64);
        // Squared distances along each axis to the points within reach, from the first such point.
        let mut first = [0usize; 3];
        let mut d2 = [[0.0f64; 2 * CHUNK_CELLS as usize]; 3];
        let mut count = [0usize; 3];
        for a in 0..3 {
            let lo = (u[a] - reach).ceil().max(0.0);
            let hi = (u[a] + reach).floor().min(f64::from(CHUNK_LAST_POINT));
            first[a] = lo as usize;
            let mut x = lo;
            while x <= hi && count[a] < d2[a].len() {
                d2[a][count[a]] = (x - u[a]) * (x - u[a]);
                count[a] += 1;
                x += 1.0;
            }
        }
        for (k, dz2) in d2[2][..count[2]].iter().enumerate() {
            for (j, dy2) in d2[1][..count[1]].iter().enumerate() {
                let row = dz2 + dy2;
                if row >= reach2 {
                    continue;
                }
                let at =
                    ChunkShape::linearize([first[0] as u32, (first[1] + j) as u32, (first[2] + k) as u32]);
                for (i, dx2) in d2[0][..count[0]].iter().enumerate() {
                    let r2 = row + dx2;
                    if r2 < reach2 {
                        colour[at as usize + i] += (wendland(r2.sqrt() / reach) * self.scale) as f32;
                    }
                }
            }
        }
    }
}

/// The mesh of one chunk: vertices keyed by their global cell, triangles in local indices.
struct ChunkMesh {
    cells: Vec<[i64; 3]>,
    vertices: Vec<[f64; 3]>,
    normals: Vec<[f32; 3]>,
    indices: Vec<u32>,
}

/// The free surface of the fluid particles of `p` for particle spacing `spacing` > 0 [m] (as
/// `FluidConfig::validate` ensures). Other kinds are ignored, and so are particles with a
/// non-finite or astray position.
pub fn fluid_surface(p: &Particles, spacing: f64) -> TriangleMesh {
    let far = MAX_CELLS_FROM_ORIGIN * CELL_IN_SPACINGS * spacing;
    let points: Vec<[f64; 3]> = (0..p.len())
        .into_par_iter()
        .filter(|&i| p.kind[i] == FLUID)
        .map(|i| p.position(i))
        .filter(|x| x.iter().all(|c| c.abs() < far))
        .collect();
    surface_of_points(&points, spacing)
}

/// The iso-surface `c = ½` of the colour field of `points` (see the module doc).
fn surface_of_points(points: &[[f64; 3]], spacing: f64) -> TriangleMesh {
    if points.is_empty() {
        return TriangleMesh::default();
    }
    let grid = Grid::new(spacing);
    let homes: Vec<[i64; 3]> = points.par_iter().map(|&x| grid.home_chunk(x)).collect();
    let mut order: Vec<u32> = (0..points.len() as u32).collect();
    order.par_sort_unstable_by_key(|&i| homes[i as usize]);
    let mut bins: HashMap<[i64; 3], &[u32]> = HashMap::new();
    for run in order.chunk_by(|&a, &b| homes[a as usize] == homes[b as usize]) {
        bins.insert(homes[run[0] as usize], run);
    }
    // The kernel reaches 4 cells, less than a chunk: a particle touches only chunks next to its own.
    let mut active: Vec<[i64; 3]> = bins
        .keys()
        .flat_map(|&c| neighbours(c))
        .collect::<std::collections::HashSet<_>>()
        .into_iter()
        .collect();
    active.sort_unstable();

    // Meshed and welded a batch at a time, so that only one batch's chunk meshes are held at once.
    let mut welded = Welded::default();
    for batch in active.chunks(CHUNKS_PER_BATCH) {
        let chunks: Vec<ChunkMesh> = batch
            .par_iter()
            .map_init(SurfaceNetsBuffer::default, |buffer, &chunk| {
                mesh_chunk(&grid, chunk, points, &bins, buffer)
            })
            .flatten()
            .collect();
        for chunk in chunks {
            welded.add(chunk);
        }
    }
    welded.mesh
}

/// The 27 chunks around and including `c`.
fn neighbours(c: [i64; 3]) -> impl Iterator<Item = [i64; 3]> {
    (0..27).map(move |n| [c[0] + n % 3 - 1, c[1] + (n / 3) % 3 - 1, c[2] + n / 9 - 1])
}

/// Samples the colour on `chunk`'s 18³ points and meshes its iso-surface; `None` when the chunk
/// holds no surface.
fn mesh_chunk(
    grid: &Grid,
    chunk: [i64; 3],
    points: &[[f64; 3]],
    bins: &HashMap<[i64; 3], &[u32]>,
    buffer: &mut SurfaceNetsBuffer,
) -> Option<ChunkMesh> {
    let base = chunk.map(|c| c * CHUNK_CELLS);
    // Particles whose kernel reaches the chunk's points lie in this box.
    let lo = base.map(|b| b as f64 * grid.cell - grid.radius);
    let hi = base.map(|b| (b + i64::from(CHUNK_LAST_POINT)) as f64 * grid.cell + grid.radius);
    let mut colour = vec![0.0f32; ChunkShape::USIZE];
    for near in neighbours(chunk) {
        for &i in bins.get(&near).copied().unwrap_or_default() {
            let p = points[i as usize];
            if (0..3).all(|a| p[a] > lo[a] && p[a] < hi[a]) {
                grid.splat(p, base, &mut colour);
            }
        }
    }
    let iso = ISO_LEVEL as f32;
    let inside = colour.iter().filter(|&&c| c > iso).count();
    if inside == 0 || inside == colour.len() {
        return None;
    }
    // Negative inside, as `surface_nets` wants.
    let field: Vec<f32> = colour.iter().map(|&c| iso - c).collect();
    surface_nets(&field, &ChunkShape {}, [0; 3], [CHUNK_LAST_POINT; 3], buffer);
    if buffer.indices.is_empty() {
        return None;
    }
    let cells = buffer
        .surface_points
        .iter()
        .map(|l| [0, 1, 2].map(|a| base[a] + i64::from(l[a])))
        .collect();
    let vertices = buffer
        .positions
        .iter()
        .map(|l| [0, 1, 2].map(|a| (base[a] as f64 + f64::from(l[a])) * grid.cell))
        .collect();
    let normals = buffer.normals.iter().map(|&n| unit(n)).collect();
    Some(ChunkMesh {
        cells,
        vertices,
        normals,
        indices: buffer.indices.clone(),
    })
}

/// `n / |n|`, or zero for a zero vector.
fn unit(n: [f32; 3]) -> [f32; 3] {
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 {
        n.map(|c| c / len)
    } else {
        [0.0; 3]
    }
}

/// The chunk meshes joined so far. A vertex in a cell on a chunk's border (local cell 0 or
/// `CHUNK_CELLS` along some axis: chunks overlap by one cell) is made by every chunk sharing that
/// cell and kept once, found by its global cell; the others belong to one chunk only. Vertices no
/// triangle uses are dropped.
#[derive(Default)]
struct Welded {
    mesh: TriangleMesh,
    /// Global cell → vertex index, for border vertices.
    border: HashMap<[i64; 3], u32>,
}

impl Welded {
    fn add(&mut self, c: ChunkMesh) {
        let mut global = vec![u32::MAX; c.cells.len()];
        for t in c.indices.chunks_exact(3) {
            let mut tri = [0u32; 3];
            for (corner, &local) in tri.iter_mut().zip(t) {
                let l = local as usize;
                if global[l] == u32::MAX {
                    let mesh = &mut self.mesh;
                    let mut push = || {
                        mesh.vertices.push(c.vertices[l]);
                        mesh.normals.push(c.normals[l]);
                        (mesh.vertices.len() - 1) as u32
                    };
                    let on_border = c.cells[l].iter().any(|&x| x.rem_euclid(CHUNK_CELLS) == 0);
                    global[l] = if on_border {
                        *self.border.entry(c.cells[l]).or_insert_with(push)
                    } else {
                        push()
                    };
                }
                *corner = global[l];
            }
            self.mesh.triangles.push(tri);
        }
    }
}
