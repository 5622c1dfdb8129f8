//! Substep counts (issue 11, item 4): an advance as long as `max_step` is one substep even late in
//! a run, where `t_end − t` is `max_step` only to within the round-off of t.

use schemas::case::Case;
use std::path::Path;
use structure_solver::output::output_times;
use structure_solver::{ExternalLoads, Structure};

/// One unit mass on a spring to the ground (period 1 s), max_step = 1e-3 s.
fn oscillator() -> Structure {
    let text = r#"
[case]
name = "one-mass"
end_time = 100.0

[structure.s]
max_step = 1e-3

[[structure.s.point_mass]]
name = "m"
mass = 1.0
position = [0, 0, 0]
displacement = [1, 0, 0]

[[structure.s.spring]]
a = "m"
b = "ground"
stiffness = 39.47841760435743
"#;
    let case = Case::parse(Path::new("one-mass.toml"), text.to_string()).expect("the test case is valid");
    Structure::from_config(&case.structure["s"], "structure.s").expect("valid structure")
}

/// A 100 s run with its history every max_step takes 100 000 substeps, as standalone mode drives it
/// (advance to each output time in turn); today's relative tolerance of 1e-12 split 47 392 of them.
#[test]
fn history_interval_equal_to_max_step_takes_one_substep_each() {
    let mut s = oscillator();
    let loads = |_t: f64| Ok(ExternalLoads::zeros(1, 0, 0));
    for t in output_times(1e-3, 100.0) {
        s.advance(t, &loads).expect("stable");
    }
    assert_eq!(s.substeps(), 100_000);
}
