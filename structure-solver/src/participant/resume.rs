//! Checkpoints of a structure participant and the run resumed from one: the [`Structure`] (point
//! masses, springs, rigid bodies with their supports, the frame with its fractured topology,
//! hinges and Newmark history, clock; `frame/checkpoint.rs`), the geometry version sent and where
//! each output stands, so that the resumed run writes the same rows, events and snapshots as a run
//! that never stopped. Writing a checkpoint drops the frame's factorisation (a resumed run starts
//! without one), so that both runs do the same arithmetic from there.

use super::StructureParticipant;
use crate::output::{Output, OutputState};
use crate::structure::Structure;
use schemas::case::Case;
use schemas::participant::ProgressSink;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Everything a structure participant's checkpoint holds.
#[derive(Serialize, Deserialize)]
struct Saved {
    /// The participant's name (a checkpoint of another participant is refused).
    name: String,
    structure: Structure,
    geometry_sent: Option<u64>,
    /// Where the outputs stand (`None` without an output folder).
    output: Option<OutputState>,
    /// Whether the state has its history row (a run resumed at its end writes one at `Finish`
    /// when it has not).
    row_now: bool,
}

impl StructureParticipant {
    /// Writes the history rows kept back from the accepted window, then the state to `path`.
    pub(super) fn checkpoint_to(
        &mut self,
        path: &Path,
        progress: &mut dyn ProgressSink,
    ) -> Result<u64, String> {
        self.commit()?;
        // the resumed run starts without the frame's factorisation: so does this one from here
        self.structure
            .drop_caches()
            .map_err(|e| format!("structure `{}`: {e}", self.name))?;
        let saved = Saved {
            name: self.name.clone(),
            structure: self.structure.clone(),
            geometry_sent: self.geometry_sent,
            output: self.output.as_ref().map(Output::state),
            row_now: self.row_now,
        };
        schemas::checkpoint::write(path, &saved, progress).map_err(|e| {
            format!(
                "structure `{}`: cannot write the checkpoint {}: {e}",
                self.name,
                path.display()
            )
        })
    }

    /// Participant `name` of `case` continued from the checkpoint `from`; with `out`, it appends to
    /// the history files there (cut back by the coupler to their length at the checkpoint).
    pub fn resume(case: &Case, name: &str, out: Option<&Path>, from: &Path) -> Result<Self, String> {
        let saved: Saved = schemas::checkpoint::read(from)?;
        if saved.name != name {
            return Err(format!(
                "{} is the checkpoint of structure `{}`, not of `{name}`",
                from.display(),
                saved.name
            ));
        }
        let mut p = StructureParticipant::from_case(case, name, None)?;
        let cfg = case
            .structure
            .get(name)
            .ok_or_else(|| format!("{}: there is no [structure.{name}] section", case.path.display()))?;
        p.structure = saved.structure;
        p.geometry_sent = saved.geometry_sent;
        p.row_now = saved.row_now;
        if let Some(dir) = out {
            let state = saved.output.unwrap_or_default();
            p.output = Some(Output::resume(dir, cfg, &p.structure, &state)?);
            p.history = cfg.history.as_ref().map(|h| h.interval);
        }
        eprintln!(
            "structure `{name}`: resumed from {} at t = {} s",
            from.display(),
            p.structure.time()
        );
        Ok(p)
    }
}
