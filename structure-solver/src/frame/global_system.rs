//! Element contributions gathered into the global system: tangent stiffness (with the geometric
//! stiffness of the axial force), internal forces R and lumped mass with rotary inertia; the linear
//! static solve and dense matrices for eigen-analysis built from them.

use super::assembly::NODE_DOFS;
use super::condensation::Block;
use super::condensed_system::NodeBlock;
use super::element::{
    add_axial_geometric_stiffness, global_stiffness, local_forces, to_global_vector, ELEMENT_DOFS,
};
use super::hinge::StressState;
use super::section::Section;
use super::topology::Element;
use super::Frame;
use nalgebra::{DMatrix, Matrix3, Vector3};
use rayon::prelude::*;

/// What one element adds to the right-hand side and the mass of the global system at the current
/// state (its stiffness is [`tangent_stiffness`]).
pub(super) struct Contribution {
    /// Internal end forces R, global axes.
    pub force: [f64; ELEMENT_DOFS],
    /// Lumped rotary inertia given to each end node, global axes.
    pub rotary: Matrix3<f64>,
    /// Lumped mass given to each end node.
    pub mass: f64,
}

impl Contribution {
    /// What element `e` of `section` in stress state `stress` adds at its current state.
    pub(super) fn of(e: &Element, stress: &StressState, section: &Section, density: f64) -> Contribution {
        let f = local_forces(e.length0, stress.s, &stress.sigma);
        let (mass, rotary) = end_mass(e, section, density);
        Contribution {
            force: to_global_vector(&e.current.frame, &f),
            rotary,
            mass,
        }
    }
}

/// Tangent stiffness of element `e` in stress state `stress` at its current state (with the
/// geometric stiffness of its axial force), global axes.
pub(super) fn tangent_stiffness(e: &Element, stress: &StressState, section: &Section) -> Block {
    let frame = &e.current.frame;
    let mut k = global_stiffness(frame, e.length0, stress.s, &stress.tangent(section));
    if !e.linear {
        add_axial_geometric_stiffness(&mut k, frame, stress.sigma[0], e.current.length);
    }
    k
}

