//! ASI-Gauss framed structures (S2 §3, physics.md §5): members of two linear Timoshenko elements with
//! one integration point each, plastic hinges by the full-plastic yield function, fracture by S2-17,
//! co-rotational (updated-Lagrangian) large displacements and rotations, Newmark β = 4/9, δ = 5/6 with
//! lumped mass and rotary inertia, and a sparse Cholesky solve per step.
//!
//! Node order: the config's nodes in config order, then one mid node per member in member order,
//! then nodes made by fracture. Loads, velocities and displacements have 6 entries per node
//! (x, y, z, rx, ry, rz; global axes).

pub mod assembly;
pub mod element;
pub mod fracture;
pub mod hinge;
pub mod newmark;
pub mod section;
pub mod topology;
pub mod vtu;

use assembly::{SparseSystem, NODE_DOFS};
use element::ELEMENT_DOFS;
use element::{
    add_axial_geometric_stiffness, corotate, local_forces, local_stiffness, strain_matrix, strains, to_global_matrix, to_global_vector,
};
use fracture::FractureCriterion;
use hinge::StressState;
use nalgebra::{DMatrix, Matrix3, UnitQuaternion, Vector3};
use rayon::prelude::*;
use schemas::case::frame::FrameConfig;
use schemas::case::FieldError;
use section::Section;
use std::collections::BTreeMap;
use topology::{Element, Node};

/// Newton corrections per step at most, after the first solve.
pub const MAX_CORRECTIONS: usize = 6;
/// A step has converged when its unbalanced force is this share of the first one.
const RESIDUAL_TOLERANCE: f64 = 1e-6;
/// Largest axial strain of an element before the run is declared unstable.
const MAX_AXIAL_STRAIN: f64 = 0.5;
/// Largest rotation of a node relative to its element's chord [rad] before the run is declared
/// unstable (the natural deformation is ambiguous near π).
const MAX_RELATIVE_ROTATION: f64 = 2.5;

/// An ASI-Gauss frame and its state; a clone is a checkpoint.
#[derive(Clone)]
pub struct Frame {
    time_step: f64,
    gravity: Vector3<f64>,
    density: f64,
    sections: Vec<Section>,
    fracture: Option<FractureCriterion>,
    nodes: Vec<Node>,
    elements: Vec<Element>,
    ids: BTreeMap<u32, usize>,
    system: SparseSystem,
    connectivity: u64,
}

/// What one element adds to the global system at the current state.
struct Contribution {
    /// Tangent stiffness, global axes.
    stiffness: [[f64; ELEMENT_DOFS]; ELEMENT_DOFS],
    /// Internal end forces R, global axes.
    force: [f64; ELEMENT_DOFS],
    /// Lumped rotary inertia given to each end node, global axes.
    rotary: Matrix3<f64>,
    /// Lumped mass given to each end node.
    mass: f64,
}

/// Stiffness and lumped mass over the unknowns, for eigen-analysis of small frames.
pub struct DenseMatrices {
    pub stiffness: DMatrix<f64>,
    pub mass: DMatrix<f64>,
    /// Global DOF (`6 node + k`) of each unknown.
    pub dofs: Vec<usize>,
}

impl Frame {
    /// Builds a frame from its validated config; `key` is the table's path for error messages.
    pub fn from_config(cfg: &FrameConfig, key: &str) -> Result<Frame, FieldError> {
        let (nodes, elements, ids) = topology::build(cfg, key)?;
        let sections = cfg
            .section
            .iter()
            .map(|s| Section::new(s, &cfg.material))
            .collect();
        let fixed: Vec<_> = nodes.iter().map(|n| n.fixed).collect();
        let pairs: Vec<_> = elements.iter().map(|e| e.nodes).collect();
        let system = SparseSystem::new(nodes.len(), &fixed, &pairs).map_err(|m| FieldError::new(key, m))?;
        Ok(Frame {
            time_step: cfg.time_step,
            gravity: Vector3::from(cfg.gravity),
            density: cfg.material.density,
            sections,
            fracture: FractureCriterion::new(&cfg.material),
            nodes,
            elements,
            ids,
            system,
            connectivity: 0,
        })
    }

