//! Nodes and elements of a frame, built from its config: each member becomes two ASI-Gauss elements
//! joined at a new mid node.

use super::element::{corotate, initial_frame, linear_kinematics, quaternion_of, Corotated, S_GAUSS};
use super::hinge::StressState;
use nalgebra::{UnitQuaternion, Vector3};
use schemas::case::frame::{FrameConfig, Geometry, DOF_NAMES};
use schemas::case::FieldError;
use std::collections::BTreeMap;

/// A node: 3 translations and 3 rotations.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Node {
    /// Its id in the config; `None` for member mid nodes and nodes made by fracture.
    pub id: Option<u32>,
    pub position: Vector3<f64>,
    /// Position at t = 0 (first-order kinematics measure displacements from it).
    pub initial: Vector3<f64>,
    /// Rotation from the initial orientation.
    pub rotation: UnitQuaternion<f64>,
    /// `[v, ω]`, global.
    pub velocity: [f64; 6],
    /// `[a, α]`, global.
    pub acceleration: [f64; 6],
    pub fixed: [bool; 6],
}

impl Node {
    fn new(id: Option<u32>, position: Vector3<f64>) -> Node {
        Node {
            id,
            position,
            initial: position,
            rotation: UnitQuaternion::identity(),
            velocity: [0.0; 6],
            acceleration: [0.0; 6],
            fixed: [false; 6],
        }
    }
}

/// One half of a member.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Element {
    pub nodes: [usize; 2],
    pub member: usize,
    /// 0 for the member's first half, 1 for its second.
    pub half: usize,
    pub section: usize,
    /// Length at t = 0 (the strain reference).
    pub length0: f64,
    /// Rotation to the element frame at t = 0 (nodal rotations are measured from it).
    pub reference: UnitQuaternion<f64>,
    /// Current frame and natural deformations.
    pub current: Corotated,
    /// Times this element has fractured (and been split off a node).
    pub fractures: u32,
    /// First-order kinematics (`geometry = "linear"`): strains from the undeformed configuration,
    /// no geometric stiffness.
    pub linear: bool,
}

impl Element {
    /// The integration point of this element while elastic: on the member's Gauss point placement
    /// (+s in the first half, −s in the second), or at the midpoint when the other half has a hinge.
    pub fn elastic_integration_point(&self, other_half_hinged: bool) -> f64 {
        match (other_half_hinged, self.half) {
            (true, _) => 0.0,
            (false, 0) => S_GAUSS,
            (false, _) => -S_GAUSS,
        }
    }

    /// The co-rotational frame and natural deformations of this element at its nodes' current
    /// positions and rotations (first-order kinematics for a `linear` element).
    pub fn kinematics(&self, nodes: &[Node]) -> Corotated {
        let [a, b] = self.nodes;
        let (na, nb) = (&nodes[a], &nodes[b]);
        if self.linear {
            linear_kinematics(
                &na.position,
                &nb.position,
                &na.initial,
                &nb.initial,
                &na.rotation,
                &nb.rotation,
                &self.reference,
                self.length0,
            )
        } else {
            corotate(
                &na.position,
                &nb.position,
                &na.rotation,
                &nb.rotation,
                &self.reference,
                self.length0,
            )
        }
    }
}

/// A frame's nodes and elements as built from its config.
pub struct Topology {
    /// Config nodes first, in config order, then member mid nodes in member order.
    pub nodes: Vec<Node>,
    /// Two per member, in member order.
    pub elements: Vec<Element>,
    /// Each element's stress state: unstressed, its integration point on the Gauss placement.
    pub stresses: Vec<StressState>,
    /// Config node id → node index.
    pub ids: BTreeMap<u32, usize>,
}

/// Validates the config and builds its nodes and elements.
pub fn build(cfg: &FrameConfig, key: &str) -> Result<Topology, FieldError> {
    cfg.validate(key)?;
    let mut nodes: Vec<Node> = Vec::with_capacity(cfg.node.len() + cfg.member.len());
    let mut index = BTreeMap::new();
    for n in &cfg.node {
        index.insert(n.id, nodes.len());
        nodes.push(Node::new(Some(n.id), Vector3::from(n.position)));
    }
    for s in &cfg.support {
        let node = &mut nodes[index[&s.node]];
        for d in &s.fixed {
            if let Some(k) = DOF_NAMES.iter().position(|n| n == d) {
                node.fixed[k] = true;
            }
        }
    }
    let sections: BTreeMap<&str, usize> = cfg
        .section
        .iter()
        .enumerate()
        .map(|(i, s)| (s.name.as_str(), i))
        .collect();
    let mut elements = Vec::with_capacity(2 * cfg.member.len());
    let mut stresses = Vec::with_capacity(2 * cfg.member.len());
    for (m, member) in cfg.member.iter().enumerate() {
        let (a, b) = (index[&member.nodes[0]], index[&member.nodes[1]]);
        let mid = nodes.len();
        nodes.push(Node::new(None, (nodes[a].position + nodes[b].position) * 0.5));
        let axis = nodes[b].position - nodes[a].position;
        let reference = quaternion_of(&initial_frame(&axis, member.orientation));
        for (half, pair) in [[a, mid], [mid, b]].into_iter().enumerate() {
            let length0 = (nodes[pair[1]].position - nodes[pair[0]].position).norm();
            let q = UnitQuaternion::identity();
            let current = corotate(
                &nodes[pair[0]].position,
                &nodes[pair[1]].position,
                &q,
                &q,
                &reference,
                length0,
            );
            let element = Element {
                nodes: pair,
                member: m,
                half,
                section: sections[member.section.as_str()],
                length0,
                reference,
                current,
                fractures: 0,
                linear: cfg.geometry == Geometry::Linear,
            };
            stresses.push(StressState::elastic(element.elastic_integration_point(false)));
            elements.push(element);
        }
    }
    Ok(Topology {
        nodes,
        elements,
        stresses,
        ids: index,
    })
}
