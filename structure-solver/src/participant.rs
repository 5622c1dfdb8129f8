//! [`StructureParticipant`]: a [`Structure`] taking part in a coupled run through
//! [`schemas::participant::serve`]. Inputs: `point_force` (3/point), `body_force` (6/body),
//! `node_force` (6/node), read at any time by the window's interpolation and added to the case's
//! prescribed loads. Outputs: `point_displacement`, `point_velocity`, `body_pose`,
//! `body_velocity`, `node_position`, `node_velocity` at every exchange time of the window.
//!
//! With an output folder, the case's histories (and frame snapshots) are written as in standalone
//! mode, at the first exchange time at or after each history time (the stepping is never changed
//! for output), and at the end of the run; the rows of a window are kept back until the window is
//! accepted (the next advance comes without a restore, or the run finishes), so an implicit
//! iteration that is repeated never writes twice. The end's row, when the end is not a history
//! time, is written at `Finish`, after any checkpoint taken at the end: a run extended from that
//! checkpoint (`coupler run --resume OUT --end-time T`) has only the rows a run to T would have.

mod resume;

use crate::frame::Frame;
use crate::load_schedule::LoadSchedule;
use crate::output::Output;
use crate::structure::Structure;
use schemas::case::Case;
use schemas::f64s::F64s;
use schemas::message::{Fields, Geometry, InterfaceDecl, Role, Waveform};
use schemas::participant::{DiscardProgress, Participant, ProgressSink};
use std::path::Path;

/// A window may start this far (relative to max(1, t)) from the time the structure is at.
const TIME_MATCH: f64 = 1e-9;

/// One structure participant of a case, with its checkpoint.
pub struct StructureParticipant {
    name: String,
    structure: Structure,
    schedule: LoadSchedule,
    /// The state at the window start and the geometry version sent by then.
    checkpoint: Option<(Structure, Option<u64>)>,
    /// Frame connectivity version last sent as geometry.
    geometry_sent: Option<u64>,
    output: Option<Output>,
    /// History interval [s].
    history: Option<f64>,
    /// Whether the state the structure is at has its history row (written or kept back); at
    /// `Finish` one is written when it has not.
    row_now: bool,
    /// States of the last window due for a history row, written once the window is accepted.
    pending: Vec<Structure>,
}

impl StructureParticipant {
    /// Builds participant `name` of `case` at t = 0; with `out`, writes its output there.
    pub fn from_case(case: &Case, name: &str, out: Option<&Path>) -> Result<Self, String> {
        let cfg = case.structure.get(name).ok_or_else(|| {
            let names: Vec<&String> = case.structure.keys().collect();
            format!(
                "{}: there is no [structure.{name}] section; structure participants: {names:?}",
                case.path.display()
            )
        })?;
        let key = format!("structure.{name}");
        let at_key = |e: schemas::case::FieldError| schemas::case::CaseError::at(&case.path, e).to_string();
        let mut structure = Structure::from_config(cfg, &key).map_err(at_key)?;
        if out.is_some() {
            structure.record_hinge_events();
            if cfg.history.is_some() {
                structure.record_energy();
            }
        }
        let schedule = LoadSchedule::from_config(cfg, &key, &case.dir(), &structure).map_err(at_key)?;
        let mut output = out.map(|dir| Output::create(dir, cfg, &structure)).transpose()?;
        if let Some(o) = &mut output {
            o.record(&structure)?;
        }
        let history = cfg
            .history
            .as_ref()
            .filter(|_| output.is_some())
            .map(|h| h.interval);
        Ok(Self {
            name: name.to_string(),
            structure,
            schedule,
            checkpoint: None,
            geometry_sent: None,
            output,
            history,
            row_now: true,
            pending: Vec::new(),
        })
    }

    /// Writes the kept-back history states: their window was accepted.
    fn commit(&mut self) -> Result<(), String> {
        if let Some(o) = &mut self.output {
            for s in self.pending.drain(..) {
                o.record(&s)?;
            }
        }
        Ok(())
    }

    /// Which exchange times of a window (after its start) get a history row: the first one at or
    /// after each history time k·interval (within round-off). The stepping is never changed for
    /// output, so a run with an output folder answers exactly as one without.
    fn history_rows(&self, times: &[f64]) -> Vec<bool> {
        let Some(interval) = self.history else {
            return vec![false; times.len().saturating_sub(1)];
        };
        let start = times.first().copied().unwrap_or(0.0);
        let due = |k: f64| k * interval - 1e-9 * interval;
        let mut k = (start / interval + 1e-9).floor() + 1.0;
        times
            .iter()
            .skip(1)
            .map(|&t| {
                let row = t >= due(k);
                while t >= due(k) {
                    k += 1.0;
                }
                row
            })
            .collect()
    }

    /// The structure as it is now.
    pub fn structure(&self) -> &Structure {
        &self.structure
    }

