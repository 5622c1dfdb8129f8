//! One Newmark step of a frame (S2-14): the increment is solved with the kept factor of the
//! effective matrix, the state is brought to the end of the step in co-rotational form, and
//! corrections remove the unbalanced force.

use super::assembly::{SparseSystem, NODE_DOFS};
use super::element::{corotate, ELEMENT_DOFS};
use super::global_system::Contribution;
use super::newmark;
use super::topology::{Element, Node};
use super::Frame;
use nalgebra::{UnitQuaternion, Vector3};
use rayon::prelude::*;

/// Corrections per step at most.
pub const MAX_CORRECTIONS: usize = 12;
/// Times a correction that increases the unbalanced force is halved before it is taken anyway.
const MAX_HALVINGS: usize = 3;
/// A correction that reduces the unbalanced force by less than this factor makes the factor be redone.
const SLOW_CONVERGENCE: f64 = 0.25;
/// A step has converged when its unbalanced force is this share of the first one.
const RESIDUAL_TOLERANCE: f64 = 1e-6;
/// Largest axial strain of an element before the run is declared unstable.
const MAX_AXIAL_STRAIN: f64 = 0.5;
/// Largest rotation of a node relative to its element's chord [rad] before the run is declared
/// unstable (the natural deformation is ambiguous near π).
const MAX_RELATIVE_ROTATION: f64 = 2.5;

