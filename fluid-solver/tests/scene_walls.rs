//! Walls from geometry files (issue 37): a solid from an STL cube is the wall box of the same
//! extent particle for particle; a sphere's wall particles are its skin (inside it, none deeper
//! than `wall_layers` sites); a terrain under a plane gives ISPH's wall normals the plane's
//! direction; still water filled over a beach by a block stays off the terrain.

use fluid_solver::isph::kernel::Wendland;
use fluid_solver::isph::neighbour_list::{cell_edge, NeighbourList};
use fluid_solver::isph::walls;
use fluid_solver::neighbour_search::CellGrid;
use fluid_solver::vector_field::VectorField;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::{Case, FluidConfig};
use schemas::geometry::{write_binary_stl, TriangleMesh};
use schemas::validation::{largest, record, smallest, Record};
use std::path::PathBuf;

fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("scene-walls-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

/// The fluid section of a 0.6 × 0.4 × 0.4 m tank at Δs = 0.02 m with a water block on its left
/// and `extra` appended, loaded from `dir` (where its files are).
fn tank(dir: &std::path::Path, extra: &str, method: &str, spacing: f64) -> FluidConfig {
    let text = format!(
        r#"[case]
name = "walls"
end_time = 1.0

[fluid.tank]
method = "{method}"
spacing = {spacing}
time_step = 1.0e-3
sound_speed = 10.0
output_interval = 0.1
tank = {{ min = [0.0, 0.0, 0.0], max = [0.6, 0.4, 0.4] }}

[[fluid.tank.block]]
min = [0.0, 0.0, 0.0]
max = [0.1, 0.4, 0.2]
{extra}"#
    );
    let case = Case::parse(&dir.join("case.toml"), text).unwrap_or_else(|e| panic!("{e}"));
    case.fluid["tank"].clone()
}

/// (position, kind) of every particle, sorted.
fn sites(solver: &FluidSolver) -> Vec<([i64; 3], u8)> {
    let p = solver.particles();
    let mut v: Vec<([i64; 3], u8)> = (0..p.len())
        .map(|i| {
            (
                [p.x[i], p.y[i], p.z[i]].map(|c| (c * 1e6).round() as i64),
                p.kind[i],
            )
        })
        .collect();
    v.sort_unstable();
    v
}

#[test]
fn an_stl_cube_gives_the_particles_of_the_wall_box_of_the_same_extent() {
    let dir = folder("cube");
    // 0.1 m: five sites a side, all within wall_layers = 4 of its outside
    let (min, max) = ([0.3, 0.1, 0.0], [0.4, 0.2, 0.1]);
    write_binary_stl(&dir.join("cube.stl"), &TriangleMesh::cuboid(min, max))
        .unwrap_or_else(|e| panic!("{e}"));
    let from_mesh = FluidSolver::new(&tank(
        &dir,
        "\n[[fluid.tank.solid]]\nmesh = \"cube.stl\"\n",
        "emps",
        0.02,
    ));
    let from_box = FluidSolver::new(&tank(
        &dir,
        &format!("\n[[fluid.tank.wall]]\nmin = {min:?}\nmax = {max:?}\n"),
        "emps",
        0.02,
    ));
    let (a, b) = (sites(&from_mesh), sites(&from_box));
    let walls = |v: &[([i64; 3], u8)]| v.iter().filter(|s| s.1 == Kind::Wall.code()).count();
    println!("{} particles, {} of them walls", a.len(), walls(&a));
    assert_eq!(a.len(), b.len());
    assert!(a == b, "the mesh cube's particles differ from the wall box's");
}

#[test]
fn a_sphere_is_built_as_its_skin_inside_its_surface() {
    let dir = folder("sphere");
    let (centre, r) = ([0.4, 0.2, 0.2], 0.15);
    let sphere = TriangleMesh::uv_sphere(centre, r, 48, 96);
    write_binary_stl(&dir.join("ball.stl"), &sphere).unwrap_or_else(|e| panic!("{e}"));
    let cfg = tank(
        &dir,
        "\n[[fluid.tank.solid]]\nmesh = \"ball.stl\"\n",
        "emps",
        0.01,
    );
    let solver = FluidSolver::new(&cfg);
    let p = solver.particles();
    let ds = cfg.spacing;
    let dist: Vec<f64> = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Wall.code())
        .map(|i| [p.x[i], p.y[i], p.z[i]])
        .filter(|x| x[0] > 0.0 && x[0] < 0.6 && x[1] > 0.0 && x[1] < 0.4 && x[2] > 0.0)
        .map(|x| {
            ((x[0] - centre[0]).powi(2) + (x[1] - centre[1]).powi(2) + (x[2] - centre[2]).powi(2)).sqrt()
        })
        .collect();
    let outer = largest(dist.iter().copied(), 0.0);
    let inner = smallest(dist.iter().copied(), f64::INFINITY);
    println!(
        "{} sphere particles, at {:.4} … {:.4} m from the centre (r = {r} m)",
        dist.len(),
        inner,
        outer
    );
    // The mesh's facets lie inside the true sphere by at most r (1 − cos(π/48)) = 0.3 mm, so a
    // site inside the mesh lies within r; the outermost sites lie within a lattice diagonal
    // (√3 Δs) of the surface (a site further in has its whole cube inside). A site is skin when
    // the cube of half-side wall_layers Δs around it reaches outside the sphere: its farthest
    // corner, √3 wall_layers Δs away, must lie beyond r, so none lies deeper than that (plus
    // the facets' 0.3 mm), and the centre, 15 sites in, is empty.
    assert!(outer <= r + 1e-9, "a particle outside the sphere: {outer}");
    assert!(
        outer >= r - 3f64.sqrt() * ds,
        "the outer layer is {} deep",
        r - outer
    );
    let skin =
        3f64.sqrt() * f64::from(cfg.wall_layers) * ds + r * (1.0 - (std::f64::consts::PI / 48.0).cos());
    assert!(
        inner >= r - skin,
        "a particle {} deep, below the skin ({skin} m)",
        r - inner
    );
}

