//! Fracture of a fully plastic section (S2-17) and the split of the fractured element at its hinge.

use super::assembly::NODE_DOFS;
use super::global_system::tangent_stiffness;
use super::hinge::StressState;
use super::hinge_events::{HingeEvent, HingeEventKind};
use super::section::Resultants;
use super::topology::{Element, Node};
use super::Frame;
use nalgebra::Vector3;
use schemas::case::frame::MaterialConfig;

/// Critical strains of S2-17; a term whose critical value is not given is left out.
#[derive(Debug, Clone, Copy, serde::Serialize, serde::Deserialize)]
pub struct FractureCriterion {
    /// `[axial ε, γy, γz, twist (never checked), κy, κz]`; infinity where not checked.
    critical: Resultants,
}

impl FractureCriterion {
    /// The criterion from the material's optional `fracture_*` keys; `None` when none is given.
    pub fn new(material: &MaterialConfig) -> Option<FractureCriterion> {
        let inf = f64::INFINITY;
        let [ky, kz] = material.fracture_curvature.unwrap_or([inf, inf]);
        let [gy, gz] = material.fracture_shear_strain.unwrap_or([inf, inf]);
        let ea = material.fracture_axial_strain.unwrap_or(inf);
        let critical = [ea, gy, gz, inf, ky, kz];
        critical
            .iter()
            .any(|c| c.is_finite())
            .then_some(FractureCriterion { critical })
    }

    /// S2-17: `(χy/χy_c)² + (χz/χz_c)² + (ε/ε_c)² + (γy/γy_c)² + (γz/γz_c)² ≥ 1`.
    pub fn is_reached(&self, strain: &Resultants) -> bool {
        self.value(strain) >= 1.0
    }

    /// The left side of S2-17.
    pub fn value(&self, strain: &Resultants) -> f64 {
        strain
            .iter()
            .zip(&self.critical)
            .map(|(e, c)| (e / c).powi(2))
            .sum::<f64>()
    }
}

/// Which ends of each element are free: their node is held by no other element and no support.
pub(super) fn free_ends(nodes: &[Node], elements: &[Element]) -> Vec<[bool; 2]> {
    let mut held = vec![0_u32; nodes.len()];
    for e in elements {
        for &v in &e.nodes {
            held[v] += 1;
        }
    }
    elements
        .iter()
        .map(|e| {
            e.nodes
                .map(|v| held[v] == 1 && !nodes[v].fixed.iter().any(|&f| f))
        })
        .collect()
}

impl Frame {
    /// S2-17 at every hinge; a fractured element is split off its hinge node onto a new node (same
    /// position and motion), left unstressed, and the condensation and the sparse pattern are rebuilt.
    /// An element's free end (a node no other element and no support holds) is not split; a hinge
    /// of another element left at a node the split freed closes. The nodes whose forces the split
    /// changed start the next step from accelerations that balance them
    /// ([`Frame::restart_accelerations`]); `loads`: the step's applied loads (6 per node before the
    /// split).
    pub(super) fn split_fractured(&mut self, loads: &[f64]) -> Result<(), String> {
        let Some(criterion) = self.fracture else {
            return Ok(());
        };
        let mut changed = false;
        let mut touched = Vec::new();
        for i in 0..self.elements.len() {
            let e = &self.elements[i];
            let stress = &self.stresses.current()[i];
            let Some(end) = stress.hinge else { continue };
            if !criterion.is_reached(&stress.strain) {
                continue;
            }
            let old = e.nodes[end.node()];
            // a free end (no other element, no support) is already apart: splitting it again would
            // only add a node, step after step, while the hinge there keeps its strain
            let shared = self
                .elements
                .iter()
                .enumerate()
                .any(|(j, other)| j != i && other.nodes.contains(&old));
            if !shared && !self.nodes[old].fixed.iter().any(|&f| f) {
                continue;
            }
            let e = &self.elements[i];
            let stress = &self.stresses.current()[i];
            if let Some(events) = &mut self.events {
                let forces = super::section_forces::end_forces(e, stress)[end.node()];
                events.push(HingeEvent {
                    time: self.elapsed,
                    element: i,
                    member: e.member,
                    node: old,
                    kind: HingeEventKind::Fracture,
                    forces,
                    function: criterion.value(&stress.strain),
                });
            }
            let mut node = self.nodes[old].clone();
            node.id = None;
            node.fixed = [false; NODE_DOFS];
            self.nodes.push(node);
            let e = &mut self.elements[i];
            e.nodes[end.node()] = self.nodes.len() - 1;
            touched.extend([old, e.nodes[0], e.nodes[1]]);
            // the strain energy the fracture releases leaves the account as a shift (`energy.rs`):
            // U drops by it without work
            let stress = &mut self.stresses.current_mut()[i];
            let released = stress.strain_energy(&self.sections[e.section], e.length0);
            let (dissipated, shifted) = (stress.dissipated, stress.shifted - released);
            *stress = StressState::elastic(stress.s);
            stress.hinge = None;
            stress.dissipated = dissipated;
            stress.shifted = shifted;
            e.fractures += 1;
            changed = true;
        }
        if changed {
            // a node the split left to one element is a free end: a hinge there closes (no hinge
            // forms at a free end, `hinge.rs`), its integration point goes back where the member's
            // hinges want it (the end forces stay, the change of U is booked as a shift)
            self.free_ends = free_ends(&self.nodes, &self.elements);
            let before = self.hinges_if_recording();
            for (i, free) in self.free_ends.iter().enumerate() {
                let stress = &mut self.stresses.current_mut()[i];
                if stress.hinge.is_some_and(|end| free[end.node()]) {
                    stress.hinge = None;
                    touched.extend(self.elements[i].nodes);
                }
            }
            if let Some(before) = before {
                self.record_hinge_changes(&before);
            }
            self.update_integration_points();
            self.system = super::condensed_system_of(&self.nodes, &self.elements)?;
            self.end_of_step_forces = None;
            self.connectivity += 1;
            self.restart_accelerations(&touched, loads);
        }
        Ok(())
    }

