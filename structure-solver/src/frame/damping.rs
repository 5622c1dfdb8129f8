//! Rayleigh damping `C = a0 M + a1 K` (K the current tangent stiffness) in the Newmark step: with
//! `v' = (δ/(βΔt)) Δu + v̂`, `v̂ = (1 − δ/β) v + Δt (1 − δ/(2β)) a`, the damping force `−C v'` adds
//! `a0 δ/(βΔt) M + a1 δ/(βΔt) K` to the effective matrix and `−C v̂` to the right-hand side
//! (Hughes, The Finite Element Method, 1987, §9.1). The mass part rides on the inertia term (the
//! matrix's mass factor grows by `1 + a0 δ Δt`); the stiffness part scales the element stiffness
//! in the matrix by `1 + a1 δ/(βΔt)` and is applied element by element to the velocity.

use super::assembly::NODE_DOFS;
use super::element::ELEMENT_DOFS;
use super::global_system::tangent_stiffness;
use super::newmark::{self, BETA, DELTA};
use super::Frame;

impl Frame {
    /// Whether the frame has Rayleigh damping.
    pub fn is_damped(&self) -> bool {
        self.damping != (0.0, 0.0)
    }

    /// Rayleigh coefficients `(a0 [1/s], a1 [s])`.
    pub fn damping_coefficients(&self) -> (f64, f64) {
        self.damping
    }

    /// Factor of M in the effective matrix and of the increment in the inertia term:
    /// `(1 + a0 δ Δt) / (β Δt²)`.
    pub(super) fn effective_mass_factor(&self, dt: f64) -> f64 {
        newmark::mass_factor(dt) * (1.0 + self.damping.0 * DELTA * dt)
    }

    /// Factor of K in the effective matrix: `1 + a1 δ/(βΔt)`.
    pub(super) fn stiffness_factor(&self, dt: f64) -> f64 {
        1.0 + self.damping.1 * DELTA / (BETA * dt)
    }

    /// The step's inertia term per unit mass, `v/(βΔt) + (1/(2β) − 1) a − a0 v̂`, and (damped) v̂
    /// kept for the stiffness part.
    pub(super) fn inertia_with_damping(&mut self, dt: f64) -> Vec<f64> {
        let a0 = self.damping.0;
        let mut inertia = Vec::with_capacity(self.nodes.len() * NODE_DOFS);
        self.predicted_velocity.clear();
        for n in &self.nodes {
            for k in 0..NODE_DOFS {
                let (v, a) = (n.velocity[k], n.acceleration[k]);
                let mut term = newmark::inertia_term(v, a, dt);
                if self.is_damped() {
                    let predicted = (1.0 - DELTA / BETA) * v + dt * (1.0 - DELTA / (2.0 * BETA)) * a;
                    term -= a0 * predicted;
                    self.predicted_velocity.push(predicted);
                }
                inertia.push(term);
            }
        }
        inertia
    }

    /// Subtracts the stiffness-proportional damping force `a1 K (δ/(βΔt) Δu + v̂)` from `loads`
    /// (extended with zero loads for nodes that a fracture added within the step).
    pub(super) fn add_stiffness_damping(&self, loads: &mut Vec<f64>, du: &[f64], dt: f64) {
        loads.resize(loads.len().max(self.nodes.len() * NODE_DOFS), 0.0);
        let a1 = self.damping.1;
        if a1 == 0.0 {
            return;
        }
        let rate = DELTA / (BETA * dt);
        for (e, s) in self.elements.iter().zip(self.stresses.current()) {
            let k = tangent_stiffness(e, s, &self.sections[e.section]);
            let mut v = [0.0; ELEMENT_DOFS];
            for (end, &node) in e.nodes.iter().enumerate() {
                for c in 0..NODE_DOFS {
                    let g = node * NODE_DOFS + c;
                    v[end * NODE_DOFS + c] = rate * du[g] + self.predicted_velocity[g];
                }
            }
            for (end, &node) in e.nodes.iter().enumerate() {
                for c in 0..NODE_DOFS {
                    let row = &k[end * NODE_DOFS + c];
                    let f: f64 = row.iter().zip(&v).map(|(kij, vj)| kij * vj).sum();
                    loads[node * NODE_DOFS + c] -= a1 * f;
                }
            }
        }
    }
}
