//! Element contributions gathered into the global system: tangent stiffness (with the geometric
//! stiffness of the axial force), internal forces R and lumped mass with rotary inertia; the linear
//! static solve and dense matrices for eigen-analysis built from them.

use super::assembly::{SparseSystem, NODE_DOFS};
use super::element::{
    add_axial_geometric_stiffness, local_forces, local_stiffness, to_global_matrix, to_global_vector,
    ELEMENT_DOFS,
};
use super::Frame;
use nalgebra::{DMatrix, Matrix3, Vector3};
use rayon::prelude::*;

/// What one element adds to the global system at the current state.
pub(super) struct Contribution {
    /// Tangent stiffness, global axes (only when asked for).
    pub stiffness: Option<Box<[[f64; ELEMENT_DOFS]; ELEMENT_DOFS]>>,
    /// Internal end forces R, global axes.
    pub force: [f64; ELEMENT_DOFS],
    /// Lumped rotary inertia given to each end node, global axes.
    pub rotary: Matrix3<f64>,
    /// Lumped mass given to each end node.
    pub mass: f64,
}

/// Stiffness and lumped mass over the unknowns, for eigen-analysis of small frames.
pub struct DenseMatrices {
    pub stiffness: DMatrix<f64>,
    pub mass: DMatrix<f64>,
    /// Global DOF (`6 node + k`) of each unknown.
    pub dofs: Vec<usize>,
}

impl Frame {
    /// Linear static displacements about the current state, `K u = F − R` (F: `loads` plus gravity),
    /// 6 per node; the state is unchanged. One solve: exact for a linear problem from rest.
    pub fn linear_static_displacements(&self, loads: &[f64]) -> Result<Vec<f64>, String> {
        self.check_per_node("loads", loads)?;
        let contributions = self.contributions(true);
        let mut system = self.system.clone();
        self.assemble(&mut system, &contributions, 1.0, 0.0);
        let (mass, _) = self.lumped_masses(&contributions);
        let mut rhs = self.external_minus_internal(&system, &contributions, &mass, loads);
        system.factorize(0.0)?;
        system.solve_factored(&mut rhs)?;
        Ok(self.increments(&system, &rhs))
    }

    /// Tangent stiffness and lumped mass (with rotary inertia) as dense matrices over the unknowns.
    pub fn dense_matrices(&self) -> DenseMatrices {
        let contributions = self.contributions(true);
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

    /// Each element's tangent stiffness, internal forces and lumped masses, in parallel.
    /// `with_stiffness = false` leaves the stiffness out (only forces and masses are needed).
    pub(super) fn contributions(&self, with_stiffness: bool) -> Vec<Contribution> {
        self.elements
            .par_iter()
            .map(|e| {
                let section = &self.sections[e.section];
                let frame = &e.current.frame;
                let stiffness = with_stiffness.then(|| {
                    let mut k = local_stiffness(e.length0, e.stress.s, &e.stress.tangent(section));
                    add_axial_geometric_stiffness(&mut k, e.stress.sigma[0], e.current.length);
                    Box::new(to_global_matrix(frame, &k))
                });
                let f = local_forces(e.length0, e.stress.s, &e.stress.sigma);
                let half = 0.5 * self.density * e.length0;
                let local_inertia =
                    Matrix3::from_diagonal(&Vector3::new(section.iy + section.iz, section.iy, section.iz))
                        * half;
                Contribution {
                    stiffness,
                    force: to_global_vector(frame, &f),
                    rotary: frame * local_inertia * frame.transpose(),
                    mass: half * section.area,
                }
            })
            .collect()
    }

    /// Translational mass and rotary inertia block of each node.
    pub(super) fn lumped_masses(&self, contributions: &[Contribution]) -> (Vec<f64>, Vec<Matrix3<f64>>) {
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
    pub(super) fn assemble(
        &self,
        system: &mut SparseSystem,
        contributions: &[Contribution],
        stiffness: f64,
        mass: f64,
    ) {
        system.clear();
        if stiffness != 0.0 {
            for (e, c) in contributions.iter().enumerate() {
                if let Some(k) = &c.stiffness {
                    system.add_element(e, k);
                }
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
    pub(super) fn external_minus_internal(
        &self,
        system: &SparseSystem,
        contributions: &[Contribution],
        mass: &[f64],
        loads: &[f64],
    ) -> Vec<f64> {
        let mut rhs = vec![0.0; system.unknowns()];
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
    pub(super) fn increments(&self, system: &SparseSystem, solution: &[f64]) -> Vec<f64> {
        (0..self.nodes.len() * NODE_DOFS)
            .map(|g| system.equation(g).map_or(0.0, |eq| solution[eq]))
            .collect()
    }
}
