//! The frame's energy account (`energy.csv` of a structure run), kept while asked for
//! ([`Frame::record_energy`]). Notation for a step n → n+1: `[[x]] = x_{n+1} − x_n`,
//! `⟨x⟩ = (x_{n+1} + x_n)/2`; M the lumped mass with rotary inertia (global axes, at the state
//! where it is evaluated), u the node displacements and rotation increments (spatial), v and a the
//! Newmark velocities and accelerations (angular ones for rotations). Columns, all in J:
//!
//! - `kinetic` T = ½ vᵀ M v, at the current state.
//! - `strain` U = Σ_elements ½ l σᵀ D⁻¹ σ: the elastic strain energy of each element's section forces
//!   σ at its integration point (one-point rule of weight l, D the diagonal section stiffness).
//! - `plastic` D_p = Σ_steps Σ_hinges l ⟨σ⟩ · Δε_p with Δε_p = D⁻¹(σ_trial − σ) the plastic strain
//!   increment of the normality flow (`hinge.rs`); kept through fractures.
//! - `shift` S = Σ_elements the change of the element's U when ASI-Gauss moved its integration point
//!   (a hinge forming or closing in its member: the end forces stay, the one-point U does not),
//!   minus the strain energy a fracture released (the element's U, set to zero by the fracture:
//!   `fracture.rs`).
//! - `damping` D_d = Σ_steps [[u]]ᵀ C ⟨v⟩, C = a0 M + a1 K (tangent at the step's end).
//! - `algorithmic` D_alg = Σ_steps −Δt (γ − ½) ⟨v⟩ᵀ M [[a]] + Δt² (β − γ/2) [[½ aᵀ M a]]: the energy
//!   Newmark's β = 4/9, γ = 5/6 takes out. From `[[u]] = Δt⟨v⟩ + Δt²(β − γ/2)[[a]]` and
//!   `[[v]] = Δt⟨a⟩ + Δt(γ − ½)[[a]]` and `M a = f − R − C v` at both ends of a step,
//!   `[[T]] = [[u]]ᵀ⟨f⟩ − [[u]]ᵀ⟨R⟩ − [[u]]ᵀ⟨C v⟩ − D_alg` exactly (M held constant over the step).
//! - `external` W = Σ_steps [[u]]ᵀ ⟨f⟩ + Σ_nodes m g · [[x]], f the applied node loads (interface
//!   and contact forces included), the weights' work exact (m and g constant over a step). A node
//!   a fracture made had no load at the step's start (f_n = 0 there; its weight counts whole). The
//!   first step after recording starts takes for f_n the load that balances the state then,
//!   `M a + R + a0 M v − m g`.
//! - `residual` W − (ΔT + ΔU − S + D_p + D_d + D_alg), Δ from when recording started. Every term above
//!   is computed on its own, so the residual measures what the solver does not balance: the
//!   internal work `[[u]]ᵀ⟨R⟩` against ΔU + D_p (the co-rotational forces are not the exact
//!   gradient of U, the trapezoid of a plastic step, moves of an integration point when a hinge
//!   forms), the unbalanced force a one-solve step carries into the next, and the change of the
//!   spatial rotary inertia over a step.
//!
//! A fracture does no work (positions and velocities do not jump; the split node's mass and
//! momentum are shared by its pieces, so T does not jump either): it releases the fractured
//! element's U, booked in S. It also changes the forces on the nodes at once, which the step after
//! it must start from (`fracture.rs` makes their accelerations satisfy `M a = f − R − C v` again):
//! from the old accelerations, that step's ⟨M a⟩ missed ½ ΔF, and the account showed ½ [[u]]ᵀ ΔF
//! as lost: 3.9 J after a 132.9 J release at Δt = 1e-4 s, 2.1e-6 J from balanced accelerations
//! (`tests/frame_fracture.rs`, `docs/notes/frame-energy-at-fracture.md`).
//!
//! Measured (`tests/frame_energy.rs`): a cantilever's elastic free vibration at Δt = T1/100 leaves
//! a residual of 8e-12 of its initial energy over 5 periods with first-order elements
//! (`geometry = "linear"`: every term exact), and with co-rotational ones one that grows by
//! 3.5e-9 of it per step, iterated or not (their forces are not the exact gradient of U); a
//! fixed–fixed beam's plastic collapse ends at 3.5e-4 of the external work.
//!
//! Cost: nothing while not recorded; while recorded, one pass over the nodes and one over the
//! elements (their rotary inertia) per step, and a tangent stiffness per element per step when
//! the frame has stiffness-proportional damping. Plastic work is summed at hinges in every step
//! (a few products per hinged element, `hinge.rs`).

use super::assembly::NODE_DOFS;
use super::element::ELEMENT_DOFS;
use super::global_system::{end_mass, tangent_stiffness};
use super::newmark::{BETA, DELTA};
use super::Frame;
use nalgebra::{Matrix3, Vector3};

