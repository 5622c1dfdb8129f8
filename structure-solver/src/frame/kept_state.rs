//! The part of a frame's state that an increment changes, kept to go back to: the start of a
//! one-solve step that is taken back and cut (`stepping.rs`), and the committed state every
//! equilibrium correction starts again from (`equilibrium.rs`). Kept apart from the nodes and
//! elements, so that keeping and restoring it copy only what an increment changes and the elements
//! stay small in the per-step passes; its storage is reused from step to step.
//!
//! A one-solve step keeps the nodes' positions and rotations and the elements' stress states only:
//! an element's co-rotational frame is a function of its nodes' positions and rotations
//! ([`Element::kinematics`]), which a take-back makes anew from the restored nodes, bit for bit the
//! frame the element had (every step ends with the frames made from its nodes; checked by
//! `tests/frame_one_solve_step.rs`). Not copying the frames (176 of an element's 304 bytes of
//! state) cuts what a step copies of its elements from 0.84 to 0.34 MB on the benchmark's 7 × 7 × 7
//! building, and halves the cache misses keeping costs. An iterated step restores its committed
//! state once per correction and keeps the frames too.

use super::element::Corotated;
use super::hinge::StressState;
use super::topology::{Element, Node};
use nalgebra::{UnitQuaternion, Vector3};

#[derive(Debug, Clone, Default)]
pub struct KeptState {
    /// Position and rotation of every node.
    nodes: Vec<(Vector3<f64>, UnitQuaternion<f64>)>,
    /// Stress state of every element.
    stresses: Vec<StressState>,
    /// Co-rotational frame of every element, or none: [`KeptState::restore`] then makes them from
    /// the restored nodes.
    frames: Vec<Corotated>,
}

impl KeptState {
    /// Keeps the nodes' positions and rotations.
    fn keep_nodes(&mut self, nodes: &[Node]) {
        self.nodes.clear();
        self.nodes.extend(nodes.iter().map(|n| (n.position, n.rotation)));
    }

    /// Room for the positions and rotations of `count` nodes, for the caller to write (in the pass
    /// that moves them).
    pub fn node_slots(&mut self, count: usize) -> &mut [(Vector3<f64>, UnitQuaternion<f64>)] {
        self.nodes
            .resize(count, (Vector3::zeros(), UnitQuaternion::identity()));
        &mut self.nodes
    }

    /// Keeps the nodes' state and the elements' frames and stress states.
    pub fn keep(&mut self, nodes: &[Node], elements: &[Element]) {
        self.keep_nodes(nodes);
        self.stresses.clear();
        self.stresses.extend(elements.iter().map(|e| e.stress));
        self.frames.clear();
        self.frames.extend(elements.iter().map(|e| e.current));
    }

    /// Room for the stress states of `count` elements, for the caller to write (in the pass that
    /// updates them); the frames are not kept.
    pub fn stress_slots(&mut self, count: usize) -> &mut [StressState] {
        self.frames.clear();
        self.stresses.resize(count, StressState::elastic(0.0));
        &mut self.stresses
    }

    /// Puts the nodes and elements back in the kept state; frames that were not kept are made from
    /// the restored nodes.
    pub fn restore(&self, nodes: &mut [Node], elements: &mut [Element]) {
        for (n, kept) in nodes.iter_mut().zip(&self.nodes) {
            (n.position, n.rotation) = *kept;
        }
        for (e, kept) in elements.iter_mut().zip(&self.stresses) {
            e.stress = *kept;
        }
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
