//! The part of a frame's state that an increment changes — node positions and rotations, element
//! frames and stress states — kept to go back to: the start of a one-solve step that is taken back
//! and cut (`stepping.rs`), and the committed state every equilibrium correction starts again from
//! (`equilibrium.rs`). Kept apart from the nodes and elements, so that keeping and restoring it copy
//! only what an increment changes (a third of an element, a third of a node) and the elements stay
//! small in the per-step passes; its storage is reused from step to step.

use super::element::Corotated;
use super::hinge::StressState;
use super::topology::{Element, Node};
use nalgebra::{UnitQuaternion, Vector3};

#[derive(Debug, Clone, Default)]
pub struct KeptState {
    /// Position and rotation of every node.
    pub nodes: Vec<(Vector3<f64>, UnitQuaternion<f64>)>,
    /// Co-rotational frame and stress state of every element.
    pub elements: Vec<(Corotated, StressState)>,
}

impl KeptState {
    /// Keeps the nodes' positions and rotations.
    pub fn keep_nodes(&mut self, nodes: &[Node]) {
        self.nodes.clear();
        self.nodes.extend(nodes.iter().map(|n| (n.position, n.rotation)));
    }

    /// Keeps the elements' frames and stress states.
    pub fn keep_elements(&mut self, elements: &[Element]) {
        self.elements.clear();
        self.elements
            .extend(elements.iter().map(|e| (e.current, e.stress)));
    }

    /// Keeps the nodes' and the elements' state.
    pub fn keep(&mut self, nodes: &[Node], elements: &[Element]) {
        self.keep_nodes(nodes);
        self.keep_elements(elements);
    }

    /// Puts the nodes and elements back in the kept state.
    pub fn restore(&self, nodes: &mut [Node], elements: &mut [Element]) {
        for (n, kept) in nodes.iter_mut().zip(&self.nodes) {
            (n.position, n.rotation) = *kept;
        }
        for (e, kept) in elements.iter_mut().zip(&self.elements) {
            (e.current, e.stress) = *kept;
        }
    }
}