/// Running sums of the energy account.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub(super) struct EnergyAccount {
    /// f_n: the applied loads (without the weights) of the last step, 6 per node; nodes a fracture
    /// made since have none (`None`: the balancing load, worked out at the first step).
    previous_loads: Option<Vec<f64>>,
    external: f64,
    damping: f64,
    algorithmic: f64,
    /// T, U, D_p and S when recording started.
    start: [f64; 4],
    /// Set at the first step whose balance is lost (`energy_check.rs`).
    warning: Option<String>,
}

impl EnergyAccount {
    /// Whether the next step is the first one recorded (it needs R at its start).
    pub(super) fn starting(&self) -> bool {
        self.previous_loads.is_none()
    }
}

/// One row of the energy account [J] (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnergyRow {
    pub kinetic: f64,
    pub strain: f64,
    pub plastic: f64,
    pub shift: f64,
    pub damping: f64,
    pub algorithmic: f64,
    pub external: f64,
    pub residual: f64,
}

/// Velocities and accelerations of each node before a step.
pub(super) type Motion = Vec<([f64; NODE_DOFS], [f64; NODE_DOFS])>;

impl Frame {
    /// Starts (or stops) keeping the energy account; it starts from the current state.
    pub fn record_energy(&mut self, on: bool) {
        self.energy = on.then(|| EnergyAccount {
            previous_loads: None,
            external: 0.0,
            damping: 0.0,
            algorithmic: 0.0,
            start: [
                self.kinetic_energy(),
                self.strain_energy(),
                self.plastic_dissipation(),
                self.shift_energy(),
            ],
            warning: None,
        });
    }

    /// The energy account at the current state, when recorded.
    pub fn energy(&self) -> Option<EnergyRow> {
        let acc = self.energy.as_ref()?;
        let (kinetic, strain, plastic) = (
            self.kinetic_energy(),
            self.strain_energy(),
            self.plastic_dissipation(),
        );
        let plastic = plastic - acc.start[2];
        let shift = self.shift_energy() - acc.start[3];
        let residual = acc.external
            - (kinetic - acc.start[0] + strain - acc.start[1] - shift
                + plastic
                + acc.damping
                + acc.algorithmic);
        Some(EnergyRow {
            kinetic,
            strain,
            plastic,
            shift,
            damping: acc.damping,
            algorithmic: acc.algorithmic,
            external: acc.external,
            residual,
        })
    }

    /// Why the energy balance of the steps taken so far is lost (`energy_check.rs`): set at the
    /// first step whose balance residual exceeded [`super::energy_check::ENERGY_WARNING_SHARE`] of
    /// the run's energy scale, with the time, the residual, the scale and what to change; `None`
    /// while it holds or while the account is not kept.
    pub fn energy_warning(&self) -> Option<&str> {
        self.energy.as_ref()?.warning.as_deref()
    }

    pub(super) fn set_energy_warning(&mut self, warning: String) {
        if let Some(acc) = self.energy.as_mut() {
            acc.warning = Some(warning);
        }
    }

    /// T + U when recording started (0 while not recorded).
    pub(super) fn energy_start_mechanical(&self) -> f64 {
        self.energy
            .as_ref()
            .map_or(0.0, |acc| acc.start[0] + acc.start[1])
    }

    /// Kinetic energy ½ vᵀ M v [J].
    pub fn kinetic_energy(&self) -> f64 {
        let (m, j) = self.lumped_inertia();
        self.nodes
            .iter()
            .enumerate()
            .map(|(i, n)| 0.5 * quadratic(m[i], &j[i], &n.velocity, &n.velocity))
            .sum()
    }

    /// Elastic strain energy of the elements' section forces [J].
    pub fn strain_energy(&self) -> f64 {
        self.elements
            .iter()
            .zip(self.stresses.current())
            .map(|(e, s)| s.strain_energy(&self.sections[e.section], e.length0))
            .sum()
    }

    /// Plastic work dissipated at hinges so far [J].
    pub fn plastic_dissipation(&self) -> f64 {
        self.stresses.current().iter().map(|s| s.dissipated).sum()
    }

    /// Change of the strain energy made by moving integration points so far [J].
    pub fn shift_energy(&self) -> f64 {
        self.stresses.current().iter().map(|s| s.shifted).sum()
    }

    /// Lumped translational mass and rotary inertia (global axes) of each node at the current state.
    fn lumped_inertia(&self) -> (Vec<f64>, Vec<Matrix3<f64>>) {
        let mut mass = vec![0.0; self.nodes.len()];
        let mut rotary = vec![Matrix3::zeros(); self.nodes.len()];
        for e in &self.elements {
            let (m, j) = end_mass(e, &self.sections[e.section], self.density);
            for &v in &e.nodes {
                mass[v] += m;
                rotary[v] += j;
            }
        }
        (mass, rotary)
    }

