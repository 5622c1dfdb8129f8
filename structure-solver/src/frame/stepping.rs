//! One Newmark step of a frame (S2-14): the increment is solved with the kept factor of the effective
//! matrix and the state is brought to the end of the step in co-rotational form. As in ASI-Gauss
//! (physics.md §5) there is one linear solve per step and the unbalanced force carries into the next
//! one; equilibrium corrections within the step are an option ([`Equilibrium::Iterate`]).

use super::assembly::{SparseSystem, NODE_DOFS};
use super::element::{corotate, ELEMENT_DOFS};
use super::global_system::{Contribution, Motion, NodalForces};
use super::newmark;
use super::section::Section;
use super::topology::{Element, Node};
use super::{Frame, PARALLEL_CHUNK};
use nalgebra::{UnitQuaternion, Vector3};
use rayon::prelude::*;

/// Largest axial strain of an element before the run is declared unstable.
const MAX_AXIAL_STRAIN: f64 = 0.5;
/// Largest rotation of a node relative to its element's chord [rad] before the run is declared
/// unstable (the natural deformation is ambiguous near π).
const MAX_RELATIVE_ROTATION: f64 = 2.5;

/// Share of its first unbalanced force above which a one-solve step counts in
/// [`Frame::unconverged_steps`]: a sign that Δt is too long for one solve per step. Measured on the
/// benchmark's 3 × 3 × 3 building with hinges forming: at Δt = 1 ms steps left up to 1.3 and the run
/// ended with 130 hinge nodes against 32 with equilibrium iterations; at 0.5 ms and 0.25 ms they left
/// at most 0.018 and 0.004 and both ended with 32.
pub const ONE_SOLVE_UNBALANCE_LIMIT: f64 = 0.1;

/// What a step does with the unbalanced force its linear solve leaves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Equilibrium {
    /// ASI-Gauss's one linear solve per step (S2-14): the unbalanced force carries into the next
    /// step, whose internal forces R are evaluated at the state this one reached.
    OneSolve,
    /// Corrections of the step's increment until the unbalanced force is below `tolerance` times
    /// the step's first one, at most [`super::MAX_CORRECTIONS`] (see `equilibrium.rs`).
    Iterate { tolerance: f64 },
}

