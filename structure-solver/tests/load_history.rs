//! Tests of `structure_solver::load_history`.

use structure_solver::load_history::*;

fn at(h: &LoadHistory, t: f64) -> f64 {
    let mut out = [0.0];
    h.add_at(t, &mut out);
    out[0]
}

#[test]
fn step_and_ramp_switch_on_at_start() {
    let step = LoadHistory::Step {
        start: 1.0,
        value: vec![5.0],
    };
    assert_eq!(
        (at(&step, 0.999), at(&step, 1.0), at(&step, 7.0)),
        (0.0, 5.0, 5.0)
    );
    let ramp = LoadHistory::Ramp {
        start: 1.0,
        end: 3.0,
        value: vec![4.0],
    };
    assert_eq!(
        (at(&ramp, 0.0), at(&ramp, 2.0), at(&ramp, 3.0), at(&ramp, 9.0)),
        (0.0, 2.0, 4.0, 4.0)
    );
    assert_eq!(at(&LoadHistory::Constant(vec![-2.0]), 123.0), -2.0);
}
