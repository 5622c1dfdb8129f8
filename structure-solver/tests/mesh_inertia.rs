//! A rigid body's mass properties from a closed mesh (`inertia = { mesh = { … }, density }`,
//! issue 37): a box drawn as an STL gives the homogeneous box's mass ρ l_x l_y l_z, its middle as
//! the centre and the diagonal I = m (l_y² + l_z²) / 12 … in the body frame, also when the mesh
//! is placed rotated and the body's orientation says so; `mass` or `centre` given with a mesh,
//! a missing `density` and a missing file are refused naming the key (and the file).

use nalgebra::Matrix3;
use schemas::case::{Case, CaseError};
use schemas::geometry::{write_binary_stl, TriangleMesh};
use std::path::{Path, PathBuf};
use structure_solver::inertia::MassProperties;

/// A box whose corners are exact in an STL's f32: 0.5 × 0.25 × 0.125 m.
const HALF: [f64; 3] = [0.25, 0.125, 0.0625];
const DENSITY: f64 = 500.0;

fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mesh-inertia-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    write_binary_stl(
        &dir.join("box.stl"),
        &TriangleMesh::cuboid(HALF.map(|h| -h), HALF),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    dir
}

/// A structure case in `dir` with one body `b` whose keys are `body`.
fn parse(dir: &Path, body: &str) -> Result<Case, CaseError> {
    let text = format!(
        "[case]\nname = \"mesh-inertia\"\nend_time = 1.0\n\n[structure.s]\nmax_step = 0.01\n\n[[structure.s.body]]\nname = \"b\"\n{body}\n"
    );
    Case::parse(&dir.join("case.toml"), text)
}

fn properties(dir: &Path, body: &str) -> MassProperties {
    let case = parse(dir, body).unwrap_or_else(|e| panic!("{e}"));
    MassProperties::from_config(&case.structure["s"].body[0], "structure.s.body[0]")
        .unwrap_or_else(|e| panic!("{e:?}"))
}

/// The homogeneous box's mass and inertia about its middle, in its own axes.
fn analytic() -> (f64, Matrix3<f64>) {
    let [lx, ly, lz] = HALF.map(|h| 2.0 * h);
    let m = DENSITY * lx * ly * lz;
    let k = m / 12.0;
    let i = Matrix3::from_diagonal(&nalgebra::Vector3::new(
        k * (ly * ly + lz * lz),
        k * (lx * lx + lz * lz),
        k * (lx * lx + ly * ly),
    ));
    (m, i)
}

fn assert_box(p: &MassProperties, centre: [f64; 3]) {
    let (m, i) = analytic();
    println!(
        "mass {} kg (box: {m}), centre {:?}, inertia {}",
        p.mass, p.centre, p.inertia
    );
    assert!((p.mass - m).abs() <= 1e-13 * m, "mass {} ≠ {m}", p.mass);
    for a in 0..3 {
        assert!(
            (p.centre[a] - centre[a]).abs() <= 1e-13,
            "centre {:?} ≠ {centre:?}",
            p.centre
        );
    }
    let scale = i.max();
    for r in 0..3 {
        for c in 0..3 {
            assert!(
                (p.inertia[(r, c)] - i[(r, c)]).abs() <= 1e-12 * scale,
                "inertia {} ≠ the box's {i}",
                p.inertia
            );
        }
    }
}

#[test]
fn a_box_mesh_gives_the_box_mass_centre_and_inertia() {
    let dir = folder("box");
    let p = properties(
        &dir,
        "inertia = { mesh = { file = \"box.stl\", translate = [1.0, 2.0, 3.0] }, density = 500.0 }",
    );
    assert_box(&p, [1.0, 2.0, 3.0]);
}

#[test]
fn a_rotated_box_mesh_gives_the_box_inertia_in_the_body_frame_of_its_orientation() {
    let dir = folder("rotated");
    // placed 30° about z; the body's initial orientation is the same rotation, so the body
    // frame is the box's own axes: the tensor there is diagonal
    let half = 15f64.to_radians();
    let body = format!(
        "orientation = [{}, 0.0, 0.0, {}]\ninertia = {{ mesh = {{ file = \"box.stl\", rotate = [0.0, 0.0, 30.0], translate = [-1.0, 0.5, 2.0] }}, density = 500.0 }}",
        half.cos(),
        half.sin()
    );
    let p = properties(&dir, &body);
    assert_box(&p, [-1.0, 0.5, 2.0]);
}

fn refusal(dir: &Path, body: &str) -> CaseError {
    match parse(dir, body) {
        Ok(_) => panic!("accepted:\n{body}"),
        Err(e) => {
            println!("{e}");
            e
        }
    }
}

#[test]
fn mass_or_centre_with_a_mesh_and_a_mesh_without_density_are_refused() {
    let dir = folder("keys");
    let mesh = "inertia = { mesh = { file = \"box.stl\" }, density = 500.0 }";
    let e = refusal(&dir, &format!("mass = 1.0\n{mesh}"));
    assert_eq!(e.key, "structure.s.body[0].mass");
    assert!(e.message.contains("inertia.mesh"), "{}", e.message);
    let e = refusal(&dir, &format!("centre = [0.0, 0.0, 0.0]\n{mesh}"));
    assert_eq!(e.key, "structure.s.body[0].centre");
    let e = refusal(&dir, "inertia = { mesh = { file = \"box.stl\" } }");
    assert_eq!(e.key, "structure.s.body[0].inertia.density");
    let e = refusal(
        &dir,
        "inertia = { mesh = { file = \"box.stl\" }, box = [1.0, 1.0, 1.0], density = 500.0 }",
    );
    assert_eq!(e.key, "structure.s.body[0].inertia");
}

#[test]
fn a_missing_or_open_inertia_mesh_is_refused_naming_the_key_and_the_file() {
    let dir = folder("files");
    let e = refusal(
        &dir,
        "inertia = { mesh = { file = \"nowhere.stl\" }, density = 500.0 }",
    );
    assert_eq!(e.key, "structure.s.body[0].inertia.mesh.file");
    assert!(e.message.contains("nowhere.stl"), "{}", e.message);
    let mut open = TriangleMesh::cuboid(HALF.map(|h| -h), HALF);
    open.triangles.pop();
    write_binary_stl(&dir.join("open.stl"), &open).unwrap_or_else(|e| panic!("{e}"));
    let e = refusal(
        &dir,
        "inertia = { mesh = { file = \"open.stl\" }, density = 500.0 }",
    );
    assert_eq!(e.key, "structure.s.body[0].inertia.mesh.file");
    assert!(
        e.message.contains("open.stl") && e.message.contains("not closed"),
        "{}",
        e.message
    );
}