#[test]
fn a_plane_beach_gives_isph_wall_normals_along_the_plane_normal_and_water_fills_above_it() {
    let started = std::time::Instant::now();
    let dir = folder("beach");
    // a 1:2 beach rising towards +x from x = 0.2 m, with water up to 0.2 m over the tank
    let beach = "\n[[fluid.tank.terrain]]\nplane = { point = [0.2, 0.0, 0.0], normal = [-1.0, 0.0, 2.0] }\n";
    let mut cfg = tank(&dir, beach, "isph", 0.02);
    cfg.block[0].max = [0.6, 0.4, 0.2];
    let solver = FluidSolver::new(&cfg);
    let p = solver.particles().clone();
    let height = |x: f64| 0.5 * (x - 0.2);
    let inside = |i: usize| p.x[i] > 0.0 && p.x[i] < 0.6 && p.y[i] > 0.0 && p.y[i] < 0.4 && p.z[i] > 0.0;
    let ds = cfg.spacing;
    let fluid_below = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid.code() && p.z[i] <= height(p.x[i]))
        .count();
    let terrain = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Wall.code() && inside(i))
        .count();
    let deepest = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Wall.code() && inside(i))
        .map(|i| height(p.x[i]) - p.z[i]);
    let deepest = largest(deepest, 0.0);
    println!("{terrain} terrain particles, the deepest {deepest:.3} m under the surface");
    assert_eq!(fluid_below, 0, "water filled below the beach");
    // The skin under a 1:2 slope: a site is skin when the cube of half-side wall_layers Δs
    // around it reaches above the plane, whose corner on the lower side (−x) lies wall_layers Δs
    // up and wall_layers Δs / 2 lower on the plane: wall_layers × 1.5 Δs under it at most, plus
    // the half spacing a site's height has off the plane.
    assert!(
        deepest <= (f64::from(cfg.wall_layers) * 1.5 + 0.5) * ds + 1e-12,
        "{deepest}"
    );

    // The normals at both ISPH supports: S2-8's 2.4 Δs and the symmetric forms' 2.0 Δs.
    let mut q = p.clone();
    let d = solver.domain();
    let n = [-1.0 / 5f64.sqrt(), 0.0, 2.0 / 5f64.sqrt()];
    let angle = |m: [f64; 3]| {
        let len = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        ((m[0] * n[0] + m[1] * n[1] + m[2] * n[2]) / len)
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    };
    let mut at = Vec::new();
    for radius in [2.4, 2.0] {
        let k = Wendland::new(ds, radius);
        let mut grid = CellGrid::with_cell(d.lo, [d.hi[0], d.hi[1], d.hi[2].max(1.0)], cell_edge(ds, radius));
        grid.sort(&mut q, &mut Vec::new());
        let mut list = NeighbourList::default();
        list.build(&grid, &q, &k);
        let mut normals = VectorField::default();
        walls::normals(&k, &list, &q, &mut normals);
        // the terrain's outer layer under the water, away from the tank's walls and the beach's toe
        let slope: Vec<[f64; 3]> = (0..q.len())
            .filter(|&w| {
                q.kind[w] == Kind::Wall.code()
                    && q.x[w] > 0.3
                    && q.x[w] < 0.55
                    && q.y[w] > 0.1
                    && q.y[w] < 0.3
                    && q.z[w] > height(q.x[w]) - ds
                    && q.z[w] < 0.2
            })
            .map(|w| [normals.x[w], normals.y[w], normals.z[w]])
            .collect();
        assert!(!slope.is_empty());
        let sum = slope
            .iter()
            .fold([0.0; 3], |s, m| [s[0] + m[0], s[1] + m[1], s[2] + m[2]]);
        let worst = largest(slope.iter().map(|&m| angle(m)), 0.0);
        println!(
            "support {radius} Δs: {} slope particles: their mean normal {:.2}° off the plane's, each at most {worst:.2}°",
            slope.len(),
            angle(sum)
        );
        at.push((radius, angle(sum), worst));
    }
    // A 1:2 staircase of lattice sites: one site up every two along x, so its outer layer
    // alternates between a site at a riser's foot and one on a tread, whose normals (kernel sums
    // over the solid around them) lean towards the riser's and the tread's (measured at 2.4 Δs:
    // 58.7° and 75.0° of elevation against the plane's 63.4°, 4.7° and 11.6° off; at 2.0 Δs the
    // tread's leans 18.3° off, 30 Nov 2026). The mean over the slope is what the water feels over
    // a spacing or two: within 5° at both supports; each site within 15° at 2.4 Δs (reported at
    // 2.0 Δs, where no bound is derived yet).
    let (_, mean, worst) = at[0];
    record(Record {
        id: "scene-terrain-slope-normals".into(),
        capability: "ISPH wall normals on a terrain plane ([[terrain]] plane, 1:2)".into(),
        reference: "the plane's normal".into(),
        case: "1:2 beach in a 0.6 × 0.4 × 0.4 m tank".into(),
        resolution: "ISPH, Δs = 0.02 m, support 2.4 Δs".into(),
        measure: "angle between the slope's mean wall normal and the plane's".into(),
        value: mean,
        bound: Some(5.0),
        bound_source: "a staircase's steps repeat within the kernel's support; each site within 15°".into(),
        unit: "deg".into(),
        source: "fluid-solver/tests/scene_walls.rs::a_plane_beach_gives_isph_wall_normals_along_the_plane_normal_and_water_fills_above_it".into(),
        run_time_s: started.elapsed().as_secs_f64(),
        date: String::new(),
        machine: String::new(),
        note: Some(format!(
            "2.0 Δs: {:.2}°, worst site {:.2}°",
            at[1].1, at[1].2
        )),
    });
    for &(radius, mean, _) in &at {
        assert!(mean < 5.0, "support {radius} Δs: mean {mean}°");
    }
    assert!(worst < 15.0, "support 2.4 Δs: worst {worst}°");
}