    /// The Newmark Δt from the config [s].
    pub fn time_step(&self) -> f64 {
        self.time_step
    }

    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Index of the config node with this id.
    pub fn node_index(&self, id: u32) -> Option<usize> {
        self.ids.get(&id).copied()
    }

    /// Positions, 3 per node [m].
    pub fn node_positions(&self) -> Vec<f64> {
        self.nodes
            .iter()
            .flat_map(|n| n.position.iter().copied().collect::<Vec<_>>())
            .collect()
    }

    /// Velocities and angular velocities, 6 per node, global.
    pub fn node_velocities(&self) -> Vec<f64> {
        self.nodes.iter().flat_map(|n| n.velocity).collect()
    }

    /// Sets velocities and angular velocities (6 per node, global), e.g. as initial conditions.
    pub fn set_node_velocities(&mut self, velocities: &[f64]) -> Result<(), String> {
        self.check_per_node("velocities", velocities)?;
        for (n, v) in self.nodes.iter_mut().zip(velocities.chunks_exact(NODE_DOFS)) {
            for k in 0..NODE_DOFS {
                n.velocity[k] = if n.fixed[k] { 0.0 } else { v[k] };
            }
        }
        Ok(())
    }

    /// Lumped translational mass of each node [kg].
    pub fn node_masses(&self) -> Vec<f64> {
        let mut m = vec![0.0; self.nodes.len()];
        for e in &self.elements {
            let half = 0.5 * self.density * self.sections[e.section].area * e.length0;
            m[e.nodes[0]] += half;
            m[e.nodes[1]] += half;
        }
        m
    }

    /// Nodes where a plastic hinge currently sits (sorted, each once).
    pub fn hinge_nodes(&self) -> Vec<usize> {
        let mut v: Vec<usize> = self
            .elements
            .iter()
            .filter_map(|e| e.stress.hinge.map(|end| e.nodes[end.node()]))
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// Number of fractures so far.
    pub fn fracture_count(&self) -> u32 {
        self.elements.iter().map(|e| e.fractures).sum()
    }

    /// Node pair of each element (two elements per member, in member order).
    pub fn element_nodes(&self) -> Vec<[usize; 2]> {
        self.elements.iter().map(|e| e.nodes).collect()
    }

    /// Projected width of each element [m].
    pub fn element_widths(&self) -> Vec<f64> {
        self.elements
            .iter()
            .map(|e| self.sections[e.section].width)
            .collect()
    }

    /// Cross-section area of each element [m²].
    pub fn element_areas(&self) -> Vec<f64> {
        self.elements
            .iter()
            .map(|e| self.sections[e.section].area)
            .collect()
    }

    /// Grows by one each time the connectivity changes (a fracture made new nodes).
    pub fn connectivity_version(&self) -> u64 {
        self.connectivity
    }

    /// One Newmark step of `dt` under `loads` (6 per node: force, moment; global) plus gravity:
    /// `(K + M/(βΔt²)) δ = F − R + M (v/(βΔt) + (1/(2β) − 1) a − Δu/(βΔt²))` (S2-14), solved for the
    /// step's increment Δu; the state is then brought to the end of the step (co-rotational update)
    /// and the unbalanced force, if larger than a 1e-6 share of the first one, is removed by further
    /// Newton corrections (at most [`MAX_CORRECTIONS`]; what is left carries into the next step).
    pub fn step(&mut self, dt: f64, loads: &[f64]) -> Result<(), String> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(format!("frame step: the time step must be a finite number > 0, got {dt}"));
        }
        self.check_per_node("loads", loads)?;
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
        for iteration in 0..=MAX_CORRECTIONS {
            let contributions = self.contributions();
            self.assemble(&mut system, &contributions, 1.0, mass_factor);
            let mut rhs = self.external_minus_internal(&system, &contributions, loads);
            let (mass, rotary) = self.lumped_masses(&contributions);
            for v in 0..self.nodes.len() {
                let g = v * NODE_DOFS;
                let motion: Vec<f64> = (0..NODE_DOFS).map(|k| inertia[g + k] - mass_factor * du[g + k]).collect();
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
            let residual = rhs.iter().map(|r| r * r).sum::<f64>().sqrt();
            let first = *first_residual.get_or_insert(residual);
            if iteration > 0 && residual <= RESIDUAL_TOLERANCE * first {
                break;
            }
            if let Err(e) = system.solve(&mut rhs) {
                outcome = Err(e);
                break;
            }
            for (g, d) in du.iter_mut().enumerate() {
                *d += system.equation(g).map_or(0.0, |eq| rhs[eq]);
            }
            if let Some(i) = du.iter().position(|x| !x.is_finite()) {
                outcome = Err(format!(
                    "frame step: the displacement of node {} is not finite: the run is unstable",
                    i / NODE_DOFS
                ));
                break;
            }
            self.nodes.clone_from(&committed_nodes);
            self.apply_increment(&du);
            self.elements.clone_from(&committed_elements);
            self.update_elements();
        }
        self.system = system;
        outcome?;
        for (node, du) in self.nodes.iter_mut().zip(du.chunks_exact(NODE_DOFS)) {
            for k in 0..NODE_DOFS {
                (node.velocity[k], node.acceleration[k]) = if node.fixed[k] {
                    (0.0, 0.0)
                } else {
                    newmark::advance(du[k], node.velocity[k], node.acceleration[k], dt)
                };
            }
        }
        self.update_integration_points();
        self.split_fractured()?;
        self.check_stability()
    }

