//! Bad case input: every mistake is a clear error naming the key and what is allowed.

use schemas::case::{Case, CaseError};
use std::path::{Path, PathBuf};
use structure_solver::{LoadSchedule, Structure};

const HEAD: &str = "[case]\nname = \"bad\"\nend_time = 1.0\n\n[structure.s]\n";

const POINT: &str = r#"
[[structure.s.point_mass]]
name = "m1"
mass = 1.0
position = [0, 0, 0]
"#;

/// Loads the case text (in `dir` when given) and builds the structure and its loads.
fn load(body: &str, dir: Option<&Path>) -> Result<(), CaseError> {
    let path = dir.map_or_else(|| PathBuf::from("bad.toml"), |d| d.join("case.toml"));
    let case = Case::parse(&path, format!("{HEAD}{body}"))?;
    let cfg = &case.structure["s"];
    let at = |e| CaseError::at(&path, e);
    let s = Structure::from_config(cfg, "structure.s").map_err(at)?;
    LoadSchedule::from_config(cfg, "structure.s", &case.dir(), &s).map_err(at)?;
    Ok(())
}

fn error(body: &str) -> CaseError {
    load(body, None).expect_err("this case must be refused")
}

/// A fresh folder for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "structure-solver-bad-input-{}-{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

#[test]
fn a_good_case_loads() {
    load(&format!("max_step = 0.01\n{POINT}"), None).expect("valid");
}

#[test]
fn negative_mass() {
    let e = error(
        "max_step = 0.01\n[[structure.s.point_mass]]\nname = \"m1\"\nmass = -1.0\nposition = [0, 0, 0]\n",
    );
    assert_eq!(e.key, "structure.s.point_mass[0].mass");
    assert!(e.message.contains("> 0"), "{e}");
}

#[test]
fn zero_max_step() {
    let e = error(&format!("max_step = 0.0\n{POINT}"));
    assert_eq!(e.key, "structure.s.max_step");
    assert!(e.message.contains("> 0"), "{e}");
}

/// `max_step` may be left out only by a frame alone: with a point mass it is required.
#[test]
fn missing_max_step() {
    let e = error(POINT);
    assert_eq!(e.key, "structure.s.max_step");
    assert!(e.message.contains("is required"), "{e}");
}

#[test]
fn spring_to_an_unknown_point() {
    let e = error(&format!(
        "max_step = 0.01\n{POINT}\n[[structure.s.spring]]\na = \"m1\"\nb = \"m9\"\nstiffness = 1.0\n"
    ));
    assert_eq!(e.key, "structure.s.spring[0].b");
    assert!(
        e.message.contains("`m9` is unknown") && e.message.contains("ground"),
        "{e}"
    );
}

#[test]
fn support_on_no_body() {
    let e = error(&format!(
        "max_step = 0.01\n{POINT}\n[[structure.s.support]]\nbody = \"deck\"\nrelease_force = 1.0\n"
    ));
    assert_eq!(e.key, "structure.s.support[0].body");
    assert!(e.message.contains("`deck` is not a body"), "{e}");
}

#[test]
fn non_positive_definite_inertia() {
    let e = error(
        "max_step = 0.01\n[[structure.s.body]]\nname = \"b\"\nmass = 1.0\ncentre = [0, 0, 0]\n\
         inertia = { tensor = [[1, 0, 0], [0, -2, 0], [0, 0, 3]] }\n",
    );
    assert_eq!(e.key, "structure.s.body[0].inertia.tensor");
    assert!(e.message.contains("positive definite"), "{e}");
}

#[test]
fn particles_on_one_line_give_a_singular_inertia() {
    let e = error(
        "max_step = 0.01\n[[structure.s.body]]\nname = \"b\"\n\
         inertia = { particle_mass = 1.0, particles = [[0, 0, 0], [1, 0, 0], [2, 0, 0]] }\n",
    );
    assert_eq!(e.key, "structure.s.body[0].inertia.particles");
}

#[test]
fn load_table_that_does_not_exist() {
    let dir = scratch("missing");
    let body = format!("max_step = 0.01\n{POINT}\n[[structure.s.load]]\npoint = \"m1\"\nhistory = \"table\"\ntable = \"nope.csv\"\n");
    let e = load(&body, Some(&dir)).expect_err("a missing table must be refused");
    assert_eq!(e.key, "structure.s.load[0].table");
    assert!(
        e.message.contains("nope.csv") && e.message.contains("cannot read"),
        "{e}"
    );
}

