//! Element contributions gathered into the global system: tangent stiffness (with the geometric
//! stiffness of the axial force), internal forces R and lumped mass with rotary inertia; the linear
//! static solve and dense matrices for eigen-analysis built from them.

use super::assembly::{SparseSystem, NODE_DOFS};
use super::element::{
    add_axial_geometric_stiffness, local_forces, local_stiffness, to_global_matrix, to_global_vector,
    ELEMENT_DOFS,
};
use super::section::Section;
use super::topology::Element;
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

impl Contribution {
    /// What element `e` of `section` adds at its current state (with its tangent stiffness when
    /// `with_stiffness`).
    pub(super) fn of(e: &Element, section: &Section, density: f64, with_stiffness: bool) -> Contribution {
        let frame = &e.current.frame;
        let stiffness = with_stiffness.then(|| {
            let mut k = local_stiffness(e.length0, e.stress.s, &e.stress.tangent(section));
            add_axial_geometric_stiffness(&mut k, e.stress.sigma[0], e.current.length);
            Box::new(to_global_matrix(frame, &k))
        });
        let f = local_forces(e.length0, e.stress.s, &e.stress.sigma);
        let half = 0.5 * density * e.length0;
        let local_inertia =
            Matrix3::from_diagonal(&Vector3::new(section.iy + section.iz, section.iy, section.iz)) * half;
        Contribution {
            stiffness,
            force: to_global_vector(frame, &f),
            rotary: frame * local_inertia * frame.transpose(),
            mass: half * section.area,
        }
    }
}

/// Internal forces R and lumped masses gathered on the nodes, global axes.
#[derive(Clone)]
pub(super) struct NodalForces {
    pub internal: Vec<[f64; NODE_DOFS]>,
    pub mass: Vec<f64>,
    pub rotary: Vec<Matrix3<f64>>,
}

/// Newmark terms of the unbalanced force: per global DOF the old motion's term
/// `v/(βΔt) + (1/(2β) − 1) a`, the step's increment Δu, and `1/(βΔt²)`.
pub(super) struct Motion<'a> {
    pub inertia: &'a [f64],
    pub increment: &'a [f64],
    pub mass_factor: f64,
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
        let mut rhs = self.unbalanced_force(&self.gather(&contributions), loads, None);
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
            .with_min_len(super::PARALLEL_CHUNK)
            .map(|e| Contribution::of(e, &self.sections[e.section], self.density, with_stiffness))
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

    /// Element forces and masses summed on the nodes.
    pub(super) fn gather(&self, contributions: &[Contribution]) -> NodalForces {
        let (mass, rotary) = self.lumped_masses(contributions);
        let mut internal = vec![[0.0; NODE_DOFS]; self.nodes.len()];
        for (e, c) in self.elements.iter().zip(contributions) {
            for (end, &v) in e.nodes.iter().enumerate() {
                for (r, f) in internal[v].iter_mut().zip(&c.force[end * NODE_DOFS..]) {
                    *r += f;
                }
            }
        }
        NodalForces {
            internal,
            mass,
            rotary,
        }
    }

    /// `F + M g − R` over the unknowns, plus with `motion` the Newmark inertia
    /// `M (v/(βΔt) + (1/(2β) − 1) a − Δu/(βΔt²))` (S2-14).
    pub(super) fn unbalanced_force(
        &self,
        nodal: &NodalForces,
        loads: &[f64],
        motion: Option<Motion>,
    ) -> Vec<f64> {
        let mut rhs = vec![0.0; self.system.unknowns()];
        for v in 0..self.nodes.len() {
            let g = v * NODE_DOFS;
            let mut f = [0.0; NODE_DOFS];
            for (k, fk) in f.iter_mut().enumerate() {
                *fk = loads[g + k] - nodal.internal[v][k]
                    + if k < 3 {
                        nodal.mass[v] * self.gravity[k]
                    } else {
                        0.0
                    };
            }
            if let Some(m) = &motion {
                let mut a = [0.0; NODE_DOFS];
                for (k, ak) in a.iter_mut().enumerate() {
                    *ak = m.inertia[g + k] - m.mass_factor * m.increment[g + k];
                }
                for k in 0..3 {
                    f[k] += nodal.mass[v] * a[k];
                    f[3 + k] += (0..3).map(|j| nodal.rotary[v][(k, j)] * a[3 + j]).sum::<f64>();
                }
            }
            for (k, fk) in f.iter().enumerate() {
                if let Some(eq) = self.system.equation(g + k) {
                    rhs[eq] = *fk;
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
