//! ASI-Gauss framed structures (S2 §3, docs/physics.md §5): members of two linear Timoshenko elements with
//! one integration point each, plastic hinges by the full-plastic yield function, fracture by S2-17,
//! co-rotational (updated-Lagrangian) large displacements and rotations, Newmark β = 4/9, δ = 5/6 with
//! lumped mass and rotary inertia and one linear solve per step (S2-14), the member mid nodes
//! condensed out of the effective matrix exactly, sparse Cholesky (faer) of the rest with the symbolic
//! factorisation kept until the connectivity changes and the numeric one kept while the effective
//! matrix has not changed much (members whose hinges changed are re-condensed and solved with it as
//! a preconditioner), and penalty contact through particles along the members.
//!
//! Node order: the config's nodes in config order, then one mid node per member in member order,
//! then nodes made by fracture. Loads, velocities and displacements have 6 entries per node
//! (x, y, z, rx, ry, rz; global axes).

pub mod assembly;
pub mod checkpoint;
pub mod condensation;
pub mod condensed_system;
pub mod contact;
pub mod damping;
pub mod element;
pub mod energy;
pub mod energy_check;
pub mod equilibrium;
pub mod factor_age;
pub mod fracture;
pub mod global_system;
pub mod hinge;
pub mod hinge_events;
pub mod kept_state;
pub mod newmark;
pub mod preconditioned_cg;
pub mod section;
pub mod section_forces;
pub mod stepping;
pub mod stress_states;
pub mod supernodal_solve;
pub mod topology;
pub mod vtu;
pub mod yield_function;

/// Fewest elements or nodes per rayon task in the per-step passes: a step's passes take well
/// under a millisecond at 10⁴ DOFs, and finer tasks cost more in scheduling than they save
/// (measured: a fifth of a step's time went to rayon's wake-ups and yields).
pub(crate) const PARALLEL_CHUNK: usize = 256;

pub use energy::EnergyRow;
pub use equilibrium::MAX_CORRECTIONS;
pub use global_system::DenseMatrices;
pub use stepping::Equilibrium;

use assembly::NODE_DOFS;
use condensed_system::CondensedSystem;
use factor_age::FactorAge;
use fracture::FractureCriterion;
use global_system::NodalForces;
use nalgebra::Vector3;
use schemas::case::frame::FrameConfig;
use schemas::case::FieldError;
use section::Section;
use std::collections::BTreeMap;
use stress_states::StressStates;
use topology::{Element, Node};

/// An ASI-Gauss frame and its state; a clone is a checkpoint, and so is its serde form (without
/// its caches, `checkpoint.rs`).
#[derive(Clone, serde::Serialize, serde::Deserialize)]
#[serde(into = "checkpoint::FrameFile", try_from = "checkpoint::FrameFile")]
pub struct Frame {
    time_step: f64,
    gravity: Vector3<f64>,
    density: f64,
    sections: Vec<Section>,
    fracture: Option<FractureCriterion>,
    contact: Option<contact::Contact>,
    nodes: Vec<Node>,
    elements: Vec<Element>,
    /// The elements' stress states (`stress_states.rs`), element `i`'s at `i`.
    stresses: StressStates,
    ids: BTreeMap<u32, usize>,
    system: CondensedSystem,
    connectivity: u64,
    factorizations: u64,
    /// Factorisations that assembled their values anew (the others reused the kept ones).
    assemblies: u64,
    cg_iterations: u64,
    unconverged: u64,
    /// Steps taken, and the largest unbalanced force one left (as a share of its first one).
    steps: u64,
    worst_unbalance: f64,
    /// Which of the last [`stepping::PERSISTENCE_WINDOW`] steps were unconverged (bit 0: the last).
    recent_unconverged: u32,
    /// The step (counted from 1) that began the first persistent stretch of unconverged steps (see
    /// [`stepping::PERSISTENT_UNCONVERGED`]).
    persistent_from: Option<u64>,
    equilibrium: Equilibrium,
    /// η of the refactorisation criterion (`factor_age.rs`).
    stale_limit: f64,
    factor_age: FactorAge,
    /// Internal forces and masses at the end of the last step, for the next one's right-hand side.
    end_of_step_forces: Option<NodalForces>,
    /// Unbalanced force left by the last step over its first one.
    unbalance: f64,
    /// Steps taken back and cut into parts because they left too much of their unbalanced force.
    cut_steps: u64,
    /// The state of the nodes and elements to go back to: before the increment of a one-solve step
    /// that may be taken back ([`Frame::take_back`]), at the start of an iterated step.
    kept: kept_state::KeptState,
    /// Time since the frame was built: the sum of its steps [s].
    elapsed: f64,
    /// Hinge events, when recorded (`hinge_events.rs`).
    events: Option<Vec<hinge_events::HingeEvent>>,
    /// Rayleigh damping coefficients `(a0, a1)` of `C = a0 M + a1 K` (`damping.rs`).
    damping: (f64, f64),
    /// The predicted part of the step's end velocity, `(1 − δ/β) v + Δt (1 − δ/(2β)) a`, 6 per
    /// node, while the frame is damped.
    predicted_velocity: Vec<f64>,
    /// The energy account, when kept (`energy.rs`).
    energy: Option<energy::EnergyAccount>,
    /// Which ends of each element are free, held by no other element and no support
    /// (`fracture.rs`); made again when a fracture changes the connectivity.
    free_ends: Vec<[bool; 2]>,
}