#[test]
fn malformed_load_table() {
    let dir = scratch("malformed");
    std::fs::write(dir.join("f.csv"), "t,fx,fy,fz\n0,1,2,3\n0.5,1,2\n").expect("write table");
    let body = format!("max_step = 0.01\n{POINT}\n[[structure.s.load]]\npoint = \"m1\"\nhistory = \"table\"\ntable = \"f.csv\"\n");
    let e = load(&body, Some(&dir)).expect_err("a short row must be refused");
    assert_eq!(e.key, "structure.s.load[0].table");
    assert!(
        e.message.contains("line 3") && e.message.contains("expected 4 columns"),
        "{e}"
    );

    std::fs::write(dir.join("f.csv"), "0,1,2,3\n0,1,2,3\n").expect("write table");
    let e = load(&body, Some(&dir)).expect_err("repeated times must be refused");
    assert!(e.message.contains("times must increase"), "{e}");

    std::fs::write(dir.join("f.csv"), "0,1,2,3\n1,x,2,3\n").expect("write table");
    let e = load(&body, Some(&dir)).expect_err("text in a row must be refused");
    assert!(e.message.contains("line 2"), "{e}");
}

#[test]
fn load_value_of_the_wrong_size_and_stray_keys() {
    let e = error(&format!(
        "max_step = 0.01\n{POINT}\n[[structure.s.load]]\npoint = \"m1\"\nvalue = [1, 2]\n"
    ));
    assert_eq!(e.key, "structure.s.load[0].value");
    assert!(e.message.contains("3 components"), "{e}");
    let e = error(&format!(
        "max_step = 0.01\n{POINT}\n[[structure.s.load]]\npoint = \"m1\"\nvalue = [1, 2, 3]\nend = 2.0\n"
    ));
    assert_eq!(e.key, "structure.s.load[0].end");
    let e = error(&format!(
        "max_step = 0.01\n{POINT}\n[[structure.s.load]]\npoint = \"m1\"\nvalue = [1, 2, 3]\nhistory = \"ramp\"\nstart = 1.0\nend = 0.5\n"
    ));
    assert_eq!(e.key, "structure.s.load[0].end");
}

#[test]
fn duplicate_names_and_unknown_keys() {
    let e = error(&format!("max_step = 0.01\n{POINT}{POINT}"));
    assert_eq!(e.key, "structure.s.point_mass[1].name");
    let e = error(&format!("max_step = 0.01\nstiffnes = 3\n{POINT}"));
    assert!(e.message.contains("stiffnes"), "{e}");
}

#[test]
fn frame_nodes_without_a_frame() {
    let e = error(&format!(
        "max_step = 0.01\n{POINT}\n[[structure.s.load]]\nnode = 3\nvalue = [0, 0, 1, 0, 0, 0]\n"
    ));
    assert_eq!(e.key, "structure.s.load[0].node");
    assert!(e.message.contains("no [frame] section"), "{e}");
    let e = error(&format!(
        "max_step = 0.01\n{POINT}\n[structure.s.history]\ninterval = 0.1\nnodes = [3]\n"
    ));
    assert_eq!(e.key, "structure.s.history.nodes[0]");
}

#[test]
fn frame_node_that_does_not_exist_and_conflicting_gravity() {
    let case = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/structure-cantilever/case.toml"),
    )
    .expect("cantilever case");
    let bad_node = case.replace("nodes = [5]", "nodes = [50]");
    let e = Case::parse(Path::new("c.toml"), bad_node).expect_err("node 50 does not exist");
    assert_eq!(e.key, "structure.beam.history.nodes[0]");
    assert!(e.message.contains("50"), "{e}");
    let two_gravities = case
        .replace(
            "max_step = 1e-3\n",
            "max_step = 1e-3\ngravity = [0.0, 0.0, -9.8]\n",
        )
        .replace("gravity = [0.0, 0.0, 0.0]", "gravity = [0.0, 0.0, -9.81]");
    let e = Case::parse(Path::new("c.toml"), two_gravities).expect_err("two gravities");
    assert_eq!(e.key, "structure.beam.frame.gravity");
}
