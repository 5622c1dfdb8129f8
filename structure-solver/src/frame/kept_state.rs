//! The part of a frame's state that an increment changes, kept to go back to: the start of a
//! one-solve step that is taken back and cut (`stepping.rs`), and the committed state every
//! equilibrium correction starts again from (`equilibrium.rs`). Kept apart from the nodes and
//! elements, so that keeping and restoring it copy only what an increment changes; its storage is
//! reused from step to step. The elements' stress states are not copied at all: their two arrays
//! (`stress_states.rs`) still hold the ones before an update, and only where they stood is kept.
//!
//! A one-solve step keeps the nodes' positions and rotations (in the pass that moves them) and
//! where the stress states stood only: an element's co-rotational frame is a function of its
//! nodes' positions and rotations ([`Element::kinematics`]), which a take-back makes anew from the
//! restored nodes, bit for bit the frame the element had (every step ends with the frames made
//! from its nodes; checked by `tests/frame_one_solve_step.rs`). An iterated step restores its
//! committed state once per correction and keeps the frames too.

use super::element::Corotated;
use super::stress_states::{Mark, StressStates};
use super::topology::{Element, Node};
use nalgebra::{UnitQuaternion, Vector3};

#[derive(Debug, Clone, Default)]
pub struct KeptState {
    /// Position and rotation of every node.
    nodes: Vec<(Vector3<f64>, UnitQuaternion<f64>)>,
    /// Where the elements' stress states stood.
    stresses: Mark,
    /// Co-rotational frame of every element, or none: [`KeptState::restore`] then makes them from
    /// the restored nodes.
    frames: Vec<Corotated>,
}

impl KeptState {
    /// Keeps the nodes' state, the elements' frames and where their stress states stand.
    pub fn keep(&mut self, nodes: &[Node], elements: &[Element], stresses: &StressStates) {
        self.nodes.clear();
        self.nodes.extend(nodes.iter().map(|n| (n.position, n.rotation)));
        self.stresses = stresses.mark();
        self.frames.clear();
        self.frames.extend(elements.iter().map(|e| e.current));
    }

    /// Keeps where the stress states stand and gives room for the positions and rotations of
    /// `count` nodes, for the caller to write (in the pass that moves them); the frames are not
    /// kept.
    pub fn keep_for_increment(
        &mut self,
        stresses: &StressStates,
        count: usize,
    ) -> &mut [(Vector3<f64>, UnitQuaternion<f64>)] {
        self.stresses = stresses.mark();
        self.frames.clear();
        self.nodes
            .resize(count, (Vector3::zeros(), UnitQuaternion::identity()));
        &mut self.nodes
    }

    /// Puts the nodes, elements and stress states back in the kept state; frames that were not
    /// kept are made from the restored nodes.
    pub fn restore(&self, nodes: &mut [Node], elements: &mut [Element], stresses: &mut StressStates) {
        for (n, kept) in nodes.iter_mut().zip(&self.nodes) {
            (n.position, n.rotation) = *kept;
        }
        stresses.go_back(self.stresses);
        if self.frames.is_empty() {
            for e in elements.iter_mut() {
                e.current = e.kinematics(nodes);
            }
        } else {
            for (e, kept) in elements.iter_mut().zip(&self.frames) {
                e.current = *kept;
            }
        }
    }
}
