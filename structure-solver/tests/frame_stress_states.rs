//! Tests of `structure_solver::frame::stress_states`.

use structure_solver::frame::hinge::StressState;
use structure_solver::frame::stress_states::*;

/// States whose integration points are `s`.
fn states(s: &[f64]) -> Vec<StressState> {
    s.iter().map(|&s| StressState::elastic(s)).collect()
}

/// Writes `s + 1` for every state's integration point `s`, as an update would.
fn update(states: &mut StressStates) {
    let (before, after) = states.to_update();
    for (b, a) in before.iter().zip(after.iter_mut()) {
        *a = StressState::elastic(b.s + 1.0);
    }
    states.updated();
}

fn points(states: &StressStates) -> Vec<f64> {
    states.current().iter().map(|s| s.s).collect()
}

#[test]
fn going_back_returns_the_states_before_the_last_update() {
    let mut states = StressStates::new(states(&[0.1, 0.2]));
    update(&mut states);
    let mark = states.mark();
    update(&mut states);
    assert_eq!(points(&states), [2.1, 2.2]);
    states.go_back(mark);
    assert_eq!(points(&states), [1.1, 1.2]);
    // again from the same mark (an equilibrium correction's trial), and to a mark with no update
    // since
    update(&mut states);
    states.go_back(mark);
    assert_eq!(points(&states), [1.1, 1.2]);
    states.go_back(mark);
    assert_eq!(points(&states), [1.1, 1.2]);
    // a change in place is a change of the current states
    states.current_mut()[0].s = 5.0;
    update(&mut states);
    assert_eq!(points(&states), [6.0, 2.2]);
}

#[test]
#[should_panic(expected = "went back over 2 updates")]
fn a_second_update_wrote_over_the_mark() {
    let mut states = StressStates::new(states(&[0.1]));
    let mark = states.mark();
    update(&mut states);
    update(&mut states);
    states.go_back(mark);
}
