//! Bad frame input gives a clear error naming the key and what is allowed; bad step input and
//! unstable runs give an error, never a panic.

use crate::frame_common;

use frame_common::{beam, steel, support, ALL};
use schemas::case::Case;
use std::path::Path;
use structure_solver::frame::Frame;

/// A valid case with a two-member frame; each test breaks one thing in it.
const GOOD: &str = r#"
[case]
name = "frame-errors"
end_time = 0.1

[structure.bridge]
max_step = 1e-3

[structure.bridge.frame]
time_step = 1e-4
gravity = [0.0, 0.0, -9.81]

[structure.bridge.frame.material]
young_modulus = 2.0e11
poisson = 0.3
density = 7850.0
yield_stress = 2.35e8

[[structure.bridge.frame.section]]
name = "column"
kind = "rectangle"
width = 0.1
depth = 0.15

[[structure.bridge.frame.node]]
id = 1
position = [0.0, 0.0, 0.0]

[[structure.bridge.frame.node]]
id = 2
position = [0.0, 0.0, 1.0]

[[structure.bridge.frame.node]]
id = 3
position = [1.0, 0.0, 1.0]

[[structure.bridge.frame.member]]
nodes = [1, 2]
section = "column"

[[structure.bridge.frame.member]]
nodes = [2, 3]
section = "column"

[[structure.bridge.frame.support]]
node = 1
fixed = ["x", "y", "z", "rx", "ry", "rz"]
"#;

/// Parses `GOOD` with `from` replaced by `to` and returns the error's key and message.
fn error_of(from: &str, to: &str) -> (String, String) {
    assert!(GOOD.contains(from), "test bug: `{from}` is not in the case");
    let text = GOOD.replacen(from, to, 1);
    match Case::parse(Path::new("frame.toml"), text) {
        Ok(_) => panic!("`{to}` was accepted"),
        Err(e) => {
            assert_eq!(e.file, Path::new("frame.toml"));
            (e.key, e.message)
        }
    }
}

#[test]
fn the_valid_case_builds_a_frame() {
    let case = Case::parse(Path::new("frame.toml"), GOOD.to_string()).expect("valid case");
    let cfg = case.structure["bridge"].frame.as_ref().expect("frame");
    let frame = Frame::from_config(cfg, "structure.bridge.frame").expect("frame builds");
    // 3 config nodes + 2 member mid nodes
    assert_eq!(frame.node_count(), 5);
    assert_eq!(frame.node_index(3), Some(2));
    assert_eq!(frame.node_index(9), None);
    assert_eq!(frame.time_step(), 1e-4);
}

#[test]
fn zero_length_member_is_named() {
    let (key, msg) = error_of("position = [0.0, 0.0, 1.0]", "position = [0.0, 0.0, 0.0]");
    assert_eq!(key, "structure.bridge.frame.member[0].nodes");
    assert!(msg.contains("zero length"), "{msg}");
}

#[test]
fn node_shared_by_nothing_is_named() {
    let (key, msg) = error_of("nodes = [2, 3]", "nodes = [1, 2]");
    assert_eq!(key, "structure.bridge.frame.node");
    assert!(msg.contains("node id 3 belongs to no member"), "{msg}");
}

#[test]
fn negative_section_property_is_named() {
    let (key, msg) = error_of("width = 0.1", "width = -0.1");
    assert_eq!(key, "structure.bridge.frame.section[0].width");
    assert!(msg.contains("> 0") && msg.contains("-0.1"), "{msg}");
}

#[test]
fn general_section_needs_every_property() {
    let (key, msg) = error_of(
        "kind = \"rectangle\"\nwidth = 0.1\ndepth = 0.15",
        "kind = \"general\"\narea = 0.1",
    );
    assert_eq!(key, "structure.bridge.frame.section[0].iy");
    assert!(msg.contains("required"), "{msg}");
}

#[test]
fn unknown_section_kind_lists_the_allowed_ones() {
    let (key, msg) = error_of("kind = \"rectangle\"", "kind = \"circle\"");
    assert_eq!(key, "structure.bridge.frame.section[0].kind");
    assert!(msg.contains("rectangle") && msg.contains("general"), "{msg}");
}

#[test]
fn member_naming_a_missing_node_or_section_is_named() {
    let (key, msg) = error_of("nodes = [2, 3]", "nodes = [2, 7]");
    assert_eq!(key, "structure.bridge.frame.member[1].nodes");
    assert!(msg.contains("node id 7"), "{msg}");
    let (key, msg) = error_of(
        "section = \"column\"\n\n[[structure.bridge.frame.member]]",
        "section = \"beam\"\n\n[[structure.bridge.frame.member]]",
    );
    assert_eq!(key, "structure.bridge.frame.member[0].section");
    assert!(msg.contains("column"), "{msg}");
}

