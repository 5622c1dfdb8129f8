//! Speed of the structure substep: prints a table of wall time per substep for point-mass chains
//! (RK4) and free rigid bodies (kick–drift–kick with the implicit midpoint rotation).
//! Run: `cargo bench -p structure-solver --bench structure_step`.

use schemas::case::Case;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;
use structure_solver::{ExternalLoads, Structure};

/// A chain of `n` unit masses joined by springs (k = 100), both ends to ground; the first mass
/// displaced.
fn chain(n: usize) -> String {
    let mut s = String::from("max_step = 1e-3\n");
    for i in 0..n {
        let d = if i == 0 { 0.1 } else { 0.0 };
        let _ = write!(s, "[[structure.s.point_mass]]\nname = \"m{i}\"\nmass = 1.0\nposition = [{i}, 0, 0]\ndisplacement = [{d}, 0, 0]\n");
    }
    let _ = write!(
        s,
        "[[structure.s.spring]]\na = \"m0\"\nb = \"ground\"\nstiffness = 100.0\n"
    );
    for i in 1..n {
        let _ = write!(
            s,
            "[[structure.s.spring]]\na = \"m{}\"\nb = \"m{i}\"\nstiffness = 100.0\n",
            i - 1
        );
    }
    let _ = write!(
        s,
        "[[structure.s.spring]]\na = \"m{}\"\nb = \"ground\"\nstiffness = 100.0\n",
        n - 1
    );
    s
}

/// `n` free tops spinning near their intermediate axis.
fn tops(n: usize) -> String {
    let mut s = String::from("max_step = 1e-3\n");
    for i in 0..n {
        let _ = write!(
            s,
            "[[structure.s.body]]\nname = \"b{i}\"\nmass = 1.0\ncentre = [{i}, 0, 0]\nangular_velocity = [0.01, 1, 0]\n\
             inertia = {{ tensor = [[1, 0, 0], [0, 2, 0], [0, 0, 3]] }}\n"
        );
    }
    s
}

fn build(section: &str) -> Structure {
    let text = format!("[case]\nname = \"bench\"\nend_time = 1.0\n[structure.s]\n{section}");
    let case = match Case::parse(Path::new("bench.toml"), text) {
        Ok(c) => c,
        Err(e) => panic!("benchmark case: {e}"),
    };
    match Structure::from_config(&case.structure["s"], "structure.s") {
        Ok(s) => s,
        Err(e) => panic!("benchmark case: {e:?}"),
    }
}

/// Advances `steps` substeps of 1 ms; returns wall seconds.
fn time(mut s: Structure, steps: u32) -> f64 {
    let (np, nb) = (s.points().len(), s.bodies().len());
    let loads = move |_t: f64| Ok(ExternalLoads::zeros(np, nb, 0));
    let start = Instant::now();
    if let Err(e) = s.advance(f64::from(steps) * 1e-3, &loads) {
        panic!("benchmark run failed: {e}");
    }
    start.elapsed().as_secs_f64()
}

fn main() {
    println!(
        "{:<28} {:>9} {:>11} {:>14} {:>16}",
        "case", "substeps", "wall [s]", "µs / substep", "ns / DOF·substep"
    );
    let cases: [(&str, String, u32, usize); 5] = [
        ("2 point masses", chain(2), 100_000, 2),
        ("100 point masses", chain(100), 10_000, 100),
        ("1000 point masses", chain(1000), 1_000, 1000),
        ("1 rigid body", tops(1), 100_000, 1),
        ("100 rigid bodies", tops(100), 2_000, 100),
    ];
    for (name, section, steps, things) in cases {
        let s = build(&section);
        let wall = time(s, steps);
        let per_step = wall / f64::from(steps);
        let dofs = if name.contains("rigid") {
            6 * things
        } else {
            3 * things
        };
        println!(
            "{name:<28} {steps:>9} {wall:>11.3} {:>14.2} {:>16.1}",
            per_step * 1e6,
            per_step * 1e9 / dofs as f64
        );
    }
}