/// Lumped mass and rotary inertia (global axes) that element `e` gives each of its end nodes.
pub(super) fn end_mass(e: &Element, section: &Section, density: f64) -> (f64, Matrix3<f64>) {
    let frame = &e.current.frame;
    let half = 0.5 * density * e.length0;
    let local_inertia =
        Matrix3::from_diagonal(&Vector3::new(section.iy + section.iz, section.iy, section.iz)) * half;
    (half * section.area, frame * local_inertia * frame.transpose())
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
    /// 6 per node; the state is unchanged. One solve of the condensed system (exact for a linear
    /// problem from rest).
    pub fn linear_static_displacements(&self, loads: &[f64]) -> Result<Vec<f64>, String> {
        self.check_per_node("loads", loads)?;
        let contributions = self.contributions();
        let mut system = self.system.clone();
        system.assemble(
            &|e| self.tangent_stiffness(e),
            &self.node_blocks(&contributions, 0.0),
        )?;
        let mut u = self.unbalanced_force(&self.gather(&contributions), loads, None);
        system.factorize(0.0)?;
        system.solve(&mut u, 0, 0.0)?;
        Ok(u)
    }

    /// Tangent stiffness and lumped mass (with rotary inertia) as dense matrices over all unknowns
    /// (nothing condensed).
    pub fn dense_matrices(&self) -> DenseMatrices {
        let contributions = self.contributions();
        let dofs: Vec<usize> = (0..self.nodes.len() * NODE_DOFS)
            .filter(|&g| self.system.is_unknown(g))
            .collect();
        let mut column = vec![None; self.nodes.len() * NODE_DOFS];
        for (i, &g) in dofs.iter().enumerate() {
            column[g] = Some(i);
        }
        let n = dofs.len();
        let mut stiffness = DMatrix::zeros(n, n);
        for (index, e) in self.elements.iter().enumerate() {
            let at = |i: usize| column[NODE_DOFS * e.nodes[i / NODE_DOFS] + i % NODE_DOFS];
            add_block(&mut stiffness, &self.tangent_stiffness(index), at);
        }
        let mut mass = DMatrix::zeros(n, n);
        for (v, block) in self.node_blocks(&contributions, 1.0).iter().enumerate() {
            add_block(&mut mass, block, |i| column[NODE_DOFS * v + i]);
        }
        DenseMatrices {
            stiffness,
            mass,
            dofs,
        }
    }

    /// Tangent stiffness of element `e` at its current state, global axes.
    pub(super) fn tangent_stiffness(&self, e: usize) -> Block {
        let element = &self.elements[e];
        tangent_stiffness(
            element,
            &self.stresses.current()[e],
            &self.sections[element.section],
        )
    }

    /// Each element's internal forces and lumped masses, in parallel.
    pub(super) fn contributions(&self) -> Vec<Contribution> {
        self.elements
            .par_iter()
            .zip(self.stresses.current())
            .with_min_len(super::PARALLEL_CHUNK)
            .map(|(e, s)| Contribution::of(e, s, &self.sections[e.section], self.density))
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

    /// Each node's 6 × 6 block of `mass · M` (lumped mass and rotary inertia).
    pub(super) fn node_blocks(&self, contributions: &[Contribution], mass: f64) -> Vec<NodeBlock> {
        let (m, j) = self.lumped_masses(contributions);
        m.iter()
            .zip(&j)
            .map(|(m, j)| mass_block(mass * m, &(j * mass)))
            .collect()
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

    /// `F + M g − R` over all global DOFs (zero where a DOF is not an unknown), plus with `motion` the Newmark inertia
    /// `M (v/(βΔt) + (1/(2β) − 1) a − Δu/(βΔt²))` (S2-14).
    pub(super) fn unbalanced_force(
        &self,
        nodal: &NodalForces,
        loads: &[f64],
        motion: Option<Motion>,
    ) -> Vec<f64> {
        // a node that a fracture added within this step (in a cut part) has no load until the
        // structure re-declares its geometry at the window end
        const NO_LOAD: [f64; NODE_DOFS] = [0.0; NODE_DOFS];
        let mut rhs = vec![0.0; self.nodes.len() * NODE_DOFS];
        for v in 0..self.nodes.len() {
            let g = v * NODE_DOFS;
            // one length check per node, not one per entry (1 % of a 7³ building's step)
            let load: &[f64; NODE_DOFS] = loads
                .get(g..g + NODE_DOFS)
                .and_then(|l| l.try_into().ok())
                .unwrap_or(&NO_LOAD);
            let mut f = [0.0; NODE_DOFS];
            for (k, fk) in f.iter_mut().enumerate() {
                *fk = load[k] - nodal.internal[v][k]
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
                if self.system.is_unknown(g + k) {
                    rhs[g + k] = *fk;
                }
            }
        }
        rhs
    }
}

/// The 6 × 6 block of a translational mass `m` and a rotary inertia `j`.
pub(super) fn mass_block(m: f64, j: &Matrix3<f64>) -> NodeBlock {
    let mut block = [[0.0; NODE_DOFS]; NODE_DOFS];
    for k in 0..3 {
        block[k][k] = m;
        for l in 0..3 {
            block[3 + k][3 + l] = j[(k, l)];
        }
    }
    block
}

/// Adds the square `block` to the dense matrix `m`, its row and column i at `at(i)` (`None`: left out).
fn add_block<const N: usize>(
    m: &mut DMatrix<f64>,
    block: &[[f64; N]; N],
    at: impl Fn(usize) -> Option<usize>,
) {
    for (i, row) in block.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            if let (Some(r), Some(c)) = (at(i), at(j)) {
                m[(r, c)] += x;
            }
        }
    }
}