/// The stability monitor finds fluid inside a terrain, as inside a wall box: a water particle
/// moved 3 spacings under the beach's surface stops the next step, naming it.
#[test]
fn fluid_pushed_into_a_terrain_stops_the_run_naming_the_particle() {
    let dir = folder("into-terrain");
    let beach = "\n[[fluid.tank.terrain]]\nplane = { point = [0.2, 0.0, 0.0], normal = [-1.0, 0.0, 2.0] }\n";
    let mut cfg = tank(&dir, beach, "emps", 0.02);
    cfg.block[0].max = [0.6, 0.4, 0.2];
    let mut solver = FluidSolver::new(&cfg);
    solver.step(1.0e-3).unwrap_or_else(|e| panic!("{e}"));
    let p = solver.particles_mut();
    let i = (0..p.len())
        .find(|&i| p.kind[i] == Kind::Fluid.code() && p.x[i] > 0.45 && p.y[i] > 0.1 && p.y[i] < 0.3)
        .unwrap_or_else(|| panic!("no water over the beach"));
    p.z[i] = 0.5 * (p.x[i] - 0.2) - 3.0 * cfg.spacing;
    let id = p.id[i];
    let e = solver
        .step(1.0e-3)
        .expect_err("fluid inside the terrain must stop the run");
    println!("{e}");
    assert_eq!(e.particle, Some(id));
    assert!(
        e.to_string().contains("inside a solid from a mesh or a terrain"),
        "{e}"
    );
}
