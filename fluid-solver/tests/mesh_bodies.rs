//! Bodies from meshes (issue 37): a body from an STL cube is the box body of the same extent
//! particle for particle, and its loads after a short run next to a water column are the box
//! body's; a mesh body with `min`/`max` too, an open mesh and a missing file are refused naming
//! the key and the file (a mesh body on the GPU: `gpu_mesh_bodies.rs`).

use fluid_solver::{FluidSolver, Kind};
use schemas::case::{Case, CaseError, FluidConfig};
use schemas::geometry::{write_binary_stl, TriangleMesh};
use std::path::{Path, PathBuf};

fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mesh-bodies-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

/// A 0.6 × 0.4 × 0.4 m tank at Δs = 0.02 m with a water column on its left and `extra`
/// appended, parsed from `dir` (where its files are).
fn parse(dir: &Path, extra: &str) -> Result<Case, CaseError> {
    parse_with(dir, "", extra)
}

/// As [`parse`], with `settings` among the section's keys.
fn parse_with(dir: &Path, settings: &str, extra: &str) -> Result<Case, CaseError> {
    let text = format!(
        r#"[case]
name = "mesh-bodies"
end_time = 1.0

[fluid.tank]
{settings}
spacing = 0.02
time_step = 1.0e-3
sound_speed = 10.0
output_interval = 0.1
tank = {{ min = [0.0, 0.0, 0.0], max = [0.6, 0.4, 0.4] }}

[[fluid.tank.block]]
min = [0.0, 0.0, 0.0]
max = [0.2, 0.4, 0.3]
{extra}"#
    );
    Case::parse(&dir.join("case.toml"), text)
}

fn tank(dir: &Path, extra: &str) -> FluidConfig {
    let case = parse(dir, extra).unwrap_or_else(|e| panic!("{e}"));
    case.fluid["tank"].clone()
}

/// (position in µm, kind) of every particle, sorted.
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

/// The cube next to the water column, as an STL in `dir`, and its box.
const CUBE: ([f64; 3], [f64; 3]) = ([0.2, 0.1, 0.0], [0.3, 0.2, 0.1]);

