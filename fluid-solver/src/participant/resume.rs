//! Checkpoints of a fluid participant and the run resumed from one: the solver's whole state
//! ([`FluidState`] and [`RunState`]: particles, cell list, the method's own state, bodies, open
//! boundaries, clock and totals, the stability monitor's reference) and the output bookkeeping
//! (frames written and their series, probe rows written and the filters' readings), so that the
//! resumed run writes the same bytes as a run that never stopped.

use super::probe_rows::SavedProbes;
use super::{FluidParticipant, Frames, ProbeRows};
use crate::output::background::BackgroundWriter;
use crate::output::frame_files::FrameFiles;
use crate::sensors::probes::{ProbeFile, ProbeSet};
use crate::state::{FluidState, RunState};
use schemas::case::Case;
use schemas::f64s::F64s;
use schemas::participant::ProgressSink;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Everything a fluid participant's checkpoint holds.
#[derive(Serialize, Deserialize)]
struct Saved {
    /// The participant's name (a checkpoint of another participant is refused).
    name: String,
    state: FluidState,
    run: RunState,
    initial_momentum: [f64; 3],
    end_samples: Option<(f64, Vec<f64>, Vec<f64>)>,
    frames: Option<SavedFrames>,
    probes: Option<SavedProbes>,
}

/// The next frame's index, the frames' series (time, file) and the surface meshes' series.
#[derive(Serialize, Deserialize)]
struct SavedFrames {
    next: u64,
    series: Vec<(f64, String)>,
    surfaces: Option<Vec<(f64, String)>>,
}

impl FluidParticipant {
    /// Writes the rows and frame kept back from the accepted window, then the state to `path`,
    /// telling `progress` of the bytes written.
    pub(super) fn checkpoint_to(
        &mut self,
        path: &Path,
        progress: &mut dyn ProgressSink,
    ) -> Result<u64, String> {
        self.commit(progress)?;
        let frames = match &mut self.frames {
            Some(f) => {
                let next = f.next;
                let (series, surfaces) = f.files.wait(progress)?.series_lists();
                Some(SavedFrames {
                    next,
                    series,
                    surfaces,
                })
            }
            None => None,
        };
        self.solver.sync_host();
        let saved = Saved {
            name: self.name.clone(),
            state: self.solver.save_state(),
            run: self.solver.run_state(),
            initial_momentum: self.initial_momentum,
            end_samples: self
                .end_samples
                .as_ref()
                .map(|(t, v, l)| (*t, v.0.clone(), l.0.clone())),
            frames,
            probes: self.probes.as_ref().map(ProbeRows::saved),
        };
        schemas::checkpoint::write(path, &saved, progress).map_err(|e| {
            format!(
                "fluid `{}`: cannot write the checkpoint {}: {e}",
                self.name,
                path.display()
            )
        })
    }

    /// Participant `name` of `case` continued from the checkpoint `from`; with `out`, it appends to
    /// the output files there (cut back by the coupler to their length at the checkpoint).
    pub fn resume(case: &Case, name: &str, out: Option<&Path>, from: &Path) -> Result<Self, String> {
        let saved: Saved = schemas::checkpoint::read(from)?;
        if saved.name != name {
            return Err(format!(
                "{} is the checkpoint of fluid `{}`, not of `{name}`",
                from.display(),
                saved.name
            ));
        }
        let mut p = FluidParticipant::from_case(case, name, None)?;
        let cfg = case
            .fluid
            .get(name)
            .ok_or_else(|| format!("{}: there is no [fluid.{name}] section", case.path.display()))?;
        // Probes are placed on the initial layout (discs on the faces as built), as in `from_case`.
        let probe_set = match out {
            Some(_) if !cfg.probe.is_empty() => Some(
                ProbeSet::new(&cfg.probe, &p.solver)
                    .map_err(|e| format!("{}: fluid `{name}`: {e}", case.path.display()))?,
            ),
            _ => None,
        };
        p.solver.restore_state(&saved.state);
        p.solver.restore_run_state(saved.run);
        p.initial_momentum = saved.initial_momentum;
        p.end_samples = saved.end_samples.map(|(t, v, l)| (t, F64s(v), F64s(l)));
        let io = |path: &Path, e: std::io::Error| format!("cannot continue {}: {e}", path.display());
        if let (
            Some(dir),
            Some(SavedFrames {
                next,
                series,
                surfaces,
            }),
        ) = (out, saved.frames)
        {
            let files = FrameFiles::resumed(dir.to_path_buf(), name, cfg.spacing, (series, surfaces))
                .map_err(|(path, e)| io(&path, e))?;
            p.frames = Some(Frames {
                interval: cfg.output_interval,
                next,
                pending: None,
                pending_time: 0.0,
                files: BackgroundWriter::new(files),
            });
        }
        if let (Some(dir), Some(probes), Some(saved)) = (out, probe_set, saved.probes) {
            let path = dir.join(format!("{name}_probes.csv"));
            let interval = cfg.probe_interval.unwrap_or(cfg.output_interval);
            let file = ProbeFile::append(&path).map_err(|e| io(&path, e))?;
            let mut rows = ProbeRows::new(path, Some(file), probes, interval);
            rows.continue_from(saved);
            p.probes = Some(rows);
        }
        eprintln!(
            "fluid `{name}`: resumed from {} at t = {} s (step {})",
            from.display(),
            p.solver.time(),
            p.solver.steps()
        );
        Ok(p)
    }
}
