//! One Newmark step of a frame (S2-14): the increment is solved with the kept factor of the effective
//! matrix (or, after hinges formed or closed, with the members they changed re-condensed and the kept
//! factor as preconditioner) and the state is brought to the end of the step in co-rotational form. As
//! in ASI-Gauss (docs/physics.md §5) there is one linear solve per step and the unbalanced force carries
//! into the next one; equilibrium corrections within the step are an option ([`Equilibrium::Iterate`]).

use super::assembly::NODE_DOFS;
use super::condensation::Block;
use super::element::ELEMENT_DOFS;
use super::energy;
use super::factor_age::{Staleness, CG_PRODUCTS_LIMIT};
use super::global_system::{end_mass, mass_block, tangent_stiffness, Contribution, Motion, NodalForces};
use super::hinge::StressState;
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
/// Largest node rotation [rad] of a first-order (`geometry = "linear"`) element: its rotations are
/// the rotation vectors of the node orientations, which wrap at π.
const MAX_LINEAR_ROTATION: f64 = 3.0;

/// Share of its first unbalanced force above which a one-solve step counts in
/// [`Frame::unconverged_steps`]: a sign that Δt is too long for one solve per step. Measured on the
/// benchmark's 3 × 3 × 3 building with hinges forming: at Δt = 1 ms steps left up to 1.3 and the run
/// ended with 130 hinge nodes against 32 with equilibrium iterations; at 0.5 ms and 0.25 ms they left
/// at most 0.018 and 0.004 and both ended with 32.
pub const ONE_SOLVE_UNBALANCE_LIMIT: f64 = 0.1;

/// Multiple of the unbalanced force that the round-off of the node positions alone makes
/// (ε · max |x| · max EA/L per element end) below which a step counts as converged whatever the
/// tolerance: a tolerance of 1e-8 on a 1 kN step load of a 3 m beam of 0.15 m elements asks for
/// 1e-5 N, where one ulp of a coordinate (6.7e-16 m) in one element's EA/L (2e10 N/m) is already
/// 1.3e-5 N; summed over the nodes' residuals the norm is up to ~√n times that.
pub(super) const ROUND_OFF_MULTIPLE: f64 = 100.0;

/// Share of the applied loads (with the weights, as a norm) below which the unbalanced force a
/// one-solve step leaves does not count in [`Frame::unconverged_steps`] whatever its ratio to the first one: a
/// converged static hold starts its steps from an unbalanced force at round-off, and its ratio
/// means nothing (a cantilever held under 1 kN counted 299 of 400 hold steps, ratios up to 2.4).
pub const ONE_SOLVE_LOAD_FLOOR: f64 = 1e-6;

/// Ratio of the unbalanced force a one-solve step leaves to its first one above which the step is
/// taken back and done again in [`CUT_PARTS`] parts: hinges that formed within a step at Δt ≳ T1/4
/// leave 7–16 times the first (a portal frame under a beam load and a sideways push,
/// `tests/frame_one_solve_step.rs`), and two such steps in a row blew it up at 0.02 s. The
/// benchmark's collapsing buildings leave at most 3.1 (3 × 3 × 3 at 1 ms) and are never cut.
pub const CUT_TRIGGER: f64 = 5.0;

/// Parts a step that left more than [`CUT_TRIGGER`] is done again in.
pub const CUT_PARTS: usize = 4;

/// Times a step is cut at most (its shortest parts: Δt / 4³).
pub const MAX_CUT_DEPTH: u32 = 3;

/// Steps looked back over to tell persistent unconverged steps from isolated ones.
pub const PERSISTENCE_WINDOW: u32 = 20;

/// Unconverged steps among the last [`PERSISTENCE_WINDOW`] from which they count as persistent, which
/// [`Frame::accuracy_warning`] reports. Measured: the benchmark's 3 × 3 × 3 building collapsing at
/// Δt = 1 ms has 19–20 of every 20 from its 47th step on; the fixed–fixed beam of the plastic-collapse
/// test, loaded past its collapse load at Δt = 3.8e-4 s, has 15 of 2 000, all after collapse, at most 6
/// within 20 steps.
pub const PERSISTENT_UNCONVERGED: u32 = 10;

