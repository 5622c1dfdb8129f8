//! Checkpoints of a structure participant and the run resumed from one: the [`Structure`] (point
//! masses, springs, rigid bodies with their supports, clock) and the geometry version sent, so
//! that the resumed run writes the same history rows as a run that never stopped. A structure
//! with a frame refuses to write a checkpoint (its factorisations and kept element states are not
//! written to files yet).

use super::StructureParticipant;
use crate::output::Output;
use crate::structure::Structure;
use schemas::case::Case;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Everything a structure participant's checkpoint holds.
#[derive(Serialize, Deserialize)]
struct Saved {
    /// The participant's name (a checkpoint of another participant is refused).
    name: String,
    structure: Structure,
    geometry_sent: Option<u64>,
}

impl StructureParticipant {
    /// Writes the history rows kept back from the accepted window, then the state to `path`.
    pub(super) fn checkpoint_to(&mut self, path: &Path) -> Result<u64, String> {
        if self.structure.frame().is_some() {
            return Err(format!(
                "structure `{}`: a structure with a frame cannot write checkpoints yet; remove \
                 coupling.checkpoint_interval from the case",
                self.name
            ));
        }
        self.commit()?;
        let saved = Saved {
            name: self.name.clone(),
            structure: self.structure.clone(),
            geometry_sent: self.geometry_sent,
        };
        schemas::checkpoint::write(path, &saved).map_err(|e| {
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
        if p.structure.frame().is_some() {
            return Err(format!(
                "structure `{name}`: a structure with a frame cannot resume from a checkpoint yet"
            ));
        }
        let cfg = case
            .structure
            .get(name)
            .ok_or_else(|| format!("{}: there is no [structure.{name}] section", case.path.display()))?;
        p.structure = saved.structure;
        p.geometry_sent = saved.geometry_sent;
        if let Some(dir) = out {
            p.output = Some(Output::resume(dir, cfg, &p.structure)?);
            p.history = cfg.history.as_ref().map(|h| (h.interval, case.info.end_time));
        }
        eprintln!(
            "structure `{name}`: resumed from {} at t = {} s",
            from.display(),
            p.structure.time()
        );
        Ok(p)
    }
}