    /// Makes the accelerations of the `touched` nodes satisfy the equation of motion at the state
    /// after a fracture, `M a = f + m g − R − C v` (C v = a0 M v + a1 K v), on their free DOFs.
    ///
    /// The fracture changes the forces on its element's nodes at once (the element's end forces go
    /// and the split node's mass is shared out), while Newmark's step starts from the acceleration
    /// the last step ended with: from that stale one, the step takes the force change as if it
    /// came on over the step, and the energy account loses `½ [[u]]ᵀ ΔF` (`energy.rs`).
    fn restart_accelerations(&mut self, touched: &[usize], loads: &[f64]) {
        let nodal = self.gather(&self.contributions());
        let mut force: Vec<[f64; NODE_DOFS]> = touched
            .iter()
            .map(|&v| {
                std::array::from_fn(|k| {
                    let load = loads.get(v * NODE_DOFS + k).copied().unwrap_or(0.0);
                    let weight = if k < 3 {
                        nodal.mass[v] * self.gravity[k]
                    } else {
                        0.0
                    };
                    load + weight - nodal.internal[v][k]
                })
            })
            .collect();
        let a1 = self.damping.1;
        if a1 != 0.0 {
            for (e, s) in self.elements.iter().zip(self.stresses.current()) {
                if !e.nodes.iter().any(|v| touched.contains(v)) {
                    continue;
                }
                let k = tangent_stiffness(e, s, &self.sections[e.section]);
                let velocity: Vec<f64> = e.nodes.iter().flat_map(|&v| self.nodes[v].velocity).collect();
                for (end, v) in e.nodes.iter().enumerate() {
                    for (t, f) in touched.iter().zip(force.iter_mut()) {
                        if t != v {
                            continue;
                        }
                        for (c, fc) in f.iter_mut().enumerate() {
                            let row = &k[end * NODE_DOFS + c];
                            *fc -= a1 * row.iter().zip(&velocity).map(|(kij, vj)| kij * vj).sum::<f64>();
                        }
                    }
                }
            }
        }
        let a0 = self.damping.0;
        for (&v, f) in touched.iter().zip(&force) {
            let (m, j) = (nodal.mass[v], nodal.rotary[v]);
            let node = &mut self.nodes[v];
            let fixed = node.fixed;
            if m > 0.0 {
                for k in 0..3 {
                    if !fixed[k] {
                        node.acceleration[k] = f[k] / m - a0 * node.velocity[k];
                    }
                }
            }
            // J α = moment on the free rotations (a fixed one: its row and column made identity,
            // its moment zero, so that it stays at rest)
            let (mut jf, mut mf) = (j, Vector3::new(f[3], f[4], f[5]));
            for k in 0..3 {
                if fixed[3 + k] {
                    jf.row_mut(k).fill(0.0);
                    jf.column_mut(k).fill(0.0);
                    jf[(k, k)] = 1.0;
                    mf[k] = 0.0;
                }
            }
            if let Some(alpha) = jf.lu().solve(&mf) {
                for k in 0..3 {
                    if !fixed[3 + k] {
                        node.acceleration[3 + k] = alpha[k] - a0 * node.velocity[3 + k];
                    }
                }
            }
        }
    }
}
