//! Where a fluid's frames go: a VTU of the particles per frame and their PVD series, and the
//! free-surface mesh of each frame with its own series (`surface_mesh = true`).

use super::vtp::SurfaceFrames;
use super::vtu;
use crate::particles::Particles;
use schemas::participant::ProgressSink;
use schemas::pvd::Collection;
use std::io;
use std::path::PathBuf;

/// The frame files of fluid `name` in `dir`.
pub struct FrameFiles {
    dir: PathBuf,
    name: String,
    series: Collection,
    surfaces: Option<SurfaceFrames>,
}

/// The (time, file) lists of a fluid's frame series and of its surface meshes' series, as a
/// checkpoint keeps them.
pub type SeriesLists = (Vec<(f64, String)>, Option<Vec<(f64, String)>>);

impl FrameFiles {
    /// Frames of fluid `name` into `dir`, with surface meshes at `spacing` [m] when `surfaces`.
    pub fn new(dir: PathBuf, name: &str, spacing: f64, surfaces: bool) -> FrameFiles {
        FrameFiles {
            series: Collection::new(dir.join(format!("{name}.pvd"))),
            surfaces: surfaces.then(|| SurfaceFrames::new(&dir, name, spacing)),
            name: name.to_string(),
            dir,
        }
    }

    /// Frames that continue the series `lists` of a resumed run (their `.pvd` files rewritten to
    /// list them); an error names the file or folder that could not be written.
    pub fn resumed(
        dir: PathBuf,
        name: &str,
        spacing: f64,
        lists: SeriesLists,
    ) -> Result<FrameFiles, (PathBuf, io::Error)> {
        let (series, surfaces) = lists;
        let pvd = dir.join(format!("{name}.pvd"));
        Ok(FrameFiles {
            series: Collection::resumed(pvd.clone(), series).map_err(|e| (pvd, e))?,
            surfaces: surfaces
                .map(|s| SurfaceFrames::resumed(&dir, name, spacing, s))
                .transpose()
                .map_err(|e| (dir.clone(), e))?,
            name: name.to_string(),
            dir,
        })
    }

    /// The series' lists so far, for a checkpoint.
    pub fn series_lists(&self) -> SeriesLists {
        (
            self.series.frames().to_vec(),
            self.surfaces.as_ref().map(|s| s.series().frames().to_vec()),
        )
    }

    /// Frame `k` of the particles `p` at `time`: its VTU, its surface mesh, then its series
    /// entry (so the series names only whole frames).
    pub fn write(
        &mut self,
        k: u64,
        time: f64,
        p: &Particles,
        progress: &mut dyn ProgressSink,
    ) -> Result<(), String> {
        let file = format!("{}_{k:05}.vtu", self.name);
        let path = self.dir.join(&file);
        vtu::write_vtu(&path, p, progress).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        if let Some(s) = &mut self.surfaces {
            s.write(k, time, p, progress)
                .map_err(|(path, e)| format!("cannot write {}: {e}", path.display()))?;
        }
        self.series
            .add(time, &file)
            .map_err(|e| format!("cannot write the PVD in {}: {e}", self.dir.display()))
    }
}