impl Frame {
    /// One Newmark step of `dt` under `loads` (6 per node: force, moment; global) plus gravity and
    /// contact forces: `(K + M/(βΔt²)) Δu = F − R + M (v/(βΔt) + (1/(2β) − 1) a)` (S2-14) with R the
    /// internal forces at the start of the step, solved once with the kept factor (see
    /// `factor_age.rs` for when it is redone), then the co-rotational update to the end of the step.
    /// With [`Equilibrium::Iterate`] the increment is corrected until equilibrium instead.
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
        let inertia: Vec<f64> = self
            .nodes
            .iter()
            .flat_map(|n| (0..NODE_DOFS).map(|k| newmark::inertia_term(n.velocity[k], n.acceleration[k], dt)))
            .collect();
        if !self.system.has_factor_for(dt)
            || self
                .factor_age
                .is_stale(&self.elements, &self.sections, self.density, dt, self.stale_limit)
        {
            self.system.drop_factor();
        }
        let (du, hinges_changed) = match self.equilibrium {
            Equilibrium::OneSolve => self.solve_once(dt, loads, &inertia)?,
            Equilibrium::Iterate { tolerance } => {
                self.solve_to_equilibrium(dt, loads, &inertia, tolerance)?
            }
        };
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
        if hinges_changed {
            self.system.drop_factor();
        }
        self.split_fractured()?;
        self.check_stability()
    }

    /// ASI's one solve: the increment from the unbalanced force at the start of the step, the state
    /// moved by it, and the internal forces there kept for the next step. Returns the increment and
    /// whether a hinge formed or closed.
    fn solve_once(&mut self, dt: f64, loads: &[f64], inertia: &[f64]) -> Result<(Vec<f64>, bool), String> {
        let mass_factor = newmark::mass_factor(dt);
        let refactor = !self.system.has_factor_for(dt);
        let nodal = match self.end_of_step_forces.take() {
            Some(nodal) if !refactor => nodal,
            _ => {
                let contributions = self.contributions(refactor);
                if refactor {
                    self.refactor(&contributions, dt, mass_factor)?;
                }
                self.gather(&contributions)
            }
        };
        let du = vec![0.0; self.nodes.len() * NODE_DOFS];
        let mut rhs = self.residual(&nodal, loads, inertia, &du, mass_factor);
        let first = norm(&rhs);
        self.system.solve_factored(&mut rhs)?;
        let du = self.increments(&self.system, &rhs);
        check_finite(&du)?;
        self.apply_increment(&du);
        let (contributions, hinges_changed) = self.update_elements_with_forces();
        let nodal = self.gather(&contributions);
        let last = norm(&self.residual(&nodal, loads, inertia, &du, mass_factor));
        self.end_of_step_forces = Some(nodal);
        self.unbalance = if first > 0.0 { last / first } else { 0.0 };
        if self.unbalance > ONE_SOLVE_UNBALANCE_LIMIT {
            self.unconverged += 1;
        }
        Ok((du, hinges_changed))
    }

    /// Assembles `K + M/(βΔt²)` from `contributions` (made with stiffness) and factorises it.
    pub(super) fn refactor(
        &mut self,
        contributions: &[Contribution],
        dt: f64,
        mass_factor: f64,
    ) -> Result<(), String> {
        let mut system = std::mem::replace(&mut self.system, SparseSystem::new(0, &[], &[])?);
        self.assemble(&mut system, contributions, 1.0, mass_factor);
        let outcome = system.factorize(dt);
        self.system = system;
        self.factorizations += 1;
        self.factor_age.record(&self.elements);
        outcome
    }

    /// Unbalanced force of the trial state reached by the increment `du` (S2-14, see
    /// [`Frame::unbalanced_force`]).
    pub(super) fn residual(
        &self,
        nodal: &NodalForces,
        loads: &[f64],
        inertia: &[f64],
        du: &[f64],
        mass_factor: f64,
    ) -> Vec<f64> {
        let motion = Motion {
            inertia,
            increment: du,
            mass_factor,
        };
        self.unbalanced_force(nodal, loads, Some(motion))
    }

    /// Moves the nodes by `du`; rotations compose as `exp(Δθ) R` (updated Lagrangian: Δθ is spatial).
    pub(super) fn apply_increment(&mut self, du: &[f64]) {
        self.nodes
            .par_iter_mut()
            .zip(du.par_chunks_exact(NODE_DOFS))
            .with_min_len(PARALLEL_CHUNK)
            .for_each(|(node, du)| {
                node.position += Vector3::new(du[0], du[1], du[2]);
                let spin = UnitQuaternion::from_scaled_axis(Vector3::new(du[3], du[4], du[5]));
                node.rotation = spin * node.rotation;
                node.rotation.renormalize_fast();
            });
    }

    /// New co-rotational frames, natural deformation increments and resultants of every element;
    /// returns whether a hinge formed or closed.
    pub(super) fn update_elements(&mut self) -> bool {
        let (nodes, sections) = (&self.nodes, &self.sections);
        self.elements
            .par_iter_mut()
            .with_min_len(PARALLEL_CHUNK)
            .map(|e| update_element(e, nodes, sections))
            .reduce(|| false, |a, b| a || b)
    }

    /// [`Frame::update_elements`] and, in the same pass, the elements' contributions at the new
    /// state without stiffness.
    fn update_elements_with_forces(&mut self) -> (Vec<Contribution>, bool) {
        let (nodes, sections, density) = (&self.nodes, &self.sections, self.density);
        let (contributions, changed): (Vec<Contribution>, Vec<bool>) = self
            .elements
            .par_iter_mut()
            .with_min_len(PARALLEL_CHUNK)
            .map(|e| {
                let changed = update_element(e, nodes, sections);
                (Contribution::of(e, &sections[e.section], density, false), changed)
            })
            .unzip();
        (contributions, changed.contains(&true))
    }

    /// Puts each elastic element's integration point where ASI-Gauss wants it given its member's hinges.
    pub(super) fn update_integration_points(&mut self) {
        self.elements
            .par_chunks_exact_mut(2)
            .with_min_len(PARALLEL_CHUNK / 2)
            .for_each(|member| {
                let hinged = [member[0].stress.hinge.is_some(), member[1].stress.hinge.is_some()];
                for (half, e) in member.iter_mut().enumerate() {
                    if !hinged[half] {
                        let s = e.elastic_integration_point(hinged[1 - half]);
                        e.stress.move_to(e.length0, s);
                    }
                }
            });
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

/// Brings element `e` to the current node positions and rotations: its co-rotational frame, natural
/// deformation increment and resultants; returns whether a hinge formed or closed.
fn update_element(e: &mut Element, nodes: &[Node], sections: &[Section]) -> bool {
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
    let hinge = e.stress.hinge;
    e.stress.update(&sections[e.section], e.length0, &dd);
    e.current = now;
    e.stress.hinge != hinge
}

/// Euclidean norm.
pub(super) fn norm(x: &[f64]) -> f64 {
    x.iter().map(|r| r * r).sum::<f64>().sqrt()
}

/// Stops a step whose increment is not finite.
pub(super) fn check_finite(du: &[f64]) -> Result<(), String> {
    match du.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(format!(
            "frame step: the displacement of node {} is not finite: the run is unstable",
            i / NODE_DOFS
        )),
        None => Ok(()),
    }
}