    /// Linear static displacements about the current state, `K u = F − R` (F: `loads` plus gravity),
    /// 6 per node; the state is unchanged. One solve: exact for a linear problem from rest.
    pub fn linear_static_displacements(&self, loads: &[f64]) -> Result<Vec<f64>, String> {
        self.check_per_node("loads", loads)?;
        let contributions = self.contributions();
        let mut system = self.system.clone();
        self.assemble(&mut system, &contributions, 1.0, 0.0);
        let mut rhs = self.external_minus_internal(&system, &contributions, loads);
        system.solve(&mut rhs)?;
        Ok(self.increments(&system, &rhs))
    }

    /// Tangent stiffness and lumped mass (with rotary inertia) as dense matrices over the unknowns.
    pub fn dense_matrices(&self) -> DenseMatrices {
        let contributions = self.contributions();
        let n = self.system.unknowns();
        let dofs: Vec<usize> = (0..self.nodes.len() * NODE_DOFS)
            .filter(|&g| self.system.equation(g).is_some())
            .collect();
        let dense = |stiffness: f64, mass: f64| {
            let mut system = self.system.clone();
            self.assemble(&mut system, &contributions, stiffness, mass);
            DMatrix::from_fn(n, n, |r, c| system.get(r, c))
        };
        DenseMatrices {
            stiffness: dense(1.0, 0.0),
            mass: dense(0.0, 1.0),
            dofs,
        }
    }

    fn check_per_node(&self, what: &str, values: &[f64]) -> Result<(), String> {
        let expected = self.nodes.len() * NODE_DOFS;
        if values.len() != expected {
            return Err(format!(
                "frame: {what} must have 6 entries per node ({} nodes → {expected}), got {}",
                self.nodes.len(),
                values.len()
            ));
        }
        match values.iter().position(|x| !x.is_finite()) {
            Some(i) => Err(format!("frame: {what} of node {} is not finite", i / NODE_DOFS)),
            None => Ok(()),
        }
    }

    /// Each element's tangent stiffness, internal forces and lumped masses, in parallel.
    fn contributions(&self) -> Vec<Contribution> {
        self.elements
            .par_iter()
            .map(|e| {
                let section = &self.sections[e.section];
                let tangent = e.stress.tangent(section);
                let mut k = local_stiffness(e.length0, e.stress.s, &tangent);
                add_axial_geometric_stiffness(&mut k, e.stress.sigma[0], e.current.length);
                let f = local_forces(e.length0, e.stress.s, &e.stress.sigma);
                let frame = &e.current.frame;
                let half = 0.5 * self.density * e.length0;
                let local_inertia =
                    Matrix3::from_diagonal(&Vector3::new(section.iy + section.iz, section.iy, section.iz))
                        * half;
                Contribution {
                    stiffness: to_global_matrix(frame, &k),
                    force: to_global_vector(frame, &f),
                    rotary: frame * local_inertia * frame.transpose(),
                    mass: half * section.area,
                }
            })
            .collect()
    }