fn write_cube(dir: &Path, name: &str, mesh: &TriangleMesh) {
    write_binary_stl(&dir.join(name), mesh).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn an_stl_cube_body_gives_the_particles_and_loads_of_the_box_body_of_the_same_extent() {
    let dir = folder("cube");
    let (min, max) = CUBE;
    // drawn in millimetres about its own middle, placed by scale and translate
    let half = [50.0, 50.0, 50.0];
    write_cube(&dir, "cube.stl", &TriangleMesh::cuboid(half.map(|h| -h), half));
    let centre: [f64; 3] = std::array::from_fn(|a| 0.5 * (min[a] + max[a]));
    let mesh_body = format!(
        "\n[[fluid.tank.body]]\nname = \"cube\"\nmesh = {{ file = \"cube.stl\", scale = 0.001, translate = {centre:?} }}\n"
    );
    let box_body = format!("\n[[fluid.tank.body]]\nname = \"cube\"\nmin = {min:?}\nmax = {max:?}\n");
    let mut from_mesh = FluidSolver::new(&tank(&dir, &mesh_body));
    let mut from_box = FluidSolver::new(&tank(&dir, &box_body));
    let (a, b) = (sites(&from_mesh), sites(&from_box));
    let bodies = a.iter().filter(|s| s.1 == Kind::Body.code()).count();
    println!("{} particles, {bodies} of them the body's", a.len());
    // 0.1 m a side at Δs = 0.02 m: 5 × 5 × 5 sites, the whole cube, not a skin
    assert_eq!(bodies, 125);
    assert_eq!(a.len(), b.len());
    assert!(
        a == b,
        "the mesh cube body's particles differ from the box body's"
    );

    // The water column pushes on the held body: the same particles give the same force, and
    // the moment about the mesh's volume centroid is the one about the box's middle (they
    // agree to round-off).
    for _ in 0..20 {
        from_mesh.step(1.0e-3).unwrap_or_else(|e| panic!("{e:?}"));
        from_box.step(1.0e-3).unwrap_or_else(|e| panic!("{e:?}"));
    }
    let (la, lb) = (from_mesh.body_loads(), from_box.body_loads());
    println!("loads: mesh body {la:?}, box body {lb:?}");
    let scale = lb.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    assert!(scale > 1.0, "the water did not push on the body: {lb:?}");
    for (x, y) in la.iter().zip(&lb) {
        assert!(
            (x - y).abs() <= 1e-9 * scale,
            "mesh body {la:?} ≠ box body {lb:?}"
        );
    }
}

/// The error of a case that must be refused, with its key.
fn refusal(dir: &Path, extra: &str) -> CaseError {
    refusal_with(dir, "", extra)
}

fn refusal_with(dir: &Path, settings: &str, extra: &str) -> CaseError {
    match parse_with(dir, settings, extra) {
        Ok(_) => panic!("accepted:\n{extra}"),
        Err(e) => {
            println!("{e}");
            e
        }
    }
}

#[test]
fn a_mesh_body_with_min_and_max_too_is_refused_at_its_mesh_key() {
    let dir = folder("both");
    write_cube(&dir, "cube.stl", &TriangleMesh::cuboid(CUBE.0, CUBE.1));
    let e = refusal(
        &dir,
        "\n[[fluid.tank.body]]\nname = \"cube\"\nmin = [0.2, 0.1, 0.0]\nmax = [0.3, 0.2, 0.1]\nmesh = { file = \"cube.stl\" }\n",
    );
    assert_eq!(e.key, "fluid.tank.body[0].mesh");
    assert!(e.message.contains("not both"), "{}", e.message);
    let e = refusal(
        &dir,
        "\n[[fluid.tank.body]]\nname = \"cube\"\nmin = [0.2, 0.1, 0.0]\n",
    );
    assert_eq!(e.key, "fluid.tank.body[0]");
    assert!(e.message.contains("`mesh"), "{}", e.message);
}

#[test]
fn an_open_mesh_for_a_body_is_refused_naming_the_key_and_the_file() {
    let dir = folder("open");
    let mut open = TriangleMesh::cuboid(CUBE.0, CUBE.1);
    open.triangles.pop();
    write_cube(&dir, "open.stl", &open);
    let e = refusal(
        &dir,
        "\n[[fluid.tank.body]]\nname = \"cube\"\nmesh = { file = \"open.stl\" }\n",
    );
    assert_eq!(e.key, "fluid.tank.body[0].mesh.file");
    assert!(e.message.contains("open.stl"), "{}", e.message);
}

#[test]
fn a_missing_mesh_file_for_a_body_is_refused_naming_the_key_and_the_file() {
    let dir = folder("missing");
    let e = refusal(
        &dir,
        "\n[[fluid.tank.body]]\nname = \"cube\"\nmesh = { file = \"nowhere.stl\" }\n",
    );
    assert_eq!(e.key, "fluid.tank.body[0].mesh.file");
    assert!(e.message.contains("nowhere.stl"), "{}", e.message);
}

#[test]
fn a_mesh_body_outside_the_tank_or_over_a_wall_box_is_refused() {
    let dir = folder("placed");
    write_cube(&dir, "cube.stl", &TriangleMesh::cuboid(CUBE.0, CUBE.1));
    let e = refusal(
        &dir,
        "\n[[fluid.tank.body]]\nname = \"cube\"\nmesh = { file = \"cube.stl\", translate = [0.0, 0.0, 0.35] }\n",
    );
    assert_eq!(e.key, "fluid.tank.body[0].mesh");
    assert!(
        e.message.contains("inside the tank") && e.message.contains("cube.stl"),
        "{}",
        e.message
    );
    let e = refusal(
        &dir,
        "\n[[fluid.tank.wall]]\nmin = [0.25, 0.0, 0.0]\nmax = [0.35, 0.4, 0.1]\n[[fluid.tank.body]]\nname = \"cube\"\nmesh = { file = \"cube.stl\" }\n",
    );
    assert_eq!(e.key, "fluid.tank.body[0].mesh");
    assert!(e.message.contains("fluid.tank.wall[0]"), "{}", e.message);
}
