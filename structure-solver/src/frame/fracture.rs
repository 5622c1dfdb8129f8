//! Fracture of a fully plastic section (S2-17) and the split of the fractured element at its hinge.

use super::assembly::NODE_DOFS;
use super::hinge::StressState;
use super::hinge_events::{HingeEvent, HingeEventKind};
use super::section::Resultants;
use super::Frame;
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

impl Frame {
    /// S2-17 at every hinge; a fractured element is split off its hinge node onto a new node (same
    /// position and motion), left unstressed, and the condensation and the sparse pattern are rebuilt.
    /// An element's free end (a node no other element and no support holds) is not split.
    pub(super) fn split_fractured(&mut self) -> Result<(), String> {
        let Some(criterion) = self.fracture else {
            return Ok(());
        };
        let mut changed = false;
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
            self.update_integration_points();
            self.system = super::condensed_system_of(&self.nodes, &self.elements)?;
            self.end_of_step_forces = None;
            self.connectivity += 1;
        }
        Ok(())
    }
}