#[test]
fn orientation_parallel_to_the_member_is_named() {
    let (key, msg) = error_of(
        "nodes = [1, 2]\nsection = \"column\"",
        "nodes = [1, 2]\nsection = \"column\"\norientation = [0.0, 0.0, 2.0]",
    );
    assert_eq!(key, "structure.bridge.frame.member[0].orientation");
    assert!(msg.contains("not parallel"), "{msg}");
}

#[test]
fn bad_support_and_material_values_are_named() {
    let (key, msg) = error_of("fixed = [\"x\",", "fixed = [\"u\",");
    assert_eq!(key, "structure.bridge.frame.support[0].fixed");
    assert!(msg.contains("`u`") && msg.contains("rz"), "{msg}");
    let (key, _) = error_of("poisson = 0.3", "poisson = 0.7");
    assert_eq!(key, "structure.bridge.frame.material.poisson");
    let (key, _) = error_of("time_step = 1e-4", "time_step = 0.0");
    assert_eq!(key, "structure.bridge.frame.time_step");
    let (key, _) = error_of("id = 3", "id = 2");
    assert_eq!(key, "structure.bridge.frame.node[2].id");
}

#[test]
fn unknown_key_is_rejected() {
    let (key, msg) = error_of("yield_stress = 2.35e8", "yield_stress = 2.35e8\nyeild = 1.0");
    assert!(key.starts_with("structure.bridge.frame.material"), "{key}");
    assert!(msg.contains("yeild"), "{msg}");
}

#[test]
fn bad_step_input_is_an_error() {
    let mut cfg = beam(1.0, 2, 0.1, 0.1, steel());
    cfg.support.push(support(1, &ALL));
    let mut frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid");
    let n = 6 * frame.node_count();
    let err = frame.step(1e-4, &vec![0.0; n - 1]).expect_err("short loads");
    assert!(err.contains("6 entries per node"), "{err}");
    let mut loads = vec![0.0; n];
    loads[7] = f64::NAN;
    let err = frame.step(1e-4, &loads).expect_err("NaN load");
    assert!(err.contains("not finite"), "{err}");
    let err = frame.step(-1.0, &vec![0.0; n]).expect_err("negative dt");
    assert!(err.contains("time step"), "{err}");
}

#[test]
fn an_unsupported_frame_cannot_be_solved_statically() {
    let cfg = beam(1.0, 2, 0.1, 0.1, steel());
    let frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid");
    let err = frame
        .linear_static_displacements(&vec![0.0; 6 * frame.node_count()])
        .expect_err("mechanism");
    assert!(err.contains("not positive definite"), "{err}");
}

/// A load far beyond what the beam can carry tears it apart within a few steps: the run stops with
/// a diagnostic instead of producing garbage.
#[test]
fn a_run_that_blows_up_is_stopped_with_a_diagnostic() {
    let mut cfg = beam(1.0, 2, 0.01, 0.01, steel());
    cfg.material.yield_stress = 1e30;
    cfg.support.push(support(1, &ALL));
    let mut frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid");
    let tip = frame.node_index(3).expect("tip");
    let mut loads = vec![0.0; 6 * frame.node_count()];
    loads[6 * tip] = 1e12;
    let outcome = (0..1000).try_for_each(|_| frame.step(1e-3, &loads));
    let err = outcome.expect_err("a 1e12 N load on a 1 cm bar must stop the run");
    assert!(err.contains("unstable"), "{err}");
}

#[test]
fn the_equilibrium_choice_comes_from_the_case() {
    use structure_solver::frame::Equilibrium;
    let build = |text: String| {
        let case = Case::parse(Path::new("frame.toml"), text).expect("valid case");
        let cfg = case.structure["bridge"].frame.clone().expect("frame");
        Frame::from_config(&cfg, "structure.bridge.frame")
            .expect("frame builds")
            .equilibrium()
    };
    assert_eq!(
        build(GOOD.to_string()),
        Equilibrium::OneSolve,
        "ASI-Gauss's one solve per step by default"
    );
    let iterate = GOOD.replacen(
        "time_step = 1e-4",
        "time_step = 1e-4\nequilibrium_tolerance = 1e-8",
        1,
    );
    assert_eq!(build(iterate), Equilibrium::Iterate { tolerance: 1e-8 });
    let (key, msg) = error_of(
        "time_step = 1e-4",
        "time_step = 1e-4\nequilibrium_tolerance = 2.0",
    );
    assert_eq!(key, "structure.bridge.frame.equilibrium_tolerance");
    assert!(msg.contains("[1e-14, 0.5]"), "{msg}");
}
