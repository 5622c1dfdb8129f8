//! A frame in a checkpoint file: its whole state — nodes (with the ones fracture made), elements with
//! their frames and fracture counts, their current stress states with the hinges, the Newmark
//! velocities and accelerations, contact, hinge events, the energy account, counters and the
//! accuracy record — without what it caches to go faster: the condensed system with its symbolic
//! and numeric factorisations, the factor's age, the internal forces kept from the last step, the
//! kept state's scratch copy, the stress states before the last update and which element ends are
//! free. Those are made again from the state: a frame read back has no factor, and its next step
//! assembles and factorises anew.
//!
//! So that a resumed run does exactly the arithmetic of one that never stopped, a run that writes
//! a checkpoint drops the same caches at that moment ([`Frame::drop_caches`]): both then continue
//! from the same state with no factor. (A run without checkpoints refactorises at other steps, so
//! its results differ from those by the refactorisation criterion's tolerance, `factor_age.rs`.)
//! The [`From`] and [`TryFrom`] below name every field of [`Frame`], so that a field added to it
//! does not compile until it is said to be state or cache.

use super::contact::Contact;
use super::energy::EnergyAccount;
use super::fracture::{free_ends, FractureCriterion};
use super::hinge::StressState;
use super::hinge_events::HingeEvent;
use super::section::Section;
use super::stepping::Equilibrium;
use super::stress_states::StressStates;
use super::topology::{Element, Node};
use super::{condensed_system_of, Frame};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The state of a [`Frame`] as a checkpoint file holds it (see the module doc).
#[derive(Clone, Serialize, Deserialize)]
pub struct FrameFile {
    time_step: f64,
    gravity: Vector3<f64>,
    density: f64,
    sections: Vec<Section>,
    fracture: Option<FractureCriterion>,
    contact: Option<Contact>,
    nodes: Vec<Node>,
    elements: Vec<Element>,
    /// The elements' current stress states (the ones before the last update are a cache).
    stresses: Vec<StressState>,
    ids: BTreeMap<u32, usize>,
    connectivity: u64,
    factorizations: u64,
    assemblies: u64,
    cg_iterations: u64,
    unconverged: u64,
    steps: u64,
    worst_unbalance: f64,
    recent_unconverged: u32,
    persistent_from: Option<u64>,
    equilibrium: Equilibrium,
    stale_limit: f64,
    unbalance: f64,
    cut_steps: u64,
    elapsed: f64,
    events: Option<Vec<HingeEvent>>,
    damping: (f64, f64),
    energy: Option<EnergyAccount>,
}

impl From<Frame> for FrameFile {
    fn from(f: Frame) -> FrameFile {
        let Frame {
            time_step,
            gravity,
            density,
            sections,
            fracture,
            contact,
            nodes,
            elements,
            stresses,
            ids,
            // caches, made again from the state
            system: _,
            factor_age: _,
            end_of_step_forces: _,
            kept: _,
            predicted_velocity: _,
            free_ends: _,
            connectivity,
            factorizations,
            assemblies,
            cg_iterations,
            unconverged,
            steps,
            worst_unbalance,
            recent_unconverged,
            persistent_from,
            equilibrium,
            stale_limit,
            unbalance,
            cut_steps,
            elapsed,
            events,
            damping,
            energy,
        } = f;
        FrameFile {
            time_step,
            gravity,
            density,
            sections,
            fracture,
            contact,
            nodes,
            elements,
            stresses: stresses.current().to_vec(),
            ids,
            connectivity,
            factorizations,
            assemblies,
            cg_iterations,
            unconverged,
            steps,
            worst_unbalance,
            recent_unconverged,
            persistent_from,
            equilibrium,
            stale_limit,
            unbalance,
            cut_steps,
            elapsed,
            events,
            damping,
            energy,
        }
    }
}

impl TryFrom<FrameFile> for Frame {
    type Error = String;

    /// The frame of a checkpoint, with its condensed system made anew and no factor.
    fn try_from(f: FrameFile) -> Result<Frame, String> {
        if f.stresses.len() != f.elements.len() {
            return Err(format!(
                "frame checkpoint: {} stress states for {} elements",
                f.stresses.len(),
                f.elements.len()
            ));
        }
        let system = condensed_system_of(&f.nodes, &f.elements)?;
        let free_ends = free_ends(&f.nodes, &f.elements);
        Ok(Frame {
            time_step: f.time_step,
            gravity: f.gravity,
            density: f.density,
            sections: f.sections,
            fracture: f.fracture,
            contact: f.contact,
            nodes: f.nodes,
            elements: f.elements,
            stresses: StressStates::new(f.stresses),
            ids: f.ids,
            system,
            factor_age: Default::default(),
            end_of_step_forces: None,
            kept: Default::default(),
            predicted_velocity: Vec::new(),
            connectivity: f.connectivity,
            factorizations: f.factorizations,
            assemblies: f.assemblies,
            cg_iterations: f.cg_iterations,
            unconverged: f.unconverged,
            steps: f.steps,
            worst_unbalance: f.worst_unbalance,
            recent_unconverged: f.recent_unconverged,
            persistent_from: f.persistent_from,
            equilibrium: f.equilibrium,
            stale_limit: f.stale_limit,
            unbalance: f.unbalance,
            cut_steps: f.cut_steps,
            elapsed: f.elapsed,
            events: f.events,
            damping: f.damping,
            energy: f.energy,
            free_ends,
        })
    }
}

impl Frame {
    /// Drops the caches a checkpoint file does not hold (see the module doc): the frame is then
    /// exactly the one read back from the checkpoint, and its next step assembles and factorises
    /// anew.
    pub fn drop_caches(&mut self) -> Result<(), String> {
        *self = Frame::try_from(FrameFile::from(self.clone()))?;
        Ok(())
    }
}