    /// The interface outputs of the current state.
    pub fn outputs(&self) -> Fields {
        let s = &self.structure;
        Fields {
            point_displacement: F64s(s.point_displacement()),
            point_velocity: F64s(s.point_velocity()),
            body_pose: F64s(s.body_pose()),
            body_velocity: F64s(s.body_velocity()),
            node_position: F64s(s.node_position()),
            node_velocity: F64s(s.node_velocity()),
            ..Fields::default()
        }
    }
}

impl Participant for StructureParticipant {
    fn role(&self) -> Role {
        Role::Structure
    }

    fn time(&self) -> f64 {
        self.structure.time()
    }

    fn interface(&self) -> InterfaceDecl {
        let s = &self.structure;
        InterfaceDecl {
            points: s.points().iter().map(|p| p.name.clone()).collect(),
            bodies: s.bodies().iter().map(|b| b.name.clone()).collect(),
            frame_nodes: u32::try_from(s.frame_node_count()).unwrap_or(u32::MAX),
        }
    }

    fn initial_outputs(&mut self) -> Fields {
        self.outputs()
    }

    fn geometry_update(&mut self) -> Option<Geometry> {
        let frame = self.structure.frame()?;
        let version = frame.connectivity_version();
        if self.geometry_sent == Some(version) {
            return None;
        }
        self.geometry_sent = Some(version);
        let member_nodes = frame
            .element_nodes()
            .iter()
            .flat_map(|[a, b]| [*a, *b])
            .map(|n| u32::try_from(n).unwrap_or(u32::MAX))
            .collect();
        Some(Geometry {
            member_nodes,
            member_width: F64s(frame.element_widths()),
            member_area: F64s(frame.element_areas()),
        })
    }

    fn save_checkpoint(&mut self) {
        self.checkpoint = Some((self.structure.clone(), self.geometry_sent));
    }

    fn restore_checkpoint(&mut self) -> Result<(), String> {
        self.pending.clear();
        let saved = self.checkpoint.as_ref().ok_or_else(|| {
            format!(
                "structure `{}`: asked to restore a checkpoint, but none was saved",
                self.name
            )
        })?;
        self.structure = saved.0.clone();
        self.geometry_sent = saved.1;
        Ok(())
    }

    fn advance(&mut self, inputs: &Waveform) -> Result<Vec<Fields>, String> {
        self.advance_reporting(inputs, &mut DiscardProgress)
    }

    fn advance_reporting(
        &mut self,
        inputs: &Waveform,
        progress: &mut dyn ProgressSink,
    ) -> Result<Vec<Fields>, String> {
        let now = self.structure.time();
        let start = inputs.start();
        if (start - now).abs() > TIME_MATCH * now.abs().max(1.0) {
            return Err(format!(
                "structure `{}`: the window starts at t = {start} s but the structure is at t = {now} s",
                self.name
            ));
        }
        self.commit()?;
        let rows = self.history_rows(&inputs.times);
        self.row_now = rows.last().copied().unwrap_or(self.row_now);
        let mut outputs = vec![self.outputs()];
        for (&t, row) in inputs.times.iter().skip(1).zip(rows) {
            let schedule = &self.schedule;
            let loads = |tt: f64| {
                let mut l = schedule.at(tt);
                l.add_fields(&inputs.at(tt)?)?;
                Ok(l)
            };
            let warned = self.structure.frame().and_then(Frame::energy_warning).is_some();
            self.structure
                .advance_reporting(t, &loads, progress)
                .map_err(|e| format!("structure `{}`: {e}", self.name))?;
            if let (false, Some(w)) = (warned, self.structure.frame().and_then(Frame::energy_warning)) {
                eprintln!("warning: structure.{}.frame: {w}", self.name);
            }
            outputs.push(self.outputs());
            if row {
                self.pending.push(self.structure.clone());
            }
        }
        Ok(outputs)
    }

    fn write_checkpoint(&mut self, path: &Path, progress: &mut dyn ProgressSink) -> Result<u64, String> {
        self.checkpoint_to(path, progress)
    }

    /// Writes the last histories and tables: a few rows, written at once (`progress` hears
    /// nothing; the frame's and bodies' histories are small next to a fluid's frames).
    fn finish(&mut self, _progress: &mut dyn ProgressSink) -> Result<(), String> {
        self.commit()?;
        // the end of the run, when it is not a history time
        if let (Some(_), false, Some(o)) = (self.history, self.row_now, &mut self.output) {
            o.record(&self.structure)?;
            self.row_now = true;
        }
        for (body, t) in self.structure.releases() {
            println!("{}: body `{body}` released at t = {t} s", self.name);
        }
        if let Some(f) = self.structure.frame() {
            for w in [f.accuracy_warning(), f.energy_warning().map(str::to_string)]
                .into_iter()
                .flatten()
            {
                eprintln!("warning: structure.{}.frame: {w}", self.name);
            }
        }
        match &mut self.output {
            Some(o) => o.finish(&self.structure),
            None => Ok(()),
        }
    }
}