/// What a step does with the unbalanced force its linear solve leaves.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
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
        self.step_or_cut(dt, loads, 0)
    }

    /// [`Frame::step`] at cut depth `depth`: a one-solve step that leaves more than [`CUT_TRIGGER`]
    /// times the unbalanced force it began with (hinges changed within it) is taken back and done
    /// again in [`CUT_PARTS`] parts, each of them cut again the same way, down to
    /// [`MAX_CUT_DEPTH`].
    fn step_or_cut(&mut self, dt: f64, loads: &[f64], depth: u32) -> Result<(), String> {
        let may_cut = self.equilibrium == Equilibrium::OneSolve && depth < MAX_CUT_DEPTH;
        if self.step_once(dt, loads, may_cut)? {
            return Ok(());
        }
        self.cut_steps += 1;
        let part = dt / CUT_PARTS as f64;
        for _ in 0..CUT_PARTS {
            self.step_or_cut(part, loads, depth + 1)?;
        }
        Ok(())
    }

    /// Puts the nodes and elements back where the last increment found them (a one-solve step that
    /// has not been finished: velocities, accelerations and counters untouched).
    fn take_back(&mut self) {
        self.kept
            .restore(&mut self.nodes, &mut self.elements, &mut self.stresses);
        self.end_of_step_forces = None;
    }

    /// [`Frame::step`] without the cut; with `may_cut`, a one-solve step that leaves more than
    /// [`CUT_TRIGGER`] times its first unbalanced force is taken back (returns false).
    fn step_once(&mut self, dt: f64, loads: &[f64], may_cut: bool) -> Result<bool, String> {
        let with_contact: Vec<f64>;
        let loads = match &self.contact {
            Some(c) => {
                let f = c.forces(&self.nodes, &self.elements, &self.sections, self.density);
                with_contact = loads.iter().zip(&f).map(|(a, b)| a + b).collect();
                &with_contact
            }
            None => loads,
        };
        let inertia = self.inertia_with_damping(dt);
        let staleness = self.factor_age.staleness(
            &self.elements,
            self.stresses.current(),
            &self.sections,
            self.density,
            dt,
            self.stale_limit,
        );
        match staleness {
            Staleness::Reassemble => self.system.drop_values(),
            Staleness::Refactor => self.system.drop_factor(),
            Staleness::Fresh => {}
        }
        let unconverged = self.unconverged;
        let hinges_before = self.hinges_if_recording();
        let motion_before: Option<energy::Motion> = self
            .energy
            .as_ref()
            .map(|_| self.nodes.iter().map(|n| (n.velocity, n.acceleration)).collect());
        let internal_before = match &self.energy {
            Some(acc) if acc.starting() => Some(self.gather(&self.contributions()).internal),
            _ => None,
        };
        let du = match self.equilibrium {
            Equilibrium::OneSolve => self.solve_once(dt, loads, &inertia, may_cut)?,
            Equilibrium::Iterate { tolerance } => {
                self.solve_to_equilibrium(dt, loads, &inertia, tolerance)?
            }
        };
        if may_cut && self.unbalance > CUT_TRIGGER {
            self.take_back();
            self.unconverged = unconverged;
            return Ok(false);
        }
        for (node, du) in self.nodes.iter_mut().zip(du.chunks_exact(NODE_DOFS)) {
            for (k, duk) in du.iter().enumerate() {
                (node.velocity[k], node.acceleration[k]) = if node.fixed[k] {
                    (0.0, 0.0)
                } else {
                    newmark::advance(*duk, node.velocity[k], node.acceleration[k], dt)
                };
            }
        }
        if let Some(before) = &motion_before {
            self.account_step(dt, loads, &du, before, internal_before.as_deref());
        }
        self.elapsed += dt;
        if motion_before.is_some() {
            self.check_energy_balance(dt);
        }
        if let Some(before) = &hinges_before {
            self.record_hinge_changes(before);
        }
        self.update_integration_points();
        self.split_fractured(loads)?;
        self.check_stability(dt)?;
        self.steps += 1;
        self.worst_unbalance = self.worst_unbalance.max(self.unbalance);
        let window = (1u32 << PERSISTENCE_WINDOW) - 1;
        self.recent_unconverged =
            ((self.recent_unconverged << 1) | u32::from(self.unconverged > unconverged)) & window;
        if self.recent_unconverged.count_ones() >= PERSISTENT_UNCONVERGED {
            // the oldest unconverged step in the window
            let age = u64::from(31 - self.recent_unconverged.leading_zeros());
            self.persistent_from.get_or_insert(self.steps - age);
        }
        Ok(true)
    }

    /// ASI's one solve: the increment from the unbalanced force at the start of the step, the state
    /// moved by it, and the internal forces there kept for the next step; with `keep`, the state
    /// before the increment is kept for [`Frame::take_back`]. Returns the increment.
    fn solve_once(
        &mut self,
        dt: f64,
        loads: &[f64],
        inertia: &[f64],
        keep: bool,
    ) -> Result<Vec<f64>, String> {
        let mass_factor = self.effective_mass_factor(dt);
        let (nodal, contributions) = match self.end_of_step_forces.take() {
            Some(nodal) if self.system.has_values_for(dt) => (nodal, None),
            _ => {
                let contributions = self.contributions();
                (self.gather(&contributions), Some(contributions))
            }
        };
        if !self.system.has_factor_for(dt) {
            self.refactor(contributions.as_deref(), dt, mass_factor)?;
        }
        let zero = vec![0.0; self.nodes.len() * NODE_DOFS];
        let mut du = self.residual(&nodal, loads, inertia, &zero, mass_factor, dt);
        let first = norm(&du);
        self.solve_with_current_tangent(&mut du, dt, mass_factor, 0.0)?;
        check_finite(&du)?;
        if keep {
            self.apply_increment_keeping(&du);
        } else {
            self.apply_increment(&du);
        }
        let contributions = self.update_elements_with_forces();
        let nodal = self.gather(&contributions);
        let last = norm(&self.residual(&nodal, loads, inertia, &du, mass_factor, dt));
        self.end_of_step_forces = Some(nodal);
        self.unbalance = if first > 0.0 { last / first } else { 0.0 };
        // the floor is only worked out for the rare steps above the limit
        if self.unbalance > ONE_SOLVE_UNBALANCE_LIMIT && last > self.unbalance_floor(loads) {
            self.unconverged += 1;
        }
        Ok(du)
    }

    /// The unbalanced force below which a one-solve step counts as accurate whatever its ratio to the
    /// first one: [`ONE_SOLVE_LOAD_FLOOR`] of the applied loads with the weights, or the round-off
    /// of the positions ([`Frame::round_off_unbalance`]) if larger.
    fn unbalance_floor(&self, loads: &[f64]) -> f64 {
        let masses = self.node_masses();
        let applied = loads
            .chunks_exact(NODE_DOFS)
            .zip(&masses)
            .map(|(f, m)| {
                let mut force = [0.0; NODE_DOFS];
                for (k, fk) in force.iter_mut().enumerate() {
                    *fk = f[k] + if k < 3 { m * self.gravity[k] } else { 0.0 };
                }
                force.iter().map(|x| x * x).sum::<f64>()
            })
            .sum::<f64>()
            .sqrt();
        (ONE_SOLVE_LOAD_FLOOR * applied).max(self.round_off_unbalance())
    }

    /// The unbalanced force that the round-off of the node positions makes, times
    /// [`ROUND_OFF_MULTIPLE`]: ε · max |x| · max EA/L0 over the elements.
    pub(super) fn round_off_unbalance(&self) -> f64 {
        let extent = self.nodes.iter().fold(0.0_f64, |m, n| m.max(n.position.amax()));
        let axial = self.elements.iter().fold(0.0_f64, |m, e| {
            m.max(self.sections[e.section].stiffness[0] / e.length0)
        });
        ROUND_OFF_MULTIPLE * f64::EPSILON * extent * axial
    }

    /// Solves the effective system in place (`x`: the right-hand side, then the increment) with the
    /// current tangent of every element whose hinge or integration point changed since its matrix was
    /// made: those members are re-condensed and the system is solved by conjugate gradients with the
    /// kept factor as preconditioner; when they do not converge within [`CG_PRODUCTS_LIMIT`]
    /// products, those values are factorised and the system solved directly. Conjugate gradients stop
    /// at the relative tolerance or at a residual of `enough` (0: the relative tolerance alone).
    pub(super) fn solve_with_current_tangent(
        &mut self,
        x: &mut [f64],
        dt: f64,
        mass_factor: f64,
        enough: f64,
    ) -> Result<(), String> {
        self.recondense_changed(dt, mass_factor)?;
        let rhs = x.to_vec();
        let outcome = self.system.solve(x, CG_PRODUCTS_LIMIT, enough)?;
        self.cg_iterations += outcome.iterations as u64;
        self.factor_age.add_cg_products(outcome.iterations);
        if !outcome.converged {
            self.refactor(None, dt, mass_factor)?;
            x.copy_from_slice(&rhs);
            self.system.solve(x, 0, 0.0)?;
        }
        Ok(())
    }

    /// Re-condenses the members with an element whose hinge or integration point changed since its
    /// matrix was made, at the current state.
    fn recondense_changed(&mut self, dt: f64, mass_factor: f64) -> Result<(), String> {
        let scale = self.stiffness_factor(dt);
        let changed = self.factor_age.changed_tangents(self.stresses.current());
        if changed.is_empty() {
            return Ok(());
        }
        let elements = self.system.with_partners(&changed);
        let (matrices, end_blocks): (Vec<_>, Vec<_>) = elements
            .iter()
            .map(|&e| {
                let (element, section) = (&self.elements[e], &self.sections[self.elements[e].section]);
                let (m, j) = end_mass(element, section, self.density);
                (
                    scaled(
                        tangent_stiffness(element, &self.stresses.current()[e], section),
                        scale,
                    ),
                    mass_block(mass_factor * m, &(j * mass_factor)),
                )
            })
            .unzip();
        self.system.update(&elements, &matrices, &end_blocks)?;
        self.factor_age
            .record_tangents(self.stresses.current(), &elements);
        Ok(())
    }

    /// Factorises `K + M/(βΔt²)`: the kept values with the members whose tangent changed
    /// re-condensed when they hold the mass term of `dt`, otherwise values assembled and condensed
    /// at the current state (the masses from `contributions` when given).
    pub(super) fn refactor(
        &mut self,
        contributions: Option<&[Contribution]>,
        dt: f64,
        mass_factor: f64,
    ) -> Result<(), String> {
        if self.system.has_values_for(dt) {
            self.recondense_changed(dt, mass_factor)?;
            self.factor_age.factorized();
        } else {
            let computed;
            let contributions = match contributions {
                Some(c) => c,
                None => {
                    computed = self.contributions();
                    &computed
                }
            };
            let node_blocks = self.node_blocks(contributions, mass_factor);
            let (elements, stresses, sections) = (&self.elements, self.stresses.current(), &self.sections);
            let scale = self.stiffness_factor(dt);
            let unscaled =
                |e: usize| tangent_stiffness(&elements[e], &stresses[e], &sections[elements[e].section]);
            let scaled_by = |e: usize| scaled(unscaled(e), scale);
            // without damping, each block goes straight to the assembly (no copy on the way)
            let stiffness: &(dyn Fn(usize) -> Block + Sync) =
                if scale == 1.0 { &unscaled } else { &scaled_by };
            self.system.assemble(stiffness, &node_blocks)?;
            self.factor_age.record(&self.elements, self.stresses.current());
            self.assemblies += 1;
        }
        self.factorizations += 1;
        self.system.factorize(dt)
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
        dt: f64,
    ) -> Vec<f64> {
        let motion = Motion {
            inertia,
            increment: du,
            mass_factor,
        };
        if self.damping.1 == 0.0 {
            return self.unbalanced_force(nodal, loads, Some(motion));
        }
        let mut damped = loads.to_vec();
        self.add_stiffness_damping(&mut damped, du, dt);
        self.unbalanced_force(nodal, &damped, Some(motion))
    }

    /// Moves the nodes by `du`; rotations compose as `exp(Δθ) R` (updated Lagrangian: Δθ is spatial).
    /// On one thread: about 15 ns per node, and rayon's tasks took longer than the work (measured on
    /// the benchmark's 7 × 7 × 7 grid: 0.15 ms per step in rayon tasks, 0.03 ms on one thread).
    pub(super) fn apply_increment(&mut self, du: &[f64]) {
        for (node, du) in self.nodes.iter_mut().zip(du.chunks_exact(NODE_DOFS)) {
            move_node(node, du);
        }
    }

    /// [`Frame::apply_increment`], keeping each node's position and rotation before it for
    /// [`Frame::take_back`] in the same pass (a separate pass read every node twice), and where the
    /// elements' stress states stand.
    fn apply_increment_keeping(&mut self, du: &[f64]) {
        let kept = self.kept.keep_for_increment(&self.stresses, self.nodes.len());
        for ((node, du), kept) in self.nodes.iter_mut().zip(du.chunks_exact(NODE_DOFS)).zip(kept) {
            *kept = (node.position, node.rotation);
            move_node(node, du);
        }
    }

    /// New co-rotational frames, natural deformation increments and resultants of every element
    /// (the stress states before them stay in their other array, `stress_states.rs`).
    pub(super) fn update_elements(&mut self) {
        let (nodes, sections, free) = (&self.nodes, &self.sections, &self.free_ends);
        let (before, after) = self.stresses.to_update();
        self.elements
            .par_iter_mut()
            .zip(before)
            .zip(after)
            .zip(free)
            .with_min_len(PARALLEL_CHUNK)
            .for_each(|(((e, before), after), &free)| {
                update_element(e, before, after, nodes, sections, free)
            });
        self.stresses.updated();
    }

    /// [`Frame::update_elements`] and, in the same pass, the elements' contributions at the new
    /// state without stiffness.
    fn update_elements_with_forces(&mut self) -> Vec<Contribution> {
        let (nodes, sections, density) = (&self.nodes, &self.sections, self.density);
        let free = &self.free_ends;
        let (before, after) = self.stresses.to_update();
        let contributions = self
            .elements
            .par_iter_mut()
            .zip(before)
            .zip(after)
            .zip(free)
            .with_min_len(PARALLEL_CHUNK)
            .map(|(((e, before), after), &free)| {
                update_element(e, before, after, nodes, sections, free);
                Contribution::of(e, after, &sections[e.section], density)
            })
            .collect();
        self.stresses.updated();
        contributions
    }

    /// Puts each elastic element's integration point where ASI-Gauss wants it given its member's hinges
    /// (a few comparisons per member: on one thread, cheaper than rayon's tasks).
    pub(super) fn update_integration_points(&mut self) {
        let sections = &self.sections;
        let stresses = self.stresses.current_mut().chunks_exact_mut(2);
        for (member, stress) in self.elements.chunks_exact(2).zip(stresses) {
            let hinged = [stress[0].hinge.is_some(), stress[1].hinge.is_some()];
            for (half, (e, stress)) in member.iter().zip(stress.iter_mut()).enumerate() {
                if !hinged[half] {
                    let s = e.elastic_integration_point(hinged[1 - half]);
                    stress.move_to(&sections[e.section], e.length0, s);
                }
            }
        }
    }

    /// Stops a run whose elements stretch or twist beyond what the formulation can represent.
    /// `dt`: the step just taken, for the diagnostic.
    fn check_stability(&self, dt: f64) -> Result<(), String> {
        for (i, e) in self.elements.iter().enumerate() {
            let strain = e.current.length / e.length0 - 1.0;
            let rotation = e.current.deformation[3..6]
                .iter()
                .chain(&e.current.deformation[9..12])
                .fold(0.0_f64, |m, x| m.max(x.abs()));
            let bad_values = !(strain.is_finite() && rotation.is_finite());
            let rotation_limit = if e.linear {
                MAX_LINEAR_ROTATION
            } else {
                MAX_RELATIVE_ROTATION
            };
            if bad_values || strain.abs() > MAX_AXIAL_STRAIN || rotation > rotation_limit {
                let advice = if self.equilibrium == Equilibrium::OneSolve
                    && self.unbalance > ONE_SOLVE_UNBALANCE_LIMIT
                {
                    format!(
                        "step {} (Δt = {dt} s) left {:.2} of its unbalanced force: one solve per step has lost \
                         its accuracy; use time_step ≤ {:.3e} s or set equilibrium_tolerance",
                        self.steps + 1,
                        self.unbalance,
                        0.5 * dt
                    )
                } else {
                    "reduce the time step or the loads".to_string()
                };
                return Err(format!(
                    "frame: element {i} (member {}) has axial strain {strain:.3} and end rotation {rotation:.3} rad \
                     relative to its chord (limits {MAX_AXIAL_STRAIN} and {rotation_limit} rad): the run is \
                     unstable; {advice}",
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

/// Moves `node` by its 6 entries of an increment: the translation, and the rotation composed as
/// `exp(Δθ) R`.
#[inline(always)]
fn move_node(node: &mut Node, du: &[f64]) {
    node.position += Vector3::new(du[0], du[1], du[2]);
    let spin = UnitQuaternion::from_scaled_axis(Vector3::new(du[3], du[4], du[5]));
    node.rotation = spin * node.rotation;
    node.rotation.renormalize_fast();
}

/// Brings element `e` to the current node positions and rotations: its co-rotational frame, natural
/// deformation increment, and into `after` its stress state `before` advanced by that increment.
fn update_element(
    e: &mut Element,
    before: &StressState,
    after: &mut StressState,
    nodes: &[Node],
    sections: &[Section],
    free: [bool; 2],
) {
    let now = e.kinematics(nodes);
    let mut dd = [0.0; ELEMENT_DOFS];
    for (i, d) in dd.iter_mut().enumerate() {
        *d = now.deformation[i] - e.current.deformation[i];
    }
    after.update_from(before, &sections[e.section], e.length0, &dd, free);
    e.current = now;
}

/// `k` times `scale` (unchanged when `scale` is 1: no stiffness-proportional damping).
fn scaled(mut k: Block, scale: f64) -> Block {
    if scale != 1.0 {
        k.iter_mut().flatten().for_each(|x| *x *= scale);
    }
    k
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