impl Frame {
    /// Builds a frame from its validated config; `key` is the table's path for error messages.
    pub fn from_config(cfg: &FrameConfig, key: &str) -> Result<Frame, FieldError> {
        let topology::Topology {
            nodes,
            elements,
            stresses,
            ids,
        } = topology::build(cfg, key)?;
        let sections: Vec<Section> = cfg
            .section
            .iter()
            .map(|s| Section::new(s, &cfg.material))
            .collect();
        let contact = match &cfg.contact {
            Some(c) => {
                let limit = contact::Contact::stiffness_limit(
                    &elements,
                    &sections,
                    cfg.material.density,
                    cfg.time_step,
                );
                if c.stiffness > limit {
                    return Err(FieldError::new(
                        format!("{key}.contact.stiffness"),
                        format!(
                            "{} N/m is too stiff for time_step = {} s (contact forces are explicit): must be \
                             ≤ {limit:.4e} N/m (the lightest contact particle's mass / Δt²)",
                            c.stiffness, cfg.time_step
                        ),
                    ));
                }
                Some(contact::Contact::new(c, &cfg.wall))
            }
            None => None,
        };
        let system = condensed_system_of(&nodes, &elements).map_err(|m| FieldError::new(key, m))?;
        let free_ends = fracture::free_ends(&nodes, &elements);
        Ok(Frame {
            time_step: cfg.time_step,
            gravity: Vector3::from(cfg.gravity),
            density: cfg.material.density,
            sections,
            fracture: FractureCriterion::new(&cfg.material),
            contact,
            nodes,
            elements,
            stresses: StressStates::new(stresses),
            ids,
            system,
            connectivity: 0,
            factorizations: 0,
            assemblies: 0,
            cg_iterations: 0,
            unconverged: 0,
            steps: 0,
            worst_unbalance: 0.0,
            recent_unconverged: 0,
            persistent_from: None,
            equilibrium: match cfg.equilibrium_tolerance {
                Some(tolerance) => Equilibrium::Iterate { tolerance },
                None => Equilibrium::OneSolve,
            },
            stale_limit: factor_age::DEFAULT_STALE_LIMIT,
            factor_age: FactorAge::default(),
            end_of_step_forces: None,
            unbalance: 0.0,
            cut_steps: 0,
            kept: Default::default(),
            elapsed: 0.0,
            events: None,
            damping: match &cfg.damping {
                Some(d) => d.coefficients(&format!("{key}.damping"))?,
                None => (0.0, 0.0),
            },
            predicted_velocity: Vec::new(),
            energy: None,
            free_ends,
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
            for (k, vk) in v.iter().enumerate() {
                n.velocity[k] = if n.fixed[k] { 0.0 } else { *vk };
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
            .zip(self.stresses.current())
            .filter_map(|(e, s)| s.hinge.map(|end| e.nodes[end.node()]))
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

    /// Number of numeric factorisations of the effective matrix so far.
    pub fn factorization_count(&self) -> u64 {
        self.factorizations
    }

    /// Number of those factorisations that assembled the effective matrix anew; the others
    /// factorised the kept values with the members whose hinges changed re-condensed
    /// (`factor_age.rs`).
    pub fn assembly_count(&self) -> u64 {
        self.assemblies
    }

    /// Number of products with the effective matrix in conjugate-gradient solves so far (solves after
    /// hinges formed or closed, preconditioned by the kept factor; see `preconditioned_cg.rs`).
    pub fn cg_iteration_count(&self) -> u64 {
        self.cg_iterations
    }

    /// Number of steps whose corrections did not reach the residual tolerance (with
    /// [`Equilibrium::Iterate`]), or that left more than [`stepping::ONE_SOLVE_UNBALANCE_LIMIT`] of
    /// their unbalanced force (one solve per step: Δt is then too long for the method).
    pub fn unconverged_steps(&self) -> u64 {
        self.unconverged
    }

    /// Steps taken back and done again in [`stepping::CUT_PARTS`] parts because they left more than
    /// [`stepping::CUT_TRIGGER`] times their first unbalanced force (hinges changed within them).
    pub fn cut_step_count(&self) -> u64 {
        self.cut_steps
    }

    /// Unbalanced force left at the end of the last step, as a share of the one at its start.
    pub fn last_unbalance(&self) -> f64 {
        self.unbalance
    }

    /// What a user should know about the accuracy of the steps taken so far. One solve per step:
    /// `None` unless unconverged steps became persistent (isolated ones, where hinges form or a
    /// mechanism runs away, are the one-solve scheme working as designed: their unbalanced force
    /// carries into the next step), otherwise how many there were, from when, and what to change in
    /// the case. Iterated steps: every step that kept an unconverged iterate (`equilibrium.rs`).
    pub fn accuracy_warning(&self) -> Option<String> {
        let (steps, worst) = (self.steps, self.worst_unbalance);
        match self.equilibrium {
            Equilibrium::OneSolve => {
                let from = self.persistent_from?;
                Some(format!(
                    "{} of {steps} frame steps left more than {:.0} % of their unbalanced force ({} or more of \
                     every {} from step {from} on; worst {worst:.2}): time_step is too long for one solve per \
                     step, and hinges may form where they should not; halve time_step or set \
                     equilibrium_tolerance",
                    self.unconverged,
                    100.0 * stepping::ONE_SOLVE_UNBALANCE_LIMIT,
                    stepping::PERSISTENT_UNCONVERGED,
                    stepping::PERSISTENCE_WINDOW
                ))
            }
            Equilibrium::Iterate { tolerance } => (self.unconverged > 0).then(|| {
                format!(
                    "{} of {steps} frame steps did not reach equilibrium_tolerance = {tolerance} within {} \
                     corrections and carried the unbalanced force left (worst {worst:.2e} of their first) into \
                     the next step; halve time_step",
                    self.unconverged, MAX_CORRECTIONS
                )
            }),
        }
    }

    /// How steps treat the unbalanced force; [`Equilibrium::OneSolve`] (ASI-Gauss) by default.
    pub fn equilibrium(&self) -> Equilibrium {
        self.equilibrium
    }

    /// Chooses how steps treat the unbalanced force; a tolerance must be finite and in (0, 1).
    pub fn set_equilibrium(&mut self, equilibrium: Equilibrium) -> Result<(), String> {
        if let Equilibrium::Iterate { tolerance } = equilibrium {
            if !(tolerance > 0.0 && tolerance < 1.0) {
                return Err(format!(
                    "frame: the equilibrium tolerance must be a share of the first unbalanced force in (0, 1), \
                     got {tolerance}"
                ));
            }
        }
        self.equilibrium = equilibrium;
        Ok(())
    }

    /// Sets η of the refactorisation criterion (`factor_age.rs`, default
    /// [`factor_age::DEFAULT_STALE_LIMIT`]): how far the kept effective matrix may drift from the
    /// current one, as a share of the mass term; 0 refactorises every step. Must be finite and ≥ 0.
    pub fn set_stale_limit(&mut self, limit: f64) -> Result<(), String> {
        if !(limit.is_finite() && limit >= 0.0) {
            return Err(format!(
                "frame: the stale-matrix limit must be a finite number ≥ 0, got {limit}"
            ));
        }
        self.stale_limit = limit;
        Ok(())
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
}

/// The condensed effective system of these nodes and elements (mid and fracture nodes, which have no
/// config id, are condensed first).
fn condensed_system_of(nodes: &[Node], elements: &[Element]) -> Result<CondensedSystem, String> {
    let fixed: Vec<_> = nodes.iter().map(|n| n.fixed).collect();
    let loose: Vec<_> = nodes.iter().map(|n| n.id.is_none()).collect();
    let pairs: Vec<_> = elements.iter().map(|e| e.nodes).collect();
    CondensedSystem::new(&fixed, &loose, &pairs)
}