impl Frame {
    /// One Newmark step of `dt` under `loads` (6 per node: force, moment; global) plus gravity and
    /// contact forces: `(K + M/(βΔt²)) δ = F − R + M (v/(βΔt) + (1/(2β) − 1) a − Δu/(βΔt²))` (S2-14)
    /// is solved for corrections δ of the step's increment Δu, the state being brought to the end of
    /// the step (co-rotational update) after each, until the unbalanced force is below a 1e-6 share
    /// of the first one. A correction that increases it is halved (hinges switching); when
    /// [`MAX_CORRECTIONS`] do not suffice, the best iterate is kept and its unbalanced force carries
    /// into the next step as in ASI's one-solve steps ([`Frame::unconverged_steps`] counts these).
    /// The factor of the effective matrix is kept between steps (modified Newton) and redone when
    /// Δt, the connectivity or a hinge changed, or when a correction converges slowly.
    pub fn step(&mut self, dt: f64, loads: &[f64]) -> Result<(), String> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(format!(
                "frame step: the time step must be a finite number > 0, got {dt}"
            ));
        }
        self.check_per_node("loads", loads)?;
        let with_contact: Vec<f64>;
        let loads = match &self.contact {
            Some(c) => {
                let f = c.forces(&self.nodes, &self.elements, &self.sections, self.density);
                with_contact = loads.iter().zip(&f).map(|(a, b)| a + b).collect();
                &with_contact
            }
            None => loads,
        };
        let committed_nodes = self.nodes.clone();
        let committed_elements = self.elements.clone();
        let mass_factor = newmark::mass_factor(dt);
        let inertia: Vec<f64> = self
            .nodes
            .iter()
            .flat_map(|n| (0..NODE_DOFS).map(|k| newmark::inertia_term(n.velocity[k], n.acceleration[k], dt)))
            .collect();
        let mut du = vec![0.0; self.nodes.len() * NODE_DOFS];
        let mut system = std::mem::replace(&mut self.system, SparseSystem::new(0, &[], &[])?);
        let mut first_residual = None;
        let mut outcome = Ok(());
        let mut last_residual = f64::INFINITY;
        let mut best = (f64::INFINITY, du.clone());
        // the iterate the last correction started from, that correction and the halvings done on it
        let mut last_correction: Option<(Vec<f64>, Vec<f64>)> = None;
        let mut halvings = 0;
        for iteration in 0..=MAX_CORRECTIONS + 1 {
            let mut refactor = !system.has_factor_for(dt);
            let mut contributions = self.contributions(refactor);
            let mut rhs = self.residual(&system, &contributions, loads, &inertia, &du, mass_factor);
            let residual = rhs.iter().map(|r| r * r).sum::<f64>().sqrt();
            let first = *first_residual.get_or_insert(residual);
            if iteration > 0 && residual <= RESIDUAL_TOLERANCE * first {
                break;
            }
            if iteration > MAX_CORRECTIONS {
                // as in ASI's one-solve steps, the unbalanced force of the best iterate carries into
                // the next step's residual
                self.unconverged += 1;
                if best.1 != du {
                    du = best.1.clone();
                    self.set_trial(&committed_nodes, &committed_elements, &du);
                }
                break;
            }
            if residual < best.0 {
                best = (residual, du.clone());
            }
            if let Some((from, delta)) = &mut last_correction {
                if residual > last_residual && halvings < MAX_HALVINGS {
                    // the correction overshot (hinges switching): try half of it
                    halvings += 1;
                    delta.iter_mut().for_each(|d| *d *= 0.5);
                    du = from.iter().zip(delta.iter()).map(|(a, b)| a + b).collect();
                    self.set_trial(&committed_nodes, &committed_elements, &du);
                    continue;
                }
                if residual > SLOW_CONVERGENCE * last_residual && !refactor {
                    // the kept factor is a poor iteration matrix now: redo it from the current tangent
                    refactor = true;
                    contributions = self.contributions(true);
                }
            }
            halvings = 0;
            last_residual = residual;
            if refactor {
                self.assemble(&mut system, &contributions, 1.0, mass_factor);
                self.factorizations += 1;
                if let Err(e) = system.factorize(dt) {
                    outcome = Err(e);
                    break;
                }
            }
            if let Err(e) = system.solve_factored(&mut rhs) {
                outcome = Err(e);
                break;
            }
            let delta: Vec<f64> = (0..du.len())
                .map(|g| system.equation(g).map_or(0.0, |eq| rhs[eq]))
                .collect();
            last_correction = Some((du.clone(), delta.clone()));
            for (d, x) in du.iter_mut().zip(&delta) {
                *d += x;
            }
            if let Some(i) = du.iter().position(|x| !x.is_finite()) {
                outcome = Err(format!(
                    "frame step: the displacement of node {} is not finite: the run is unstable",
                    i / NODE_DOFS
                ));
                break;
            }
            self.set_trial(&committed_nodes, &committed_elements, &du);
        }
        self.system = system;
        outcome?;
        for (node, du) in self.nodes.iter_mut().zip(du.chunks_exact(NODE_DOFS)) {
            for (k, duk) in du.iter().enumerate() {
                (node.velocity[k], node.acceleration[k]) = if node.fixed[k] {
                    (0.0, 0.0)
                } else {
                    newmark::advance(*duk, node.velocity[k], node.acceleration[k], dt)
                };
            }
        }
        self.update_integration_points();
        let hinges_changed = self
            .elements
            .iter()
            .zip(&committed_elements)
            .any(|(now, before)| now.stress.hinge != before.stress.hinge);
        if hinges_changed {
            self.system.drop_factor();
        }
        self.split_fractured()?;
        self.check_stability()
    }

    /// Unbalanced force of the trial state reached by the increment `du`:
    /// `F + M g − R + M (v/(βΔt) + (1/(2β) − 1) a − Δu/(βΔt²))` over the unknowns.
    fn residual(
        &self,
        system: &SparseSystem,
        contributions: &[Contribution],
        loads: &[f64],
        inertia: &[f64],
        du: &[f64],
        mass_factor: f64,
    ) -> Vec<f64> {
        let (mass, rotary) = self.lumped_masses(contributions);
        let mut rhs = self.external_minus_internal(system, contributions, &mass, loads);
        for v in 0..self.nodes.len() {
            let g = v * NODE_DOFS;
            let motion: Vec<f64> = (0..NODE_DOFS)
                .map(|k| inertia[g + k] - mass_factor * du[g + k])
                .collect();
            for k in 0..NODE_DOFS {
                if let Some(eq) = system.equation(g + k) {
                    rhs[eq] += if k < 3 {
                        mass[v] * motion[k]
                    } else {
                        (0..3).map(|j| rotary[v][(k - 3, j)] * motion[3 + j]).sum::<f64>()
                    };
                }
            }
        }
        rhs
    }

    /// Puts the frame in the state the committed one reaches with the increment `du`.
    fn set_trial(&mut self, committed_nodes: &[Node], committed_elements: &[Element], du: &[f64]) {
        self.nodes.clone_from_slice(committed_nodes);
        self.apply_increment(du);
        self.elements.clone_from_slice(committed_elements);
        self.update_elements();
    }

    /// Moves the nodes by `du`; rotations compose as `exp(Δθ) R` (updated Lagrangian: Δθ is spatial).
    fn apply_increment(&mut self, du: &[f64]) {
        for (node, du) in self.nodes.iter_mut().zip(du.chunks_exact(NODE_DOFS)) {
            node.position += Vector3::new(du[0], du[1], du[2]);
            let spin = UnitQuaternion::from_scaled_axis(Vector3::new(du[3], du[4], du[5]));
            node.rotation = spin * node.rotation;
            node.rotation.renormalize_fast();
        }
    }

    /// New co-rotational frames, natural deformation increments and resultants of every element.
    fn update_elements(&mut self) {
        let nodes = &self.nodes;
        let sections = &self.sections;
        self.elements.par_iter_mut().for_each(|e| {
            let [a, b] = e.nodes;
            let (na, nb) = (&nodes[a], &nodes[b]);
            let now = corotate(
                &na.position,
                &nb.position,
                &na.rotation,
                &nb.rotation,
                &e.reference,
                e.length0,
            );
            let mut dd = [0.0; ELEMENT_DOFS];
            for (i, d) in dd.iter_mut().enumerate() {
                *d = now.deformation[i] - e.current.deformation[i];
            }
            e.stress.update(&sections[e.section], e.length0, &dd);
            e.current = now;
        });
    }

    /// Puts each elastic element's integration point where ASI-Gauss wants it given its member's hinges.
    pub(super) fn update_integration_points(&mut self) {
        for first in (0..self.elements.len()).step_by(2) {
            let hinged = [
                self.elements[first].stress.hinge.is_some(),
                self.elements[first + 1].stress.hinge.is_some(),
            ];
            for half in 0..2 {
                let e = &mut self.elements[first + half];
                if !hinged[half] {
                    let s = e.elastic_integration_point(hinged[1 - half]);
                    e.stress.move_to(e.length0, s);
                }
            }
        }
    }

    /// Stops a run whose elements stretch or twist beyond what the formulation can represent.
    fn check_stability(&self) -> Result<(), String> {
        for (i, e) in self.elements.iter().enumerate() {
            let strain = e.current.length / e.length0 - 1.0;
            let rotation = e.current.deformation[3..6]
                .iter()
                .chain(&e.current.deformation[9..12])
                .fold(0.0_f64, |m, x| m.max(x.abs()));
            let bad_values = !(strain.is_finite() && rotation.is_finite());
            if bad_values || strain.abs() > MAX_AXIAL_STRAIN || rotation > MAX_RELATIVE_ROTATION {
                return Err(format!(
                    "frame: element {i} (member {}) has axial strain {strain:.3} and end rotation {rotation:.3} rad \
                     relative to its chord (limits {MAX_AXIAL_STRAIN} and {MAX_RELATIVE_ROTATION} rad): the run is \
                     unstable; reduce the time step or the loads",
                    e.member
                ));
            }
        }
        match &self.contact {
            Some(c) => c.check_walls(&self.nodes, &self.elements, &self.sections),
            None => Ok(()),
        }
    }
}
