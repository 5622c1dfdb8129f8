//! Filling a lattice of about 1e7 sites (215³) from a closed binary STL of about 1e5 triangles (a
//! UV sphere written to a temporary file and read back, the reading timed) and from a 1000 × 1000
//! ESRI ASCII height grid (written and read back likewise), then taking each solid's skin 3 layers
//! deep. Prints a table of seconds.
//!
//! Run: `cargo bench -p schemas --bench lattice_fill`.
//! Goal: each fill, reading included, under 10 s on a 2-core machine.

use schemas::geometry::{
    read_height_grid, read_mesh, sites_below_surface, sites_inside_mesh, write_ascii_grid, write_binary_stl,
    HeightGrid, Lattice, TriangleMesh,
};
use std::fmt::Display;
use std::path::PathBuf;
use std::time::Instant;

/// Prints `what` and the error, then exits: a benchmark has nobody to hand errors to.
fn or_die<T, E: Display>(result: Result<T, E>, what: &str) -> T {
    result.unwrap_or_else(|e| {
        eprintln!("lattice_fill: {what}: {e}");
        std::process::exit(1)
    })
}

/// Runs `f` and returns its result and the seconds it took.
fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let start = Instant::now();
    let value = f();
    (value, start.elapsed().as_secs_f64())
}

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("lattice-fill-bench-{}-{name}", std::process::id()))
}

const LAYERS: usize = 3;

fn main() {
    let n = 215;
    let lattice = Lattice {
        origin: [0.0; 3],
        spacing: 1.0 / n as f64,
        n: [n; 3],
    };
    println!(
        "lattice {n}³ = {} sites, {} threads\n",
        lattice.site_count(),
        rayon::current_num_threads()
    );
    println!("| input | size | read [s] | fill [s] | read + fill [s] | sites inside | skin {LAYERS} layers [s] | skin sites |");
    println!("|---|---|---|---|---|---|---|---|");

    // a closed sphere of about 1e5 triangles, as binary STL
    let stl = scratch("sphere.stl");
    let sphere = TriangleMesh::uv_sphere([0.5; 3], 0.45, 224, 224);
    or_die(write_binary_stl(&stl, &sphere), "writing the sphere");
    let (mesh, read) = timed(|| {
        let mesh = or_die(read_mesh(&stl), "reading the sphere");
        or_die(
            mesh.check_solid().map_err(|e| e.in_file(&stl)),
            "checking the sphere",
        );
        mesh
    });
    let _ = std::fs::remove_file(&stl);
    let (inside, fill) = timed(|| sites_inside_mesh(&mesh, &lattice));
    let (skin, skin_time) = timed(|| inside.within_layers_of_outside(LAYERS, true));
    println!(
        "| UV sphere, binary STL (read + check_solid) | {} triangles | {read:.3} | {fill:.3} | {:.3} | {} | {skin_time:.3} | {} |",
        mesh.triangles.len(),
        read + fill,
        inside.count(),
        skin.count()
    );

    // a 1000 × 1000 terrain as an ESRI ASCII grid
    let asc = scratch("terrain.asc");
    let cells = 1000;
    let size = 1.0 / cells as f64;
    let terrain = or_die(
        HeightGrid::from_fn(cells, cells, [0.5 * size; 2], [size; 2], |x, y| {
            0.3 + 0.1 * (7.0 * x).sin() * (5.0 * y).cos() + 0.05 * x
        }),
        "making the terrain",
    );
    or_die(write_ascii_grid(&asc, &terrain), "writing the terrain");
    let (grid, read) = timed(|| or_die(read_height_grid(&asc), "reading the terrain"));
    let _ = std::fs::remove_file(&asc);
    let (below, fill) = timed(|| sites_below_surface(|x, y| grid.height_at(x, y), &lattice));
    let (skin, skin_time) = timed(|| below.within_layers_of_outside(LAYERS, false));
    println!(
        "| terrain, ESRI ASCII grid | {cells} × {cells} cells | {read:.3} | {fill:.3} | {:.3} | {} | {skin_time:.3} | {} |",
        read + fill,
        below.count(),
        skin.count()
    );
}