    /// The part `M a + a0 M v − m g` of the load that balances the state `before` at the start of
    /// the first recorded step (R is added by the caller).
    fn balancing_force(&self, before: &Motion, mass: &[f64], rotary: &[Matrix3<f64>]) -> Vec<f64> {
        let mut f = vec![0.0; self.nodes.len() * NODE_DOFS];
        for (i, (v, a)) in before.iter().enumerate() {
            let fv = &mut f[i * NODE_DOFS..(i + 1) * NODE_DOFS];
            let mut rate = *a;
            for k in 0..NODE_DOFS {
                rate[k] += self.damping.0 * v[k];
            }
            for k in 0..3 {
                fv[k] += mass[i] * (rate[k] - self.gravity[k]);
                fv[3 + k] += (0..3).map(|l| rotary[i][(k, l)] * rate[3 + l]).sum::<f64>();
            }
        }
        f
    }

    /// Adds the step just taken (`dt`, increment `du`, `loads` with contact forces, node motion
    /// `before` it) to the account; `internal_before`: R at the start of the step (first step only).
    pub(super) fn account_step(
        &mut self,
        dt: f64,
        loads: &[f64],
        du: &[f64],
        before: &Motion,
        internal_before: Option<&[[f64; NODE_DOFS]]>,
    ) {
        let Some(acc) = self.energy.as_ref() else {
            return;
        };
        let (mass, rotary) = self.lumped_inertia();
        let previous = match &acc.previous_loads {
            // a node a fracture made since has no load before (nodes are only ever appended)
            Some(f) => f.clone(),
            None => {
                let mut f = self.balancing_force(before, &mass, &rotary);
                if let Some(r) = internal_before {
                    for (fv, rv) in f.chunks_exact_mut(NODE_DOFS).zip(r) {
                        for k in 0..NODE_DOFS {
                            fv[k] += rv[k];
                        }
                    }
                }
                f
            }
        };
        let (a0, a1) = self.damping;
        let (mut external, mut mass_damping, mut algorithmic) = (0.0, 0.0, 0.0);
        let mut mean_velocity = vec![0.0; du.len()];
        for (i, n) in self.nodes.iter().enumerate() {
            let (v0, acc0) = before
                .get(i)
                .copied()
                .unwrap_or(([0.0; NODE_DOFS], [0.0; NODE_DOFS]));
            let g = i * NODE_DOFS;
            let mut vm = [0.0; NODE_DOFS];
            let mut da = [0.0; NODE_DOFS];
            let load = |f: &[f64], k: usize| f.get(g + k).copied().unwrap_or(0.0);
            for k in 0..NODE_DOFS {
                external += du[g + k] * 0.5 * (load(&previous, k) + load(loads, k));
                if k < 3 {
                    external += du[g + k] * mass[i] * self.gravity[k];
                }
                vm[k] = 0.5 * (v0[k] + n.velocity[k]);
                da[k] = n.acceleration[k] - acc0[k];
                mean_velocity[g + k] = vm[k];
            }
            let (m, j) = (mass[i], &rotary[i]);
            let du_node: [f64; NODE_DOFS] = du[g..g + NODE_DOFS].try_into().unwrap_or([0.0; NODE_DOFS]);
            mass_damping += a0 * quadratic(m, j, &du_node, &vm);
            algorithmic += -dt * (DELTA - 0.5) * quadratic(m, j, &vm, &da)
                + dt * dt
                    * (BETA - 0.5 * DELTA)
                    * 0.5
                    * (quadratic(m, j, &n.acceleration, &n.acceleration) - quadratic(m, j, &acc0, &acc0));
        }
        let mut stiffness_damping = 0.0;
        if a1 != 0.0 {
            for (e, s) in self.elements.iter().zip(self.stresses.current()) {
                let k = tangent_stiffness(e, s, &self.sections[e.section]);
                let (mut x, mut y) = ([0.0; ELEMENT_DOFS], [0.0; ELEMENT_DOFS]);
                for (end, &node) in e.nodes.iter().enumerate() {
                    for c in 0..NODE_DOFS {
                        x[end * NODE_DOFS + c] = du[node * NODE_DOFS + c];
                        y[end * NODE_DOFS + c] = mean_velocity[node * NODE_DOFS + c];
                    }
                }
                stiffness_damping += k
                    .iter()
                    .zip(&x)
                    .map(|(row, xi)| xi * row.iter().zip(&y).map(|(kij, yj)| kij * yj).sum::<f64>())
                    .sum::<f64>();
            }
        }
        if let Some(acc) = self.energy.as_mut() {
            acc.external += external;
            acc.damping += mass_damping + a1 * stiffness_damping;
            acc.algorithmic += algorithmic;
            acc.previous_loads = Some(loads.to_vec());
        }
    }
}

/// `xᵀ diag(m, m, m, J) y` for one node.
fn quadratic(m: f64, j: &Matrix3<f64>, x: &[f64; NODE_DOFS], y: &[f64; NODE_DOFS]) -> f64 {
    let (xw, yw) = (Vector3::new(x[3], x[4], x[5]), Vector3::new(y[3], y[4], y[5]));
    m * (x[0] * y[0] + x[1] * y[1] + x[2] * y[2]) + xw.dot(&(j * yw))
}
