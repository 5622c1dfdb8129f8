//! Hinge events: a plastic hinge forming or closing and a fracture, with the time, where, the
//! section forces at the hinge and the value of the yield function (or of S2-17's left side for a
//! fracture). Recorded only when asked for ([`Frame::record_hinge_events`]): the comparison of every
//! element's hinge before and after a step then costs one pass over the elements.

use super::hinge::End;
use super::section::Resultants;
use super::section_forces::end_forces;
use super::Frame;

/// What happened at a hinge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum HingeEventKind {
    Forming,
    Closing,
    Fracture,
}

impl HingeEventKind {
    pub fn name(self) -> &'static str {
        match self {
            HingeEventKind::Forming => "forming",
            HingeEventKind::Closing => "closing",
            HingeEventKind::Fracture => "fracture",
        }
    }
}

/// One hinge event.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct HingeEvent {
    /// Time since the frame was built [s] (the sum of its steps).
    pub time: f64,
    pub element: usize,
    pub member: usize,
    /// The node the hinge sits on.
    pub node: usize,
    pub kind: HingeEventKind,
    /// `[N, Vy, Vz, T, My, Mz]` at the hinge's end of the element, after the step.
    pub forces: Resultants,
    /// The yield function there (0 on the surface; < 0 for a hinge that closed), or S2-17's left
    /// side (≥ 1) for a fracture.
    pub function: f64,
}

impl Frame {
    /// Starts (or stops) recording hinge events; recording starts empty.
    pub fn record_hinge_events(&mut self, on: bool) {
        self.events = on.then(Vec::new);
    }

    /// The hinge events recorded so far, in the order they happened.
    pub fn hinge_events(&self) -> &[HingeEvent] {
        self.events.as_deref().unwrap_or(&[])
    }

    /// The elements' hinges, when events are recorded (before a step).
    pub(super) fn hinges_if_recording(&self) -> Option<Vec<Option<End>>> {
        self.events
            .as_ref()
            .map(|_| self.stresses.current().iter().map(|s| s.hinge).collect())
    }

    /// Records the hinges that formed or closed since `before` (the hinges before the step).
    pub(super) fn record_hinge_changes(&mut self, before: &[Option<End>]) {
        let Some(events) = &mut self.events else {
            return;
        };
        let now = self.elements.iter().zip(self.stresses.current());
        for (i, ((e, stress), was)) in now.zip(before).enumerate() {
            let (kind, end) = match (was, stress.hinge) {
                (None, Some(end)) => (HingeEventKind::Forming, end),
                (Some(end), None) => (HingeEventKind::Closing, *end),
                _ => continue,
            };
            let forces = end_forces(e, stress)[end.node()];
            let section = &self.sections[e.section];
            events.push(HingeEvent {
                time: self.elapsed,
                element: i,
                member: e.member,
                node: e.nodes[end.node()],
                kind,
                forces,
                function: section.yield_function(forces[0], forces[4], forces[5]),
            });
        }
    }
}
