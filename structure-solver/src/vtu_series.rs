//! [`VtuSeries`]: frame snapshots `frame-NNNNN.vtu` (written by the frame) and the ParaView
//! collection `frame.pvd` that lists them with their times.

use crate::frame::Frame;
use schemas::pvd::Collection;
use std::io;
use std::path::{Path, PathBuf};

/// Snapshots written so far.
pub struct VtuSeries {
    dir: PathBuf,
    collection: Collection,
}

impl VtuSeries {
    pub fn new(dir: &Path) -> Self {
        Self {
            dir: dir.to_path_buf(),
            collection: Collection::new(dir.join("frame.pvd")),
        }
    }

    /// Continues a series in `dir` whose first `frames` (time, file) were written before a
    /// checkpoint; the `.pvd` is rewritten to list them.
    pub fn resumed(dir: &Path, frames: Vec<(f64, String)>) -> io::Result<Self> {
        Ok(Self {
            dir: dir.to_path_buf(),
            collection: Collection::resumed(dir.join("frame.pvd"), frames)?,
        })
    }

    /// Time and file of each snapshot written so far.
    pub fn frames(&self) -> &[(f64, String)] {
        self.collection.frames()
    }

    /// Writes the frame at time `t` and rewrites the `.pvd` so that it is valid after every call.
    pub fn write(&mut self, frame: &Frame, t: f64) -> io::Result<()> {
        let name = format!("frame-{:05}.vtu", self.collection.len());
        frame.write_vtu(&self.dir.join(&name))?;
        self.collection.add(t, &name)
    }
}
