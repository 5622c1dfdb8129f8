//! The elements' stress states in two arrays, so that going back to the states before an update
//! copies nothing: an update of all elements (a one-solve step's increment, an equilibrium
//! correction's trial) reads each state from the current array and writes the new one into the
//! other, which then becomes current; the array it read from still holds the states before it, and
//! [`StressStates::go_back`] makes it current again. (Keeping a copy of every state before each
//! update instead wrote 0.34 MB per step on the benchmark's 7 × 7 × 7 building.)
//!
//! Element `i`'s state is entry `i` of [`StressStates::current`]; everything that changes a state
//! outside an update (moving an integration point, a fracture) changes the current array.

use super::hinge::StressState;

/// The elements' stress states, current and before the last update (see the module doc).
#[derive(Debug, Clone)]
pub struct StressStates {
    arrays: [Vec<StressState>; 2],
    /// Index of the current array.
    current: usize,
    /// Updates since the frame was built, to check that a mark is still there to go back to.
    updates: u64,
}

/// Where the states stood when [`StressStates::mark`] was called.
#[derive(Debug, Clone, Copy, Default)]
pub struct Mark {
    array: usize,
    updates: u64,
}

impl StressStates {
    /// The elements' states, `states[i]` element `i`'s.
    pub fn new(states: Vec<StressState>) -> StressStates {
        StressStates {
            arrays: [states.clone(), states],
            current: 0,
            updates: 0,
        }
    }

    /// The current states, one per element.
    pub fn current(&self) -> &[StressState] {
        &self.arrays[self.current]
    }

    /// The current states, to change in place.
    pub fn current_mut(&mut self) -> &mut [StressState] {
        &mut self.arrays[self.current]
    }

    /// The current states to read and the other array to write each element's updated state into;
    /// [`StressStates::updated`] then makes those current.
    pub fn to_update(&mut self) -> (&[StressState], &mut [StressState]) {
        let [first, second] = &mut self.arrays;
        if self.current == 0 {
            (first, second)
        } else {
            (second, first)
        }
    }

    /// Makes the states written after [`StressStates::to_update`] current.
    pub fn updated(&mut self) {
        self.current = 1 - self.current;
        self.updates += 1;
    }

    /// Where the states stand now, to come back to with [`StressStates::go_back`].
    pub fn mark(&self) -> Mark {
        Mark {
            array: self.current,
            updates: self.updates,
        }
    }

    /// Makes the states at `mark` current again: the same states, or those before the one update
    /// since (a second update would have written over them).
    pub fn go_back(&mut self, mark: Mark) {
        assert!(
            self.updates - mark.updates <= 1,
            "internal error: the frame's stress states went back over {} updates",
            self.updates - mark.updates
        );
        self.current = mark.array;
        self.updates = mark.updates;
    }
}
