//! Mesh solids and terrains on the GPU path (issue 38): their skins are fixed wall particles of
//! the initial state, stepped on the device like the tank's walls; the slab's column collapsing
//! onto a turned cube from an STL and up a terrain plane ends where the CPU's does, within the
//! f32 bound of `gpu_common/compare.rs`, and fluid pushed into either is found by the device's
//! detector at the step, particle and quantity the CPU names.

use crate::gpu_common;

use fluid_solver::{FluidSolver, Instability, Kind};
use gpu_common::compare::{self, STEPS};
use schemas::case::FluidConfig;
use schemas::geometry::{write_binary_stl, TriangleMesh};

/// A cube 6 cm a side turned 45° about y (a diamond in the x–z plane, across the slab's depth)
/// with its centre at (0.22, 0.03, 0.06) m, in the collapsing column's path, and a 1:1 beach
/// rising towards +x from x = 0.28 m.
const SCENE: &str = r#"
[[fluid.water.solid]]
mesh = "cube.stl"
rotate = [0.0, 45.0, 0.0]
translate = [0.22, 0.03, 0.06]

[[fluid.water.terrain]]
plane = { point = [0.28, 0.0, 0.0], normal = [-1.0, 0.0, 1.0] }
"#;

/// The slab with [`SCENE`], its files written to a fresh folder `name`.
fn scene(name: &str) -> FluidConfig {
    let dir = compare::folder(name);
    let half = [0.03; 3];
    write_binary_stl(
        &dir.join("cube.stl"),
        &TriangleMesh::cuboid(half.map(|h| -h), half),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    compare::slab(&dir, SCENE)
}

/// The same particles after 200 steps (0.1 s: the front passes the diamond and runs up the
/// beach), within the f32 bound on positions and walls' impulse; the scene's solids moved the
/// fluid by far more than that bound on the CPU.
#[test]
fn gpu_step_matches_cpu_step_with_a_mesh_solid_and_a_terrain() {
    let cfg = scene("scene-walls");
    let Some(runs) = compare::run_both(&cfg, STEPS) else {
        return;
    };
    let p = runs.cpu.particles();
    let inside = |i: usize| p.x[i] > 0.0 && p.x[i] < 0.4 && p.z[i] > 0.0 && p.z[i] < 0.3;
    let solid = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Wall.code() && inside(i))
        .count();
    println!("{solid} wall particles of the solid and the terrain inside the tank");
    assert!(solid > 50, "the scene built {solid} solid particles");
    compare::check_and_record(
        &runs,
        (
            "scene-walls",
            "E-MPS with a mesh solid and a terrain",
            "the slab's column (0.4 × 0.06 × 0.3 m tank) onto an STL cube turned 45° and a 1:1 terrain plane, 200 steps of 5e-4 s",
            "gpu_scene_walls.rs::gpu_step_matches_cpu_step_with_a_mesh_solid_and_a_terrain",
        ),
    );
    let bare = compare::run_cpu(&compare::slab(&compare::folder("scene-walls-bare"), ""), STEPS);
    compare::assert_visible("the solid and the terrain", &runs.cpu, &bare);
}

/// Runs up to 6 steps of `cfg` on the CPU and on the GPU, the first fluid particle (by id) moved
/// to `at` after the second; both findings.
fn findings(cfg: &FluidConfig, at: [f64; 3]) -> Option<(Instability, Instability)> {
    let dev = gpu_common::device()?;
    let mut cpu = FluidSolver::new(cfg);
    let mut gpu = FluidSolver::new(cfg);
    gpu.to_device(cfg, dev).unwrap_or_else(|e| panic!("{e}"));
    let run = |s: &mut FluidSolver| -> Instability {
        for k in 0..6 {
            if k == 2 {
                let p = s.particles_mut();
                let i = (0..p.len())
                    .filter(|&i| p.kind[i] == Kind::Fluid.code())
                    .min_by_key(|&i| p.id[i])
                    .unwrap_or_else(|| panic!("no fluid"));
                (p.x[i], p.y[i], p.z[i]) = (at[0], at[1], at[2]);
            }
            if let Err(e) = s.step(cfg.time_step) {
                return e;
            }
        }
        panic!("no instability was found")
    };
    let (a, b) = (run(&mut cpu), run(&mut gpu));
    println!("CPU: {a}\nGPU: {b}");
    Some((a, b))
}

/// A fluid particle put 2 spacings under the beach's surface (in the cube of the site
/// (0.37, 0.03, 0.05) m, whose six neighbours are below the plane too), then one put inside the
/// turned cube (in the cube of the site (0.21, 0.03, 0.05) m, 0.02 m from its centre in the L1
/// norm of the diamond's frame, whose half diagonal is 0.042 m), each 0.43 Δs from that site's
/// wall particle: each is found at the step after, as on the CPU.
#[test]
fn fluid_pushed_into_a_terrain_or_a_mesh_solid_is_found_as_on_the_cpu() {
    let cfg = scene("scene-walls-detector");
    for at in [[0.365, 0.025, 0.045], [0.205, 0.025, 0.045]] {
        let Some((a, b)) = findings(&cfg, at) else {
            return;
        };
        assert_eq!(
            (a.step, a.quantity, a.particle),
            (b.step, b.quantity, b.particle),
            "CPU: {a}\nGPU: {b}"
        );
        assert_eq!(b.step, 3, "{b}");
        assert!(
            b.message.contains("inside a solid from a mesh or a terrain"),
            "{b}"
        );
    }
}
