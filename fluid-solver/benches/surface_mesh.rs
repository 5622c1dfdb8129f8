//! Speed of the free-surface mesh (issue 5) on the seed's dam-break tank: the water column at
//! rest at Δs = 0.01 m and 0.005 m, and the breaking column at t = 0.3 s at Δs = 0.01 m, on 1 and
//! 2 threads. Prints the milliseconds to mesh (wall and CPU time) and to write the VTP, the
//! triangle count, and the edges used by one triangle (holes) or by more than two (non-manifold);
//! a closed mesh has none.

use fluid_solver::particles::Particles;
use fluid_solver::surface_mesh::{fluid_surface, TriangleMesh};
use fluid_solver::vtp::write_vtp;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::Case;
use std::collections::HashMap;
use std::path::PathBuf;
use std::time::Instant;

mod bench_process;
use bench_process::cpu_seconds;

/// Edges used by one triangle (holes) and by more than two (non-manifold).
fn bad_edges(mesh: &TriangleMesh) -> (usize, usize) {
    let mut uses: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &mesh.triangles {
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let once = uses.values().filter(|&&n| n == 1).count();
    (once, uses.values().filter(|&&n| n > 2).count())
}

fn fail(message: String) -> ! {
    eprintln!("error: {message}");
    std::process::exit(1);
}

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let path = root.join("cases/dam-break-tank/case.toml");
    let case = Case::load(&path).unwrap_or_else(|e| fail(e.to_string()));
    let Some(cfg) = case.fluid.values().next().cloned() else {
        fail(format!("{}: no [fluid.*] section", path.display()));
    };
    let out = root.join("out/bench-surface-mesh");
    std::fs::create_dir_all(&out).unwrap_or_else(|e| fail(format!("{}: {e}", out.display())));

    let mut states: Vec<(String, Particles, f64)> = Vec::new();
    for spacing in [0.01, 0.005] {
        let mut c = cfg.clone();
        c.spacing = spacing;
        let solver = FluidSolver::new(&c);
        states.push((
            format!("column at rest, Δs = {spacing}"),
            solver.particles().clone(),
            spacing,
        ));
    }
    let mut solver = FluidSolver::new(&cfg);
    solver.remove_gates();
    solver.advance_to(0.3).unwrap_or_else(|e| fail(e.to_string()));
    states.push((
        "breaking, t = 0.3 s, Δs = 0.01".into(),
        solver.particles().clone(),
        cfg.spacing,
    ));

    println!(
        "{:<32} {:>7} {:>9} {:>10} {:>9} {:>9} {:>10} {:>9} {:>10}",
        "state",
        "threads",
        "fluid",
        "triangles",
        "edges ×1",
        "edges > 2",
        "mesh [ms]",
        "cpu [ms]",
        "write [ms]"
    );
    for (name, particles, spacing) in &states {
        for threads in [1usize, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap_or_else(|e| fail(format!("cannot start {threads} threads: {e}")));
            let reps = 3;
            let cpu = 1e3 * cpu_seconds();
            let start = Instant::now();
            let mut mesh = TriangleMesh::default();
            for _ in 0..reps {
                mesh = pool.install(|| fluid_surface(particles, *spacing));
            }
            let mesh_ms = 1e3 * start.elapsed().as_secs_f64() / f64::from(reps);
            let mesh_cpu_ms = (1e3 * cpu_seconds() - cpu) / f64::from(reps);
            let file = out.join("surface.vtp");
            let start = Instant::now();
            write_vtp(&file, &mesh, &mut schemas::participant::DiscardProgress)
                .unwrap_or_else(|e| fail(format!("{}: {e}", file.display())));
            let write_ms = 1e3 * start.elapsed().as_secs_f64();
            let (holes, non_manifold) = bad_edges(&mesh);
            println!(
                "{:<32} {:>7} {:>9} {:>10} {:>9} {:>9} {:>10.1} {:>9.0} {:>10.1}",
                name,
                threads,
                particles.count(Kind::Fluid),
                mesh.triangles.len(),
                holes,
                non_manifold,
                mesh_ms,
                mesh_cpu_ms,
                write_ms
            );
        }
    }
}