    /// Translational mass and rotary inertia block of each node.
    fn lumped_masses(&self, contributions: &[Contribution]) -> (Vec<f64>, Vec<Matrix3<f64>>) {
        let mut mass = vec![0.0; self.nodes.len()];
        let mut rotary = vec![Matrix3::zeros(); self.nodes.len()];
        for (e, c) in self.elements.iter().zip(contributions) {
            for &v in &e.nodes {
                mass[v] += c.mass;
                rotary[v] += c.rotary;
            }
        }
        (mass, rotary)
    }

    /// Fills `system` with `stiffness · K + mass · M`.
    fn assemble(&self, system: &mut SparseSystem, contributions: &[Contribution], stiffness: f64, mass: f64) {
        system.clear();
        if stiffness != 0.0 {
            for (e, c) in contributions.iter().enumerate() {
                system.add_element(e, &c.stiffness);
            }
        }
        if mass != 0.0 {
            let (m, j) = self.lumped_masses(contributions);
            for v in 0..self.nodes.len() {
                let mut block = [[0.0; NODE_DOFS]; NODE_DOFS];
                for k in 0..3 {
                    block[k][k] = mass * m[v];
                    for l in 0..3 {
                        block[3 + k][3 + l] = mass * j[v][(k, l)];
                    }
                }
                system.add_node(v, &block);
            }
        }
    }

    /// `F + M g − R` over the unknowns.
    fn external_minus_internal(
        &self,
        system: &SparseSystem,
        contributions: &[Contribution],
        loads: &[f64],
    ) -> Vec<f64> {
        let mut rhs = vec![0.0; system.unknowns()];
        let (mass, _) = self.lumped_masses(contributions);
        for v in 0..self.nodes.len() {
            for k in 0..NODE_DOFS {
                if let Some(eq) = system.equation(v * NODE_DOFS + k) {
                    rhs[eq] += loads[v * NODE_DOFS + k] + if k < 3 { mass[v] * self.gravity[k] } else { 0.0 };
                }
            }
        }
        for (e, c) in self.elements.iter().zip(contributions) {
            for (i, f) in c.force.iter().enumerate() {
                let dof = e.nodes[i / NODE_DOFS] * NODE_DOFS + i % NODE_DOFS;
                if let Some(eq) = system.equation(dof) {
                    rhs[eq] -= f;
                }
            }
        }
        rhs
    }

    /// Solution over the unknowns spread to 6 entries per node (zero where fixed or unused).
    fn increments(&self, system: &SparseSystem, solution: &[f64]) -> Vec<f64> {
        (0..self.nodes.len() * NODE_DOFS)
            .map(|g| system.equation(g).map_or(0.0, |eq| solution[eq]))
            .collect()
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
            let de = strains(&strain_matrix(e.length0, e.stress.s), &dd);
            e.stress.update(&sections[e.section], e.length0, &de);
            e.current = now;
        });
    }

    /// Puts each elastic element's integration point where ASI-Gauss wants it given its member's hinges.
    fn update_integration_points(&mut self) {
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

    /// S2-17 at every hinge; a fractured element is split off its hinge node onto a new node (same
    /// position and motion), left unstressed, and the sparse pattern is rebuilt.
    fn split_fractured(&mut self) -> Result<(), String> {
        let Some(criterion) = self.fracture else {
            return Ok(());
        };
        let mut changed = false;
        for i in 0..self.elements.len() {
            let e = &self.elements[i];
            let Some(end) = e.stress.hinge else { continue };
            if !criterion.is_reached(&e.stress.strain) {
                continue;
            }
            let old = e.nodes[end.node()];
            let mut node = self.nodes[old].clone();
            node.id = None;
            node.fixed = [false; NODE_DOFS];
            self.nodes.push(node);
            let e = &mut self.elements[i];
            e.nodes[end.node()] = self.nodes.len() - 1;
            e.stress = StressState::elastic(e.stress.s);
            e.stress.hinge = None;
            e.fractures += 1;
            changed = true;
        }
        if changed {
            self.update_integration_points();
            let fixed: Vec<_> = self.nodes.iter().map(|n| n.fixed).collect();
            let pairs: Vec<_> = self.elements.iter().map(|e| e.nodes).collect();
            self.system = SparseSystem::new(self.nodes.len(), &fixed, &pairs)?;
            self.connectivity += 1;
        }
        Ok(())
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
        Ok(())
    }
}
